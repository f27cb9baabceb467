// --operator: its arguments, and how the watching of one request judges its
// end from what the component's pins and status file say, poll by poll.
#include "cli/operator_watch.hpp"

#include <gtest/gtest.h>

#include "cli/parse_options.hpp"
#include "cli/usage.hpp"

namespace fatc::io {
namespace {

using Action = OperatorRequest::Action;

std::optional<Options> parsed(const std::vector<std::string>& args, std::string& error) {
  return parse_options(args, error);
}

TEST(OperatorArguments, shouldReadEachActionTheWayAMachinistTypesIt) {
  std::string error;
  const auto load =
      parsed({"--operator", "load:3", "--into", "5", "--yes", "--ini", "m.ini"}, error);
  ASSERT_TRUE(load) << error;
  EXPECT_EQ(load->mode, Options::Mode::operator_request);
  EXPECT_EQ(load->request->action, Action::load);
  EXPECT_EQ(load->request->number, 3);
  EXPECT_EQ(*load->into_pocket, 5);
  EXPECT_TRUE(load->answer_yes);
  EXPECT_FALSE(load->step_by_step);
  EXPECT_TRUE(load->state_path.empty());  // the INI's STATE, read when it runs
  for (const char* flow : {"load:3", "unload:3", "measure-all", "verify:2"}) {
    const auto stepped = parsed({"--operator", flow, "--step", "--state", "s.json"}, error);
    ASSERT_TRUE(stepped) << flow << ": " << error;
    EXPECT_TRUE(stepped->step_by_step) << flow;
  }

  const struct {
    const char* text;
    Action action;
    int number;
  } cases[] = {{"unload:12", Action::unload, 12},       {"continue", Action::continue_prompt, 0},
               {"cancel", Action::cancel, 0},           {"clear-fault", Action::clear_fault, 0},
               {"measure-all", Action::measure_all, 0}, {"measure-all:never", Action::measure_all, 1},
               {"measure-all:program", Action::measure_all, 2}, {"verify:4", Action::verify, 4}};
  for (const auto& c : cases) {
    const auto options = parsed({"--operator", c.text, "--state", "s.json"}, error);
    ASSERT_TRUE(options) << c.text << ": " << error;
    EXPECT_EQ(options->request->action, c.action) << c.text;
    EXPECT_EQ(options->request->number, c.number) << c.text;
    EXPECT_FALSE(options->answer_yes);
  }
  const auto clear = parsed(
      {"--operator", "clear-fault", "--spindle", "0", "--pocket", "yes", "--ini", "m.ini"}, error);
  ASSERT_TRUE(clear) << error;
  EXPECT_EQ(*clear->spindle_tool, 0);
  EXPECT_TRUE(*clear->pocket_holds_tool);
}

TEST(OperatorArguments, shouldReadTheIoCheckLiveOrOneOutput) {
  std::string error;
  const auto live = parsed({"--operator", "io", "--timeout", "2", "--ini", "m.ini"}, error);
  ASSERT_TRUE(live) << error;
  EXPECT_EQ(live->request->action, Action::io);
  EXPECT_EQ(live->request->io, std::nullopt);
  const auto release =
      parsed({"--operator", "io:chuck-release", "--holding-tool", "--ini", "m.ini"}, error);
  ASSERT_TRUE(release) << error;
  EXPECT_EQ(release->request->io, IoAction::chuck_release);
  EXPECT_TRUE(release->holding_tool);
  EXPECT_STREQ(press_of(*release->request, {}, {}, {}).pulse, "io-check-chuck-release");
  EXPECT_FALSE(parsed({"--operator", "io:flush", "--ini", "m.ini"}, error));
  EXPECT_EQ(error,
            "--operator io: expected io (the sensors, live) or one of io:chuck-release, "
            "io:chuck-clamp, io:cover-open, io:cover-close, io:air-blast, got \"io:flush\"");
  EXPECT_FALSE(parsed({"--operator", "io:chuck-clamp", "--holding-tool", "--ini", "m.ini"}, error));
  EXPECT_EQ(error, "--holding-tool is read only by --operator io:chuck-release");
  EXPECT_FALSE(parsed({"--operator", "unload:3", "--holding-tool", "--ini", "m.ini"}, error));
  EXPECT_EQ(error, "--holding-tool is read only by --operator io:chuck-release");
}

TEST(OperatorStatus, shouldReadTheIoChecksWordsWhereTheComponentWritesThem) {
  const auto words = parse_status_words(
      R"json({"state": 1, "awaiting": 0, "activity": "", "serial": 4, "messages": [],
          "io_check": {"sensors": ["drawbar-closed: on, expected on (the chuck is clamped)"],
                       "refusals": {"chuck-release": "", "cover-close": "the machine is off"},
                       "last": "", "held": false}})json");
  ASSERT_TRUE(words);
  EXPECT_EQ(words->io_sensors,
            std::vector<std::string>{"drawbar-closed: on, expected on (the chuck is clamped)"});
  ASSERT_EQ(words->io_refusals.size(), 2u);
  EXPECT_EQ(words->io_refusals[1].second, "the machine is off");
  // An older component's file has none.
  EXPECT_TRUE(parse_status_words(
                  R"({"state": 1, "awaiting": 0, "activity": "", "serial": 4, "messages": []})")
                  ->io_sensors.empty());
}

TEST(OperatorArguments, shouldRefuseBadInputWithOneLineSayingWhatIsExpected) {
  const struct {
    std::vector<std::string> args;
    const char* error;
  } cases[] = {
      {{"--operator", "lod:3", "--ini", "m.ini"},
       "--operator: expected load:T, unload:T, continue, cancel, clear-fault, measure-all, "
       "measure-all:never, measure-all:program, verify:P, io, io:OUTPUT, touch, touch:P, "
       "teach-datum, check-datum or clear-datum-drift, got \"lod:3\""},
      {{"--operator", "load:0", "--ini", "m.ini"},
       "--operator load: expected load:N, N a tool number above 0, got \"load:0\""},
      {{"--operator", "load:x", "--ini", "m.ini"},
       "--operator load: expected load:N, N a tool number above 0, got \"load:x\""},
      {{"--operator", "load", "--ini", "m.ini"},
       "--operator load: expected load:N, N a tool number above 0, got \"load\""},
      {{"--operator", "verify:-1", "--ini", "m.ini"},
       "--operator verify: expected verify:N, N a pocket number above 0, got \"verify:-1\""},
      {{"--operator", "touch:0", "--ini", "m.ini"},
       "--operator touch: expected touch:N, N a pocket number above 0, got \"touch:0\""},
      {{"--operator", "check-datum:1", "--ini", "m.ini"},
       "--operator: expected load:T, unload:T, continue, cancel, clear-fault, measure-all, "
       "measure-all:never, measure-all:program, verify:P, io, io:OUTPUT, touch, touch:P, "
       "teach-datum, check-datum or clear-datum-drift, got \"check-datum:1\""},
      {{"--operator", "continue:2", "--ini", "m.ini"},
       "--operator: expected load:T, unload:T, continue, cancel, clear-fault, measure-all, "
       "measure-all:never, measure-all:program, verify:P, io, io:OUTPUT, touch, touch:P, "
       "teach-datum, check-datum or clear-datum-drift, got \"continue:2\""},
      {{"--operator", "measure-all:some", "--ini", "m.ini"},
       "--operator: expected load:T, unload:T, continue, cancel, clear-fault, measure-all, "
       "measure-all:never, measure-all:program, verify:P, io, io:OUTPUT, touch, touch:P, "
       "teach-datum, check-datum or clear-datum-drift, got \"measure-all:some\""},
      {{"--operator", "load:3"},
       "--operator needs --ini FILE (the machine's INI, whose [FIXED_ATC_PROBE]STATE names the "
       "status file) or --state FILE"},
      {{"--operator", "unload:3", "--into", "2", "--ini", "m.ini"},
       "--into is read only by --operator load:T"},
      {{"--operator", "load:3", "--pocket", "yes", "--ini", "m.ini"},
       "--pocket is read only by --operator clear-fault"},
      {{"--operator", "load:3", "--into", "a", "--ini", "m.ini"},
       "--into: expected a pocket number (0: the changer chooses), got \"a\""},
      {{"--operator", "load:3", "--timeout", "0", "--ini", "m.ini"},
       "--timeout: expected seconds above 0, got \"0\""},
      {{"--operator", "load:3", "--yes=1", "--ini", "m.ini"}, "--yes takes no value, got \"1\""},
      {{"--operator", "load:3", "--yes", "--yes", "--ini", "m.ini"}, "--yes given twice"},
      {{"--check", "--config", "c.json", "--yes"}, "--yes is not used by --check"},
      {{"--operator", "load:3", "--step", "--step", "--ini", "m.ini"}, "--step given twice"},
      {{"--operator", "continue", "--step", "--ini", "m.ini"},
       "--step is read only by --operator load:T, unload:T, measure-all and verify:P (an M6's: "
       "the panel's switch or the step-by-step pin)"},
      {{"--plan", "--config", "c.json", "--from", "1", "--to", "2", "--step"},
       "--step is not used by --plan"},
  };
  for (const auto& c : cases) {
    std::string error;
    EXPECT_FALSE(parsed(c.args, error)) << c.args[1];
    EXPECT_EQ(error, c.error);
  }
}

TEST(OperatorArguments, shouldShowTheFlagWithoutAValueInEveryReference) {
  EXPECT_NE(usage().find("fixed_atc_probe --operator ACTION [--ini FILE] [--state FILE] [--into "
                         "P] [--spindle N] [--pocket yes|no] [--yes] [--holding-tool] [--step] "
                         "[--timeout SECONDS]"),
            std::string::npos)
      << usage();
  EXPECT_NE(options_man().find(".B --yes\n"), std::string::npos);
  EXPECT_NE(command_line_markdown().find("| `--yes` |"), std::string::npos);
  EXPECT_NE(options_man().find(".B --holding-tool\n"), std::string::npos);
}

TEST(OperatorExitStatus, shouldGiveEachOutcomeItsOwnStatusBesideUsages2) {
  EXPECT_EQ(operator_exit_status(OperatorOutcome::done), 0);
  EXPECT_EQ(operator_exit_status(OperatorOutcome::refused), 1);
  EXPECT_EQ(operator_exit_status(OperatorOutcome::fault), 3);
  EXPECT_EQ(operator_exit_status(OperatorOutcome::cancelled), 4);
  EXPECT_EQ(operator_exit_status(OperatorOutcome::timeout), 5);
  EXPECT_EQ(operator_exit_status(OperatorOutcome::not_running), 6);
}

TEST(OperatorPress, shouldSetWhatThePanelSetsThenPulseItsButton) {
  const Press load = press_of({Action::load, 3}, 5, std::nullopt, std::nullopt);
  ASSERT_EQ(load.set.size(), 2u);
  EXPECT_STREQ(load.set[0].pin, "tool-number");
  EXPECT_EQ(load.set[0].value, 3);
  EXPECT_STREQ(load.set[1].pin, "pocket-number");
  EXPECT_EQ(load.set[1].value, 5);
  EXPECT_STREQ(load.pulse, "load");
  // Unanswered questions stay "not said": the component asks for them.
  const Press clear = press_of({Action::clear_fault, 0}, std::nullopt, std::nullopt, std::nullopt);
  EXPECT_EQ(clear.set[0].value, -1);
  EXPECT_EQ(clear.set[1].value, -1);
  EXPECT_STREQ(press_of({Action::verify, 2}, {}, {}, {}).pulse, "verify-pocket");
  EXPECT_EQ(press_of({Action::measure_all, 2}, {}, {}, {}).set[0].value, 2);
}

TEST(OperatorStatus, shouldReadTheStatusFileAndNothingHalfWritten) {
  const auto words = parse_status_words(
      R"({"phase": "loading", "state": 3, "awaiting": 5, "activity": "Insert tool 3",
          "serial": 4, "messages": [{"kind": "prompt", "text": "Insert tool 3"}]})");
  ASSERT_TRUE(words);
  EXPECT_EQ(words->state, 3);
  EXPECT_EQ(words->awaiting, 5);
  EXPECT_EQ(words->serial, 4);
  ASSERT_EQ(words->messages.size(), 1u);
  EXPECT_EQ(words->messages[0].second, "Insert tool 3");
  EXPECT_FALSE(parse_status_words(R"({"phase": "loading", "sta)"));
  EXPECT_FALSE(parse_status_words(R"({"phase": "loading"})"));
}

TEST(OperatorStatus, shouldTakeNoNumberOfTheStatusFileThatIsNoWholeCodeOrCount) {
  // fuzz_status: "state": 6e22 was converted to int with undefined behaviour; a negative serial
  // would overflow the count of fresh messages.
  const auto words = [](const std::string& state, const std::string& serial) {
    return parse_status_words(R"({"state": )" + state + R"(, "awaiting": 0, "activity": "",
                                  "serial": )" +
                              serial + R"(, "messages": []})");
  };
  EXPECT_TRUE(words("3", "4"));
  for (const char* state : {"6e22", "2.5", "-1", "99999999999", "true", "\"3\""}) {
    EXPECT_FALSE(words(state, "4")) << state;
  }
  for (const char* serial : {"-9223372036854775808", "18446744073709551615", "1e300", "4.5"}) {
    EXPECT_FALSE(words("3", serial)) << serial;
  }
}

TEST(OperatorStatus, shouldRefuseContinueCancelAndClearWithNothingToActOn) {
  const ComponentPins idle{1, false, false, false};
  EXPECT_EQ(nothing_to_act_on({Action::continue_prompt, 0}, idle),
            "Continue: nothing is waiting for the operator");
  EXPECT_EQ(nothing_to_act_on({Action::cancel, 0}, idle),
            "Cancel: nothing is waiting for the operator");
  EXPECT_EQ(nothing_to_act_on({Action::clear_fault, 0}, idle), "clear fault: there is no fault");
  EXPECT_EQ(nothing_to_act_on({Action::load, 3}, idle), "");
  EXPECT_EQ(nothing_to_act_on({Action::continue_prompt, 0}, {3, true, true, false}), "");
}

/// The status file as the component writes it after `said` more messages.
StatusWords said(StatusWords words, int state, int awaiting,
                 std::vector<std::pair<std::string, std::string>> messages) {
  words.state = state;
  words.awaiting = awaiting;
  for (auto& m : messages) {
    words.messages.push_back(std::move(m));
    ++words.serial;
  }
  return words;
}

TEST(OperatorWatch, shouldAnswerEachPromptOnceWithYesAndEndDone) {
  StatusWords status;
  status.serial = 7;
  status.messages = {{"info", "an old message, not this request's"}};
  status.state = 1;
  OperatorWatch watch({Action::load, 3}, true, status.serial);
  auto turn = watch.observe(status, {1, false, false, false});
  EXPECT_TRUE(turn.lines.empty());
  EXPECT_FALSE(turn.outcome);
  EXPECT_FALSE(watch.answered());

  status = said(status, 3, 5, {{"prompt", "Insert tool 3 into the spindle, then press Continue"}});
  turn = watch.observe(status, {3, true, true, false});
  EXPECT_EQ(turn.lines, (std::vector<std::string>{
                            "prompt: Insert tool 3 into the spindle, then press Continue",
                            "continue (--yes)"}));
  EXPECT_TRUE(turn.press_continue);
  // Still waiting a poll later: the same prompt, not pressed twice.
  EXPECT_FALSE(watch.observe(status, {3, true, true, false}).press_continue);
  // The next prompt, with no poll seeing the wait end between the two.
  status = said(status, 3, 5, {{"prompt", "Jog it closer"}});
  EXPECT_TRUE(watch.observe(status, {3, true, true, false}).press_continue);

  status = said(status, 1, 0, {{"info", "tool 3 measured 24.999 mm, in pocket 3"}});
  turn = watch.observe(status, {1, false, false, false});
  EXPECT_EQ(turn.lines, std::vector<std::string>{"info: tool 3 measured 24.999 mm, in pocket 3"});
  EXPECT_EQ(turn.outcome, OperatorOutcome::done);
}

TEST(OperatorWatch, shouldWaitAtAPromptWithoutYes) {
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::unload, 2}, false, 0);
  status = said(status, 4, 5, {{"prompt", "Remove tool 2 from the spindle"}});
  const auto turn = watch.observe(status, {4, true, true, false});
  EXPECT_FALSE(turn.press_continue);
  EXPECT_FALSE(turn.outcome);
  EXPECT_EQ(turn.lines, std::vector<std::string>{"prompt: Remove tool 2 from the spindle"});
}

TEST(OperatorWatch, shouldEndRefusedWhenTheComponentRefusesAndNothingStarted) {
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::load, 9}, true, 0);
  status = said(status, 1, 0,
                {{"error", "load of tool 9 refused: tool 9 is in no pocket of the rack"}});
  EXPECT_EQ(watch.observe(status, {1, false, false, false}).outcome, OperatorOutcome::refused);
}

TEST(OperatorWatch, shouldEndCancelledWhenAnotherInvocationCancels) {
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::load, 3}, false, 0);
  status = said(status, 3, 5, {{"prompt", "Insert tool 3"}});
  EXPECT_FALSE(watch.observe(status, {3, true, true, false}).outcome);
  status = said(status, 1, 0, {{"info", "load of tool 3 cancelled, nothing measured; …"}});
  EXPECT_EQ(watch.observe(status, {1, false, false, false}).outcome, OperatorOutcome::cancelled);
}

TEST(OperatorWatch, shouldEndFailedWhenTheFlowSaidAnErrorAndEndedIdle) {
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::load, 1}, true, 0);
  status = said(status, 3, 2, {{"info", "probing tool 1"}});
  EXPECT_FALSE(watch.observe(status, {3, false, true, false}).outcome);
  status = said(
      status, 1, 0,
      {{"error", "probe: tool 1 did not touch the sensor before probe_limit; nothing written"}});
  const auto turn = watch.observe(status, {1, false, false, false});
  EXPECT_EQ(turn.outcome, OperatorOutcome::failed);
  EXPECT_EQ(operator_exit_status(*turn.outcome), 7);
  EXPECT_STREQ(outcome_word(*turn.outcome), "failed");
}

TEST(OperatorWatch, shouldEndInFaultWhenTheChangerFaults) {
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::measure_all, 0}, true, 0);
  status = said(status, 6, 1, {});
  EXPECT_FALSE(watch.observe(status, {6, false, true, false}).outcome);
  status = said(status, 5, 0, {{"error", "fault: the probe missed"}});
  const auto turn = watch.observe(status, {5, false, false, true});
  EXPECT_EQ(turn.outcome, OperatorOutcome::fault);
  EXPECT_EQ(turn.lines, std::vector<std::string>{"error: fault: the probe missed"});
}

TEST(OperatorWatch, shouldShowTheControlCharactersOfTheStatusFileNotActOnThem) {
  // The status file is anyone's text once written: a message (or its kind) that would clear the
  // screen, recolour it, set the window title or start a line of its own is shown, not obeyed.
  StatusWords status;
  status.state = 1;
  OperatorWatch watch({Action::unload, 2}, false, 0);
  status =
      said(status, 4, 5,
           {{"prompt", "\x1b[2J\x1b]0;owned\x07Remove tool 2\r\noutcome: done (exit 0)"},
            {"info\x1b[31m", std::string("C1 \xc2\x9b") + "31m, DEL \x7f, a tab\there, \xff"}});
  const auto turn = watch.observe(status, {4, true, true, false});
  EXPECT_EQ(turn.lines,
            (std::vector<std::string>{
                "prompt: \\x1b[2J\\x1b]0;owned\\x07Remove tool 2\\r\\noutcome: done (exit 0)",
                "info\\x1b[31m: C1 \\u{009b}31m, DEL \\x7f, a tab\\there, \\xff"}));
}

TEST(OperatorWatch, shouldWaitForAStatusFileItCanRead) {
  OperatorWatch watch({Action::load, 3}, true, 0);
  EXPECT_FALSE(watch.observe(std::nullopt, {3, true, true, false}).outcome);
}

TEST(OperatorWatch, shouldEndContinueAndClearFaultOnceTaken) {
  StatusWords status;
  status.state = 3;
  OperatorWatch go({Action::continue_prompt, 0}, false, 0);
  EXPECT_FALSE(go.observe(status, {3, true, true, false}).outcome);
  EXPECT_EQ(go.observe(status, {3, false, true, false}).outcome, OperatorOutcome::done);

  status.state = 5;
  OperatorWatch clear({Action::clear_fault, 0}, false, 0);
  EXPECT_FALSE(clear.observe(status, {5, false, false, true}).outcome);
  status = said(status, 5, 0,
                {{"error", "clear fault refused: say whether pocket 3 holds its tool"}});
  EXPECT_EQ(clear.observe(status, {5, false, false, true}).outcome, OperatorOutcome::refused);
}

}  // namespace
}  // namespace fatc::io
