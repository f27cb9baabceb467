#include "command_line.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include "core/config/quote.hpp"

namespace fatc::io {
namespace {

using Mode = Options::Mode;

// clang-format off
const std::vector<OptionDeclaration> kOptions = {
  {"--config", "FILE", "config.json: pocket geometry, safe and loading positions, feeds, timings",
   ""},
  {"--state", "FILE",
   "where the tool state is kept (default: with --ini, the INI's [FIXED_ATC_PROBE]STATE from "
   "the INI's folder, the file the component is given; else the config path with .state "
   "appended; --plan and --plot: the first-start map); never the config file itself. The "
   "status file for panels is FILE.status", ""},
  {"--ini", "FILE",
   "the machine's INI as LinuxCNC runs with it (its #INCLUDE lines expanded as the linuxcnc "
   "script does), read by LinuxCNC's own reader: soft limits, [FIXED_ATC_PROBE], "
   "velocities and accelerations, REMAP and SUBROUTINE_PATH", ""},
  {"--from", "A", "the tool in the spindle before the change (0: none)",
   "the tool in the spindle, 0 none"},
  {"--to", "B", "the tool M6 asks for (0: empty the spindle)", "the tool M6 asks for"},
  {"--spindle", "N",
   "--confirm, --operator clear-fault: the tool the spindle holds, as found (0: empty; "
   "--operator without it: LinuxCNC's tool)",
   "0: the spindle is empty"},
  {"--pocket", "yes|no",
   "--confirm, --operator clear-fault: whether the cut-off pocket holds its tool", ""},
  {"--into", "P", "--operator load:T: the pocket the tool goes into (0 or none: the changer "
   "chooses)", ""},
  {"--yes", "", "--operator: answer Continue at each prompt, as the operator would once the "
   "prompt's work is done (a script, a test)", ""},
  {"--timeout", "SECONDS",
   "--operator: stop waiting after this long (the request goes on: exit 5); without it the "
   "command waits for the end, as long as the operator takes", ""},
  {"--tool-table", "FILE",
   "--lint, --check, --plan, --teach: LinuxCNC's tool table (else the INI's [EMCIO]TOOL_TABLE)",
   ""},
  {"--subroutine-path", "DIR:DIR",
   "--lint: folders searched for subroutines before the INI's SUBROUTINE_PATH", ""},
  {"--at", "X,Y,Z", "--teach: the machine position (G53, config.json's units), three decimal "
   "numbers with commas between, as 120.5,80,-5 (a sign, a leading point as .5 and an exponent "
   "as 1e2 are read; hex, inf, nan, a decimal comma and anything else are refused)",
   "the machine position, G53"},
};

const std::vector<ModeDeclaration> kModes = {
  {Mode::component, "", "", {"--config"}, {"--state"}, "run as a HAL component (loadusr -W)",
   "the HAL component: loaded with loadusr -W, it answers iocontrol's tool handshake and the "
   "operator's pins. A bad config, a corrupt state file or no LinuxCNC to talk to ends it at "
   "once with one line per problem and exit status 1, before hal_ready, so loadusr -W never "
   "hangs"},
  {Mode::check, "--check", "", {"--config"}, {"--ini", "--state", "--tool-table"},
   "check config, state, INI and rack geometry",
   "check the config, the state file (--state or its default) and, with --ini, the machine INI "
   "(read by LinuxCNC's own reader: its soft limits and, when it has the section, "
   "[FIXED_ATC_PROBE]: every key there, the motion pin numbers two digits, three different "
   "analog outputs, STEP_TIMEOUT longer than the longest wait between steps the plans report; "
   "[EMCIO]TOOL_CHANGE_POSITION, TOOL_CHANGE_QUILL_UP and TOOL_CHANGE_AT_G30, which would move "
   "the machine after every change; an #INCLUDE that names no file or cannot be read), "
   "print the pockets and waypoints and check every sequence against the rack keep-out and the "
   "soft limits, each tool carried with its length in LinuxCNC's tool table (--tool-table, "
   "else [EMCIO]TOOL_TABLE; a Z of 0 or below counts as the longest tool the config allows), "
   "and say which tools of the table the rack cannot carry across its holders; one line for "
   "each problem in each file. When one input cannot be read or is "
   "not valid, its error line is followed only by how many sequences were still checked "
   "against the rack keep-out and, last, what was not checked (\"INI unreadable: soft limits "
   "not checked\"). Config, state and INI must be regular files of at most 1 MiB. Exit 0 "
   "valid, 1 invalid, 2 usage"},
  {Mode::plan, "--plan", "", {"--config", "--from", "--to"}, {"--ini", "--state", "--tool-table"},
   "print the steps of M6 TB with TA in the spindle",
   "print the steps of M6 TB with TA in the spindle (the tools where --state has them, else "
   "the first-start map, said so when --state names no file yet), then its estimated time on the config's path and on the other one "
   "(each move an exact stop, G61.1, at the --ini's velocities and axes' accelerations, as "
   "LinuxCNC plans it, else at assumed ones; the dwells; the executor's handshake a step and "
   "iocontrol's cycles a change) and, with --ini, the bound: the direct path's moves at the INI's velocities and "
   "accelerations, each an exact stop, plus the dwells (and the prototype path's time at the "
   "same limits), and how much of it may move while the spindle runs down "
   "(move_while_spindle_stops). Exit 0 printed, 1 refused or invalid, 2 usage"},
  {Mode::confirm, "--confirm", "", {"--config", "--spindle"}, {"--state", "--pocket"},
   "after a fault, LinuxCNC stopped: record what you found",
   "the recovery of a fault while LinuxCNC is not running: records in the state file that the "
   "spindle holds tool N (0: empty) and, when a sequence was cut off at a pocket, whether that "
   "pocket holds its tool, and clears the uncertainty, as clear-fault does in the running "
   "component. Answers that contradict the record (the cut-off pocket's own tool in the "
   "spindle and in its pocket; --pocket where no sequence was cut off at a pocket) are refused "
   "and nothing is written, as is a state file that is not there (a fault leaves one: a "
   "mistyped --state would get a new one while the real one stays uncertain). Nothing moves. "
   "Exit 0 written, 1 refused, 2 usage"},
  {Mode::lint, "--lint", "PROGRAM.ngc", {"--config"},
   {"--state", "--tool-table", "--ini", "--subroutine-path"},
   "read a G-code program without running it: its tool changes, problems, change time",
   "run a G-code program through LinuxCNC's own interpreter, the standalone rs274 "
   "(linuxcnc-uspace; on the PATH, or $FATC_RS274), not the machine: with --ini in the INI's "
   "folder with its REMAP lines, SUBROUTINE_PATH (the --subroutine-path folders first) and a "
   "copy of its PARAMETER_FILE, and with the tool table (--tool-table, else "
   "[EMCIO]TOOL_TABLE; without either tools 1 to 1000). Prints every M6 and M61 in the order "
   "LinuxCNC runs them with the tool's pocket, manual tools, lengths, what only the running "
   "machine knows (HAL pins, a tool read from an M66 input), the problems (each line whose "
   "motion would enter the rack with the tool then in the spindle among them), and the change "
   "time estimated as --plan estimates each change (the INI's limits with --ini, else assumed "
   "ones). rs274 is stopped after 15 s, 1 GiB of output or the error after 1000 (a "
   "problem); it is given at most 64 MiB of G-code. Exit 0 clean, 1 problems found, 2 usage, "
   "an input it cannot read "
   "(program, config, state, tool table, INI) or rs274 not installed"},
  {Mode::teach, "--teach", "pocket:N|loading|safe|sensor", {"--config", "--at"},
   {"--ini", "--tool-table"},
   "write a jogged-to machine position (G53) into config.json",
   "write a machine position (G53, in config.json's units), where the spindle was jogged to, "
   "into config.json: pocket:N the x, y and z of pockets.\"N\" (the pocket must be there "
   "already), loading and safe their x, y and z, sensor the x and y of probe_limit. The new "
   "config must pass what --check checks; otherwise nothing is written and one line names the "
   "target, the position and the first problem. The file is replaced crash-safe, the previous "
   "one kept as FILE.bak; a config that is a symbolic link, has a second name or is read-only "
   "is refused. The config is locked from before it is read until it is replaced: a second "
   "--teach, or the component's teach, waits its turn (at most 5 s). Exit 0 written, 1 refused "
   "(nothing written), 2 usage or a file that cannot be read or written"},
  {Mode::plot, "--plot", "FILE.svg", {"--config"}, {"--state", "--from", "--to", "--ini"},
   "draw the rack from above, and the path of M6 TB with TA in the spindle",
   "draw the rack from above into FILE.svg: each pocket with its number, tool, keep-out and "
   "approach, safe, loading and the touch-off sensor, as the config (and --state, else the "
   "first-start map) has them; with --from A --to B also the XY path of that change; with --ini "
   "the machine's travel, its soft limits in X and Y, as an outline. FILE.svg "
   "must not be the config or state file, a symbolic link, a second name, a read-only file or a "
   "FIFO. Exit 0 written, 1 invalid config or state or a refused change, 2 the file cannot be "
   "written"},
  {Mode::operator_request, "--operator", "ACTION", {},
   {"--ini", "--state", "--into", "--spindle", "--pocket", "--yes", "--timeout"},
   "ask the running component, as its panel does: load, unload, continue, cancel, ...",
   "the operator without a GUI (a script, a terminal over SSH): asks the running component, "
   "through the pins its panel pulses and the status file it reads, for ACTION: `load:T` "
   "(`--into P`), `unload:T`, `continue`, `cancel`, `clear-fault` (`--spindle N`, `--pocket "
   "yes|no`), `measure-all` (every tool in the rack; `measure-all:never` those never measured, "
   "`measure-all:program` the loaded program's) or `verify:P`; prints each message the "
   "component says meanwhile (the prompts' words among them) and last the outcome, and exits "
   "when the request has ended. A prompt waits for `continue` or `cancel` from another "
   "invocation (or the panel), or is answered by `--yes`. The state file, and so the status "
   "file beside it, is the INI's [FIXED_ATC_PROBE]STATE (--ini) or --state. A pin netted from a "
   "panel's button is pressed through its signal, as the button would; a pin another writer "
   "holds is refused. The component's words are printed with their control characters shown "
   "(\\x1b), never acted on. Exit 0 done, 1 refused (nothing moved; also Continue, Cancel or "
   "Clear fault with nothing to act on), 2 usage (an --ini that cannot be read or names no "
   "[FIXED_ATC_PROBE]STATE among them) or its output lost (a write to standard output failed), 3 "
   "fault, 4 cancelled, 5 timeout (--timeout, or the component did not take the request up "
   "within 10 s), 6 the component is not running (no HAL, no fixed_atc_probe pins, or no status "
   "file), 7 failed (the flow ended without doing it, its error said: a probe that missed the "
   "sensor). A signal a terminal session sends (SIGHUP of a dropped SSH session, SIGINT, SIGTERM, "
   "SIGQUIT, SIGPIPE) stops the waiting: it leaves HAL, says so on stderr and ends by that "
   "signal (the shell's 128 + N); the request goes on in the component"},
  {Mode::dot, "--dot", "", {}, {}, "print the state machine as Graphviz",
   "print the state machine as Graphviz, generated from its transition tables"},
  {Mode::help, "--help", "", {}, {}, "print this help", "print the usage (also -h)"},
  {Mode::version, "--version", "", {}, {}, "print the name and version",
   "print the name and version: the release (the package's version) and, built from a git "
   "checkout, the commit, as `fixed_atc_probe 0.1.0 (29d48c9)`; the component's first line "
   "at start says the same. Exit 0"},
};
// clang-format on

const OptionDeclaration& option(const std::string& name) {
  return *std::find_if(kOptions.begin(), kOptions.end(),
                       [&](const OptionDeclaration& o) { return name == o.name; });
}

std::string mode_name(const ModeDeclaration& mode) {
  return *mode.flag ? mode.flag : "the component (no --check, --plan, --dot)";
}

bool reads(const ModeDeclaration& mode, const std::string& name) {
  const auto named = [&](const char* o) { return name == o; };
  return std::any_of(mode.needs.begin(), mode.needs.end(), named) ||
         std::any_of(mode.may.begin(), mode.may.end(), named);
}

std::optional<int> tool_argument(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  for (const char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
  }
  return std::stoi(text);
}

/// A number as a machinist types it: an optional sign, decimal digits with
/// or without a point (12, -80.5, .5, 12.) and an optional exponent (1e2);
/// never hex, inf, nan, a decimal comma or anything after it, whatever the
/// locale says.
std::optional<double> decimal_argument(std::string_view text) {
  std::size_t at = 0;
  const auto digits = [&] {
    const std::size_t from = at;
    while (at < text.size() && text[at] >= '0' && text[at] <= '9') ++at;
    return at - from;
  };
  if (at < text.size() && (text[at] == '+' || text[at] == '-')) ++at;
  const std::size_t number_at = at;
  std::size_t mantissa = digits();
  if (at < text.size() && text[at] == '.') {
    ++at;
    mantissa += digits();
  }
  if (mantissa == 0) return std::nullopt;
  if (at < text.size() && (text[at] == 'e' || text[at] == 'E')) {
    ++at;
    if (at < text.size() && (text[at] == '+' || text[at] == '-')) ++at;
    if (digits() == 0) return std::nullopt;
  }
  if (at != text.size()) return std::nullopt;
  // from_chars reads the C locale's way and takes no '+'; out of range is no number.
  double value = 0.0;
  const char* first = text.data() + number_at;
  const auto [end, failed] = std::from_chars(first, text.data() + text.size(), value);
  if (failed != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return text[0] == '-' ? -value : value;
}

/// "X,Y,Z": three decimal numbers, blanks around each allowed; nullopt and
/// what is wrong in `error` otherwise.
std::optional<Point> position_argument(const std::string& text, std::string& error) {
  const char* const axes[] = {"X", "Y", "Z"};
  double values[3];
  std::size_t at = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const std::size_t comma = text.find(',', at);
    if (axis < 2 && comma == std::string::npos) {
      error = "expected X,Y,Z (three numbers with commas between), got " + quote(text);
      return std::nullopt;
    }
    const std::size_t end = axis < 2 ? comma : text.size();
    std::string_view part(text.data() + at, end - at);
    while (!part.empty() && (part.front() == ' ' || part.front() == '\t')) part.remove_prefix(1);
    while (!part.empty() && (part.back() == ' ' || part.back() == '\t')) part.remove_suffix(1);
    const auto value = decimal_argument(part);
    if (!value) {
      error = std::string(axes[axis]) + " " +
              (part.empty() ? std::string("is empty") : quote(part) + " is not a decimal number") +
              " (expected X,Y,Z like 120.5,80,-5 in machine coordinates; got " + quote(text) + ")";
      return std::nullopt;
    }
    values[axis] = *value;
    at = end + 1;
  }
  return Point{values[0], values[1], values[2]};
}

/// `text`, the value of `arg`, into `options`; false and one line in `error` when it is no such value.
bool take_value(const std::string& arg, const std::string& text, Options& options,
                std::string& error) {
  const bool tool = arg == "--from" || arg == "--to" || arg == "--spindle";
  // --teach, --at and --operator say what they expect themselves.
  const bool says_itself = arg == "--teach" || arg == "--at" || arg == "--operator";
  if (text.empty() && !says_itself && arg != "--into" && arg != "--timeout") {
    error = arg + ": expected " + (tool ? "a tool number" : "a file path") + ", got nothing";
    return false;
  }
  if (arg == "--operator") {
    options.request = parse_operator_action(text, error);
    return options.request.has_value();
  }
  if (arg == "--into") {
    options.into_pocket = tool_argument(text);
    if (!options.into_pocket) error = "--into: expected a pocket number (0: the changer chooses), got " + quote(text);
    return options.into_pocket.has_value();
  }
  if (arg == "--timeout") {
    options.timeout_seconds = decimal_argument(text);
    if (!options.timeout_seconds || *options.timeout_seconds <= 0.0) {
      error = "--timeout: expected seconds above 0, got " + quote(text);
      return false;
    }
    return true;
  }
  if (tool) {
    const auto number = tool_argument(text);
    if (!number) {
      error = arg + ": expected a tool number, at most 9 digits and nothing else (0 for none), got " +
              quote(text);
      return false;
    }
    (arg == "--from" ? options.from_tool : arg == "--to" ? options.to_tool : options.spindle_tool) =
        *number;
  } else if (arg == "--pocket") {
    if (text != "yes" && text != "no") {
      error = "--pocket: expected yes or no, got " + quote(text);
      return false;
    }
    options.pocket_holds_tool = text == "yes";
  } else if (arg == "--plot") {
    // A name that ends otherwise is likely the config or state given in the wrong place.
    const std::string tail = text.size() >= 4 ? text.substr(text.size() - 4) : "";
    if (tail != ".svg" && tail != ".SVG") {
      error = "--plot: expected a file name ending in .svg, got " + quote(text);
      return false;
    }
    options.plot_path = text;
  } else if (arg == "--teach") {
    options.teach_target = parse_teach_target(text);
    if (!options.teach_target) {
      error = "--teach: expected pocket:N, loading, safe or sensor, got " + quote(text);
      return false;
    }
  } else if (arg == "--at") {
    std::string wrong;
    options.teach_at = position_argument(text, wrong);
    if (!options.teach_at) {
      error = "--at: " + wrong;
      return false;
    }
  } else {
    const std::map<std::string, std::string*> paths = {{"--config", &options.config_path},
                                                       {"--state", &options.state_path},
                                                       {"--lint", &options.program_path}};
    if (const auto path = paths.find(arg); path != paths.end()) {
      *path->second = text;
    } else if (arg == "--ini") {
      options.ini_path = text;
    } else if (arg == "--tool-table") {
      options.tool_table_path = text;
    } else {
      options.subroutine_path = text;
    }
  }
  return true;
}

/// Where `arg` first stands in `args`, as itself or as arg=value.
std::size_t first_place(const std::vector<std::string>& args, const std::string& arg) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] == arg || args[i].rfind(arg + "=", 0) == 0) return i;
  }
  return args.size();
}

/// "--ini FILE", or "--yes" for a flag.
std::string named_value(const char* name) {
  const char* value = option(name).value;
  return *value ? std::string(name) + " " + value : std::string(name);
}

/// --operator's options given where its ACTION does not read them; empty when none is.
std::string operator_options_misplaced(const Options& options) {
  using Action = OperatorRequest::Action;
  if (!options.ini_path && options.state_path.empty()) {
    return "--operator needs --ini FILE (the machine's INI, whose [FIXED_ATC_PROBE]STATE names "
           "the status file) or --state FILE";
  }
  const Action action = options.request->action;
  if (options.into_pocket && action != Action::load) return "--into is read only by --operator load:T";
  if ((options.spindle_tool || options.pocket_holds_tool) && action != Action::clear_fault) {
    return std::string(options.spindle_tool ? "--spindle" : "--pocket") +
           " is read only by --operator clear-fault";
  }
  return "";
}

std::string synopsis(const ModeDeclaration& mode) {
  std::string line = "fixed_atc_probe";
  if (*mode.flag) line += std::string(" ") + mode.flag;
  if (*mode.value) line += std::string(" ") + mode.value;
  for (const char* name : mode.needs) line += std::string(" ") + name + " " + option(name).value;
  for (const char* name : mode.may) line += std::string(" [") + named_value(name) + "]";
  return line;
}

}  // namespace

const std::vector<ModeDeclaration>& modes() { return kModes; }
const std::vector<OptionDeclaration>& options() { return kOptions; }

std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error) {
  CLI::App app;
  app.set_help_flag();  // --help is a mode of its own
  app.allow_extras();
  std::map<std::string, std::vector<std::string>> values;
  std::map<std::string, CLI::Option*> given;
  std::vector<std::string> valued;  // the options and modes that take a value, in order
  for (const ModeDeclaration& mode : kModes) {
    if (!*mode.flag) continue;
    const std::string flag = mode.flag;
    if (*mode.value) {
      given[flag] = app.add_option(flag, values[flag])
                        ->expected(0, 1)
                        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
      valued.push_back(flag);
    } else {
      // A mode flag takes no value: --dot=1 is refused, not read as --dot.
      given[flag] = app.add_flag(flag == "--help" ? "-h,--help" : flag)->disable_flag_override();
    }
  }
  for (const OptionDeclaration& o : kOptions) {
    if (!*o.value) {  // a flag: --yes=1 is refused, not read as --yes
      given[o.name] = app.add_flag(o.name)->disable_flag_override();
      continue;
    }
    given[o.name] = app.add_option(o.name, values[o.name])
                        ->expected(0, 1)
                        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    valued.push_back(o.name);
  }
  // A value starting with one '-' (--at -.5,0,0) is the option's, as if given
  // --at=-.5,0,0: CLI11 takes only what reads as a negative number as a value.
  std::vector<std::string> joined;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const bool takes_value = std::find(valued.begin(), valued.end(), args[i]) != valued.end();
    if (takes_value && i + 1 < args.size() && args[i + 1].rfind('-', 0) == 0 &&
        args[i + 1].rfind("--", 0) != 0) {
      joined.push_back(args[i] + "=" + args[i + 1]);
      ++i;
    } else {
      joined.push_back(args[i]);
    }
  }
  try {
    std::vector<std::string> reversed(joined.rbegin(), joined.rend());
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    error = e.what();
    for (const std::string& arg : args) {  // CLI11's words for --dot=1 and --yes=1
      const auto equals = arg.find('=');
      const auto flag = std::find_if(kModes.begin(), kModes.end(), [&](const ModeDeclaration& m) {
        return *m.flag && !*m.value && arg.substr(0, equals) == m.flag;
      });
      const auto option_flag = std::find_if(kOptions.begin(), kOptions.end(), [&](const OptionDeclaration& o) {
        return !*o.value && arg.substr(0, equals) == o.name;
      });
      if (equals != std::string::npos && (flag != kModes.end() || option_flag != kOptions.end())) {
        error = arg.substr(0, equals) + " takes no value, got " + quote(arg.substr(equals + 1));
        break;
      }
    }
    return std::nullopt;
  }
  Options options;
  // Two modes, or one twice.
  const ModeDeclaration* mode = &kModes.front();
  std::size_t mode_at = args.size();
  for (const ModeDeclaration& m : kModes) {
    if (!*m.flag || given.at(m.flag)->count() == 0) continue;
    const std::size_t at = std::min(first_place(args, m.flag), m.mode == Mode::help
                                                                   ? first_place(args, "-h")
                                                                   : args.size());
    if (mode != &kModes.front()) {
      const bool this_first = at < mode_at;
      error = std::string(this_first ? m.flag : mode->flag) + " and " +
              (this_first ? mode->flag : m.flag) + " cannot be combined";
      return std::nullopt;
    }
    if (given.at(m.flag)->count() > 1) {
      error = std::string(m.flag) + " given twice";
      return std::nullopt;
    }
    mode = &m;
    mode_at = at;
  }
  options.mode = mode->mode;
  // Each value: there, once, and what its option expects.
  for (const std::string& arg : valued) {
    const CLI::Option* option = given.at(arg);
    if (option->count() == 0) continue;
    const std::vector<std::string>& taken = values.at(arg);
    // Given bare (not as --option=value): the next argument must be its value.
    if (const std::size_t at = first_place(args, arg); args[at] == arg) {
      if (at + 1 == args.size()) {
        error = arg + " needs a value";
        return std::nullopt;
      }
      if (args[at + 1].rfind("--", 0) == 0) {
        error = arg + " needs a value, got the option " + quote(args[at + 1]);
        return std::nullopt;
      }
    }
    if (taken.size() > 1) {
      error = arg + " given twice (" + quote(taken[0]) + " and " + quote(taken[1]) + ")";
      return std::nullopt;
    }
  }
  if (!app.remaining().empty()) {
    error = "unknown argument " + quote(app.remaining().front());
    return std::nullopt;
  }
  for (const std::string& arg : valued) {
    if (values.at(arg).empty()) continue;
    if (!take_value(arg, values.at(arg).front(), options, error)) return std::nullopt;
  }
  // An option the mode would not read is refused, not ignored.
  for (const OptionDeclaration& o : kOptions) {
    if (given.at(o.name)->count() != 0 && !reads(*mode, o.name)) {
      error = std::string(o.name) + " is not used by " + mode_name(*mode);
      return std::nullopt;
    }
  }
  for (const char* name : mode->needs) {
    if (given.at(name)->count() != 0) continue;
    const OptionDeclaration& o = option(name);
    error = std::string(name) == "--config" ? std::string("--config FILE is required")
                                            : std::string(mode->flag) + " needs " + name + " " +
                                                  o.value + (*o.hint ? std::string(" (") + o.hint + ")" : "");
    return std::nullopt;
  }
  if (options.mode == Mode::plot && options.from_tool.has_value() != options.to_tool.has_value()) {
    error = "--plot: --from A and --to B go together (the change to draw)";
    return std::nullopt;
  }
  if (options.mode == Mode::operator_request) {
    if (given.at("--yes")->count() > 1) {
      error = "--yes given twice";
      return std::nullopt;
    }
    if (const std::string wrong = operator_options_misplaced(options); !wrong.empty()) {
      error = wrong;
      return std::nullopt;
    }
    options.answer_yes = given.at("--yes")->count() == 1;
  }
  options.state_given = !options.state_path.empty();
  // --plan and --plot read a state file only when given one, --operator the INI's; the others
  // default to CONFIG.state.
  if (reads(*mode, "--state") && options.mode != Mode::plan && options.mode != Mode::plot &&
      options.mode != Mode::operator_request && options.state_path.empty()) {
    options.state_path = options.config_path + ".state";
  }
  return options;
}

std::string usage() {
  std::string out;
  for (const ModeDeclaration& mode : kModes) {
    out += (out.empty() ? "usage: " : "       ") + synopsis(mode) + "\n";
    out += "           " + std::string(mode.summary) + "\n";
  }
  out += "options:\n";
  for (const OptionDeclaration& o : kOptions) {
    out += std::string("  ") + named_value(o.name) + "\n      " + o.doc + "\n";
  }
  return out;
}

std::string synopsis_man() {
  std::string out;
  for (const ModeDeclaration& mode : kModes) {
    if (!out.empty()) out += ".br\n";
    out += ".B " + std::string(mode.mode == Mode::component ? "loadusr -W " : "") +
           "fixed_atc_probe" + (*mode.flag ? std::string(" ") + mode.flag : "") + "\n";
    if (*mode.value) out += ".I " + std::string(mode.value) + "\n";
    for (const char* name : mode.needs) {
      out += ".B " + std::string(name) + "\n.I " + option(name).value + "\n";
    }
    for (const char* name : mode.may) {
      out += *option(name).value
                 ? ".RB [ " + std::string(name) + "\n.IR " + option(name).value + " ]\n"
                 : ".RB [ " + std::string(name) + " ]\n";
    }
  }
  return out;
}

std::string options_man() {
  std::string out;
  for (const ModeDeclaration& mode : kModes) {
    if (!*mode.flag) continue;
    out += ".TP\n.B " + std::string(mode.flag) + (*mode.value ? std::string(" ") + mode.value : "") +
           "\n" + man_text(mode.doc) + ".\n";
  }
  for (const OptionDeclaration& o : kOptions) {
    out += ".TP\n.B " + named_value(o.name) + "\n" + man_text(o.doc) + ".\n";
  }
  return out;
}

std::string man_text(const std::string& text) {
  std::string out;
  bool bold = false;
  for (const char c : text) {
    if (c == '`') {
      out += bold ? "\\fR" : "\\fB";
      bold = !bold;
    } else {
      out += c == '\\' ? std::string("\\e") : std::string(1, c);
    }
  }
  return out;
}

std::string command_line_markdown() {
  std::string out = "```\n";
  for (const ModeDeclaration& mode : kModes) out += synopsis(mode) + "\n";
  out += "```\n\n| mode | what it does |\n| --- | --- |\n";
  for (const ModeDeclaration& mode : kModes) {
    out += "| `" + std::string(*mode.flag ? mode.flag : "(none)") + "` | " + mode.doc + " |\n";
  }
  out += "\n| option | what it is |\n| --- | --- |\n";
  for (const OptionDeclaration& o : kOptions) {
    out += "| `" + named_value(o.name) + "` | " + o.doc + " |\n";
  }
  return out;
}

}  // namespace fatc::io
