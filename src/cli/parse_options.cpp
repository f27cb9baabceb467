#include "parse_options.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <string_view>

#include "command_line.hpp"
#include "core/config/quote.hpp"

namespace fatc::io {
namespace {

using Mode = Options::Mode;

std::string mode_name(const ModeDeclaration& mode) {
  return *mode.flag ? mode.flag : "the component (no --check, --plan, --dot)";
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

/// --touch POCKETS: "all", "datum" or pocket numbers with commas between, each once.
std::optional<Options::Touched> parse_touched(const std::string& text) {
  Options::Touched touched;
  if (text == "all" || text == "datum") {
    (text == "all" ? touched.all : touched.datum) = true;
    return touched;
  }
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const auto number = tool_argument(text.substr(at, comma - at));
    if (!number || *number == 0 ||
        std::find(touched.pockets.begin(), touched.pockets.end(), *number) != touched.pockets.end()) {
      return std::nullopt;
    }
    touched.pockets.push_back(*number);
    at = comma + 1;
  }
  return touched;
}

/// `text`, the value of `arg`, into `options`; false and one line in `error` when it is no such value.
bool take_value(const std::string& arg, const std::string& text, Options& options,
                std::string& error) {
  const bool tool = arg == "--from" || arg == "--to" || arg == "--spindle";
  // --teach, --at and --operator say what they expect themselves.
  const bool says_itself =
      arg == "--teach" || arg == "--at" || arg == "--operator" || arg == "--touch";
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
  if (arg == "--air" || arg == "--air-feed") {
    const auto value = decimal_argument(text);
    const bool height = arg == "--air";
    if (!value || *value <= 0.0) {
      error = arg + ": expected " +
              (height ? "a height above the rack, above 0" : "a feed, units per minute, above 0") +
              ", got " + quote(text);
      return false;
    }
    (height ? options.air_height : options.air_feed) = *value;
    return true;
  }
  if (arg == "--touch") {
    options.touch = parse_touched(text);
    if (!options.touch) error = "--touch: expected all, datum or pocket numbers like 3,5, got " + quote(text);
    return options.touch.has_value();
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
      error = "--teach: expected pocket:N, loading, safe, sensor or datum, got " + quote(text);
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

/// --operator's options given where its ACTION does not read them; empty when none is.
std::string operator_options_misplaced(const Options& options) {
  using Action = OperatorRequest::Action;
  if (!options.ini_path && options.state_path.empty()) {
    return "--operator needs --ini FILE (the machine's INI, whose [FIXED_ATC_PROBE]STATE names "
           "the status file) or --state FILE";
  }
  const Action action = options.request->action;
  if (options.into_pocket && action != Action::load) return "--into is read only by --operator load:T";
  if (options.holding_tool && !(action == Action::io && options.request->io == IoAction::chuck_release)) {
    return "--holding-tool is read only by --operator io:chuck-release";
  }
  if ((options.spindle_tool || options.pocket_holds_tool) && action != Action::clear_fault) {
    return std::string(options.spindle_tool ? "--spindle" : "--pocket") +
           " is read only by --operator clear-fault";
  }
  const bool flow = action == Action::load || action == Action::unload ||
                    action == Action::measure_all || action == Action::verify;
  if (options.step_by_step && !flow) {
    return "--step is read only by --operator load:T, unload:T, measure-all and verify:P (an "
           "M6's: the panel's switch or the step-by-step pin)";
  }
  return "";
}

}  // namespace

std::optional<Options> parse_options(const std::vector<std::string>& args, std::string& error) {
  const std::vector<ModeDeclaration>& declared_modes = modes();
  const std::vector<OptionDeclaration>& declared_options = options();
  CLI::App app;
  app.set_help_flag();  // --help is a mode of its own
  app.allow_extras();
  std::map<std::string, std::vector<std::string>> values;
  std::map<std::string, CLI::Option*> given;
  std::vector<std::string> valued;  // the options and modes that take a value, in order
  for (const ModeDeclaration& mode : declared_modes) {
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
  for (const OptionDeclaration& o : declared_options) {
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
      const auto flag = std::find_if(declared_modes.begin(), declared_modes.end(), [&](const ModeDeclaration& m) {
        return *m.flag && !*m.value && arg.substr(0, equals) == m.flag;
      });
      const auto option_flag = std::find_if(declared_options.begin(), declared_options.end(), [&](const OptionDeclaration& o) {
        return !*o.value && arg.substr(0, equals) == o.name;
      });
      if (equals != std::string::npos && (flag != declared_modes.end() || option_flag != declared_options.end())) {
        error = arg.substr(0, equals) + " takes no value, got " + quote(arg.substr(equals + 1));
        break;
      }
    }
    return std::nullopt;
  }
  Options options;
  // Two modes, or one twice.
  const ModeDeclaration* mode = &declared_modes.front();
  std::size_t mode_at = args.size();
  for (const ModeDeclaration& m : declared_modes) {
    if (!*m.flag || given.at(m.flag)->count() == 0) continue;
    const std::size_t at = std::min(first_place(args, m.flag), m.mode == Mode::help
                                                                   ? first_place(args, "-h")
                                                                   : args.size());
    if (mode != &declared_modes.front()) {
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
  for (const OptionDeclaration& o : declared_options) {
    if (given.at(o.name)->count() != 0 && !reads(*mode, o.name)) {
      error = std::string(o.name) + " is not used by " + mode_name(*mode);
      return std::nullopt;
    }
  }
  const bool touching = options.mode == Mode::plan && options.touch;
  if (touching && options.to_tool) {
    error = "--plan: --touch POCKETS plans the touch path, --to B a change: give one of them";
    return std::nullopt;
  }
  if (touching && options.air_height) {
    error = "--plan: --touch is not flown in the air (--air)";
    return std::nullopt;
  }
  for (const char* name : mode->needs) {
    if (given.at(name)->count() != 0) continue;
    // The touch path needs no change: the probe comes with --from or from the config.
    if (touching && std::string(name) != "--config") continue;
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
    for (const char* flag : {"--yes", "--holding-tool", "--step"}) {
      if (given.at(flag)->count() > 1) {
        error = std::string(flag) + " given twice";
        return std::nullopt;
      }
    }
    options.holding_tool = given.at("--holding-tool")->count() == 1;
    options.step_by_step = given.at("--step")->count() == 1;
    if (const std::string wrong = operator_options_misplaced(options); !wrong.empty()) {
      error = wrong;
      return std::nullopt;
    }
    options.answer_yes = given.at("--yes")->count() == 1;
  }
  if (options.air_feed && !options.air_height) {
    error = "--air-feed is read only with --air HEIGHT";
    return std::nullopt;
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

}  // namespace fatc::io
