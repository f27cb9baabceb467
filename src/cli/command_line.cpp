#include "command_line.hpp"

#include <algorithm>

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
  {"--holding-tool", "", "--operator io:chuck-release: the operator holds the tool in the "
   "spindle, so the chuck may open on it", ""},
  {"--step", "", "--operator load, unload, measure-all, verify: step by step (the step-by-step "
   "pin on for the request's sequence, then back as it was): each move and each chuck action "
   "waits for Continue, from --yes, the panel or a second `--operator continue`", ""},
  {"--timeout", "SECONDS",
   "--operator: stop waiting after this long (the request goes on: exit 5); without it the "
   "command waits for the end, as long as the operator takes", ""},
  {"--air", "HEIGHT",
   "--plan: the change flown in the air, as the panel's air run flies it: no move over the rack "
   "lower than HEIGHT above its top (the holders' top plus rack_keepout_above, the config's "
   "units), every move at --air-feed, the chuck, the probe and LinuxCNC's tool commands left "
   "out, checked with the tool --from in the spindle all the way", ""},
  {"--air-feed", "FEED",
   "--plan --air: the feed of every move, units per minute (default: the config's verify_feed, "
   "else pocket_feed)", ""},
  {"--touch", "POCKETS",
   "--plan: the path that finds pockets by touch (rack_touch) instead of a change: all, datum, "
   "or pocket numbers with commas between (3,5), with the probe --from (else the config's first "
   "tool of kind probe) in the spindle, each touch as if it touched where expected; its moves "
   "checked against the keep-out with the probe's length in the tool table", ""},
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
  {Mode::plan, "--plan", "", {"--config", "--from", "--to"},
   {"--ini", "--state", "--tool-table", "--air", "--air-feed", "--touch"},
   "print the steps of M6 TB with TA in the spindle",
   "print the steps of M6 TB with TA in the spindle (the tools where --state has them, else "
   "the first-start map, said so when --state names no file yet), then its estimated time on the config's path and on the other one "
   "(each move an exact stop, G61.1, at the --ini's velocities and axes' accelerations, as "
   "LinuxCNC plans it, else at assumed ones; the dwells; the executor's handshake a step and "
   "iocontrol's cycles a change) and, with --ini, the bound: the direct path's moves at the INI's velocities and "
   "accelerations, each an exact stop, plus the dwells (and the prototype path's time at the "
   "same limits), and how much of it may move while the spindle runs down "
   "(move_while_spindle_stops). With --touch POCKETS instead of --to: the touch path (rack_touch) "
   "and the positions it would find. Exit 0 printed, 1 refused or invalid, 2 usage"},
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
  {Mode::teach, "--teach", "pocket:N|loading|safe|sensor|datum", {"--config", "--at"},
   {"--ini", "--tool-table"},
   "write a jogged-to machine position (G53) into config.json",
   "write a machine position (G53, in config.json's units), where the spindle was jogged to, "
   "into config.json: pocket:N the x, y and z of pockets.\"N\" (the pocket must be there "
   "already), loading and safe their x, y and z, sensor the x and y of probe_limit, datum the "
   "x, y and z of rack_touch.datum (its pocket named there already). The new "
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
   {"--ini", "--state", "--into", "--spindle", "--pocket", "--yes", "--holding-tool", "--step",
    "--timeout"},
   "ask the running component, as its panel does: load, unload, continue, cancel, ...",
   "the operator without a GUI (a script, a terminal over SSH): asks the running component, "
   "through the pins its panel pulses and the status file it reads, for ACTION: `load:T` "
   "(`--into P`), `unload:T`, `continue`, `cancel`, `clear-fault` (`--spindle N`, `--pocket "
   "yes|no`), `measure-all` (every tool in the rack; `measure-all:never` those never measured, "
   "`measure-all:program` the loaded program's), `verify:P`, `io` (the I/O check: each sensor, "
   "what it should read and why, live until Ctrl-C or --timeout) or `io:OUTPUT` (drive one "
   "output once: `chuck-release` (`--holding-tool` with a tool in the spindle), `chuck-clamp`, "
   "`cover-open`, `cover-close`, `air-blast`; prints the refusal or how long its sensor took); "
   "prints each message the "
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

}  // namespace

const std::vector<ModeDeclaration>& modes() { return kModes; }
const std::vector<OptionDeclaration>& options() { return kOptions; }

const OptionDeclaration& option(const std::string& name) {
  return *std::find_if(kOptions.begin(), kOptions.end(),
                       [&](const OptionDeclaration& o) { return name == o.name; });
}

bool reads(const ModeDeclaration& mode, const std::string& name) {
  const auto named = [&](const char* o) { return name == o; };
  return std::any_of(mode.needs.begin(), mode.needs.end(), named) ||
         std::any_of(mode.may.begin(), mode.may.end(), named);
}

std::string named_value(const char* name) {
  const char* value = option(name).value;
  return *value ? std::string(name) + " " + value : std::string(name);
}

}  // namespace fatc::io
