// Hostile input: every bad config, state or INI file is refused in one clear
// line (JSON path or INI key, what was expected, what was found), within a
// second, never with a crash, a hang or a silent acceptance. The corpus files
// are made by make_hostile_corpus.py; FIFOs, /dev/zero, directories and
// megabyte files are made here at run time.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <iostream>
#include <set>

#include "core/config/config.hpp"
#include "core/config/json_text.hpp"
#include "core/config/quote.hpp"
#include "core/rack/tool_state.hpp"
#include "io/files.hpp"
#include "linuxcnc/offline/ini.hpp"
#include "linuxcnc/offline/machine_ini.hpp"
#include "test_config.hpp"

namespace fatc {
namespace {

using Clock = std::chrono::steady_clock;

/// One corpus file and the start of the message it must give, after "PATH: ".
struct Hostile {
  const char* file;
  const char* expected;
};

std::ostream& operator<<(std::ostream& out, const Hostile& hostile) { return out << hostile.file; }

std::string test_name(const ::testing::TestParamInfo<Hostile>& info) {
  std::string name = info.param.file;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

/// The messages a reader gave for a file; empty when it accepted it.
using ReadFile = std::function<std::vector<std::string>(const std::string& path)>;

std::vector<std::string> read_config(const std::string& path) {
  return io::load_config_file(path).errors;
}

std::vector<std::string> read_state(const std::string& path) {
  const auto result = io::load_state_file(path, test::valid_config());
  if (result.state) return {};
  return {result.error};
}

std::vector<std::string> read_ini(const std::string& path) {
  std::string error;
  const auto ini = io::IniFile::read(path, error);
  if (!ini) return {error};
  // As --check says them: what its #INCLUDE lines gave first, then the keys.
  std::vector<std::string> said;
  for (const program::Finding& problem : ini->include_problems()) {
    said.push_back(problem.where.file + ": line " + std::to_string(problem.where.line) + ": " +
                   problem.text);
  }
  if (!io::soft_limits(*ini, Units::mm, error)) said.push_back(error);
  for (const std::string& problem : io::executor_problems(*ini, nullptr)) said.push_back(problem);
  for (const std::string& move : io::builtin_m6_moves(*ini)) said.push_back(path + ": " + move);
  return said;
}

/// Runs `read` on `path`; fails the test if it took a second or more. A reader
/// that blocks for good ends the whole run: better than a hung test.
std::vector<std::string> read_within_a_second(const ReadFile& read, const std::string& path) {
  const auto start = Clock::now();
  auto future = std::async(std::launch::async, read, path);
  if (future.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
    std::cerr << "reading " << path << " blocked for 10 s\n";
    std::abort();
  }
  const auto messages = future.get();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_LT(seconds, 1.0) << path << " took " << seconds << " s";
  return messages;
}

/// The first message must start with "PATH: EXPECTED"; every message is one
/// line of reasonable length.
void expect_refused(const std::vector<std::string>& messages, const std::string& path,
                    const std::string& expected) {
  ASSERT_FALSE(messages.empty()) << path << " was accepted";
  EXPECT_EQ(messages.front().rfind(path + ": " + expected, 0), 0u)
      << "expected \"" << path << ": " << expected << "\"\n     got \"" << messages.front() << "\"";
  EXPECT_LE(messages.size(), 21u);
  for (const auto& message : messages) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(message.size(), path.size() + 400) << message;
  }
}

// ---------------------------------------------------------------- the corpus

/// Fifty-eight k's, a key of deep_duplicate_long_keys.json without its number.
#define K58 "kkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkkk"

// clang-format off
const Hostile kBadConfigs[] = {
  // numbers beyond a double
  {"overflow_chuck_seconds.json", "line 11, column 24: invalid JSON: number overflow parsing '1e309'"},
  {"overflow_negative_pocket.json", "line 39, column 17: invalid JSON: number overflow parsing '-1e400'"},
  {"overflow_integer_digits.json", "line 51, column 418: invalid JSON: number overflow parsing '100000000000000000000000000000000000000000000000000000000000\u2026'"},
  // nesting
  {"deep_arrays.json", "line 1, column 76: nested deeper than 64 levels"},
  {"deep_objects.json", "line 1, column 389: nested deeper than 64 levels"},
  {"deep_unclosed.json", "line 1, column 65: nested deeper than 64 levels"},
  // duplicate keys
  {"duplicate_top_key.json", "chuck_seconds: appears twice"},
  {"duplicate_pocket.json", "pockets.2: appears twice"},
  {"duplicate_axis.json", "safe.x: appears twice"},
  // NUL bytes
  {"nul_byte.json", "line 2, column 15: expected text, found a NUL byte"},
  {"nul_after_object.json", "line 62, column 1: expected text, found a NUL byte"},
  // positive but meaningless, or overflowing
  {"side_offset_tiny.json", "pocket_side_offset: must be at least 0.1 mm long (x and y combined), got 1e-300"},
  {"feed_denormal.json", "probe_latch_feed: must be from 0.01 to 100000 mm/min, got 4.94066e-324"},
  {"latch_above_seek.json", "probe_latch_feed: must not be above probe_seek_feed (3000), got 4000"},
  {"timeout_overflows.json", "spindle_stop_timeout_seconds: must be from 0.01 to 3600 seconds, got 1e+10"},
  {"chuck_seconds_huge.json", "chuck_seconds: must be from 0.01 to 60 seconds, got 1e+300"},
  {"flush_pulse_huge.json", "flush.pulse_seconds: must be from 0.01 to 60 seconds, got 1e+20"},
  {"flush_pulses_huge.json", "flush.pulses: must be a whole number from 0 to 20, got 1e+09"},
  {"coordinate_huge.json", "safe.z: must be from -100000 to 100000 mm, got 1e+308"},
  {"pocket_plus_offset_overflows.json", "pocket_above_clearance_offset_z: must be from 0.001 to 1000 mm, got 1.7e+308"},
  {"clearance_offset_huge.json", "pocket_above_clearance_offset_z: must be from 0.001 to 1000 mm, got 1e+308"},
  {"tolerance_tiny.json", "probe_check_tolerance: must be from 0.0001 to 100 mm, got 1e-300"},
  {"margin_huge.json", "rack_keepout_margin: must be from 1 to 1000 mm, got 1e+300"},
  // a keep-out too narrow to catch a move through a holder
  {"margin_zero.json", "rack_keepout_margin: must be from 1 to 1000 mm, got 0"},
  {"margin_tiny.json", "rack_keepout_margin: must be from 1 to 1000 mm, got 1e-09"},
  {"margin_default_below_floor.json", "rack_keepout_margin: missing, and its default, half the side offset (0.75), is below 1 mm: give the tool holder's half-width"},
  {"retract_denormal.json", "probe_retract_offset_z: must be from 0.001 to 1000 mm, got 4.94066e-324"},
  {"backoff_huge.json", "probe_backoff: must be from 0.001 to 1000 mm, got 1e+06"},
  {"length_offset_huge.json", "probe_length_compensation_offset: must be from -100000 to 100000 mm, got -1e+200"},
  {"side_component_huge.json", "pocket_side_offset.x: must be from -1000 to 1000 mm, got 1e+300"},
  {"integer_beyond_64_bits.json", "chuck_seconds: must be from 0.01 to 60 seconds, got 1.23457e+29"},
  {"too_many_pockets.json", "pockets: must hold at most 200 pockets, got 201"},
  {"clearance_below_chuck.json", "pocket_above_clearance_offset_z: must be above pocket_above_chuck_offset_z (20), got 10"},
  // user text echoed: escaped, cut short
  {"escape_sequence_key.json", "\\x1b[31mred\\x1b[0m: unknown key"},
  {"escape_sequence_value.json", "units: expected \"mm\" or \"inch\", got \"\\x1b]0;pwned\\x07mm\""},
  {"c1_control_value.json", "units: expected \"mm\" or \"inch\", got \"\\u{009b}31mmm\""},
  {"bidi_override_value.json", "units: expected \"mm\" or \"inch\", got \"\\u{202e}mm\""},
  {"bidi_isolate_key.json", "\\u{2067}safe\\u{2069}: unknown key"},
  {"tag_characters_value.json", "units: expected \"mm\" or \"inch\", got \"mm\\u{e0041}\\u{e007f}\""},
  {"soft_hyphen_value.json", "probe_after_change: expected \"off\", \"always\", \"new\", \"never\", \"check\" or \"measure\", got \"mea\\u{00ad}sure\""},
  {"zero_width_key.json", "chuck_seconds\\u{200b}: unknown key, did you mean \"chuck_seconds\"?"},
  {"deep_duplicate_long_keys.json", "\u2026kkkkkkkkkkkkk56." K58 "57." K58 "58." K58 "59.x: appears twice"},
  {"newline_in_pocket_key.json", "pockets.1\\n2: the key must be a pocket number"},
  {"long_string_value.json", "probe_after_change: expected \"off\", \"always\", \"new\", \"never\", \"check\" or \"measure\", got \"xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx\u2026\""},
  {"long_unterminated_string.json", "line 1, column 20012: invalid JSON: syntax error while parsing value - invalid string: missing closing quote; last read: '\"mmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmmm\u2026'"},
  {"many_unknown_keys.json", "key0: unknown key"},
  // syntax and types
  {"empty.json", "line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of input"},
  {"top_level_array.json", "config: expected a JSON object at the top, got an array"},
  {"top_level_string.json", "config: expected a JSON object at the top, got \"config\""},
  {"truncated.json", "line 28, column 7: invalid JSON: syntax error while parsing object key - invalid string: missing closing quote"},
  {"trailing_garbage.json", "line 62, column 1: invalid JSON: syntax error while parsing value - invalid literal"},
  {"comment.json", "line 1, column 1: invalid JSON: syntax error while parsing value - invalid literal; last read: '/'"},
  {"invalid_utf8.json", "line 2, column 14: invalid JSON: syntax error while parsing value - invalid string: ill-formed UTF-8 byte; last read: '\"m\\xff'"},
  {"lone_surrogate.json", "line 2, column 19: invalid JSON: syntax error while parsing value - invalid string: surrogate U+D800..U+DBFF must be followed by U+DC00..U+DFFF"},
  {"nan_literal.json", "line 11, column 20: invalid JSON: syntax error while parsing value - invalid literal"},
  {"infinity_literal.json", "line 11, column 21: invalid JSON: syntax error while parsing value - invalid number"},
  {"tool_number_too_big.json", "pockets.99999999999: the key must be a pocket number"},
  {"units_number.json", "units: expected \"mm\" or \"inch\", got 25.4"},
  {"pockets_string.json", "pockets: expected an object, got \"1,2,3\""},
  {"pocket_default_array.json", "pocket_default: expected an object, got an array"},
  // the optional sensors and their timeout, the probe window
  {"sensors_not_object.json", "sensors: expected an object, got \"all\""},
  {"sensors_unknown_key.json", "sensors.toolpresent: unknown key, did you mean \"tool_present\"?"},
  {"sensors_not_bool.json", "sensors.air_pressure: expected true or false, got \"yes\""},
  {"sensors_null.json", "sensors.tool_present: expected true or false, got null"},
  {"sensors_pocket_missing.json", "sensors.pocket_occupancy[1]: pocket 9 is not in pockets"},
  {"sensors_pocket_twice.json", "sensors.pocket_occupancy[1]: pocket 2 is listed twice"},
  {"sensors_pocket_negative.json", "sensors.pocket_occupancy[0]: expected a pocket number (1 to 999999999), got -3"},
  {"sensors_pocket_string.json", "sensors.pocket_occupancy: expected true, false or a list of pockets like [1, 2], got \"all\""},
  {"sensor_timeout_negative.json", "sensor_timeout_seconds: must be from 0.01 to 60 seconds, got -1"},
  {"sensor_timeout_huge.json", "sensor_timeout_seconds: must be from 0.01 to 60 seconds, got 1e+10"},
  {"sensor_timeout_string.json", "sensor_timeout_seconds: expected a number, got \"1s\""},
  {"probe_window_zero.json", "probe_window: must be from 0.001 to 1000 mm, got 0"},
  {"probe_window_below_tolerance.json", "probe_window: must be larger than probe_check_tolerance (0.1: its default, left out), got 0.05"},
  {"sensor_in_rack.json", "probe_limit: the touch-off sensor at X152 Y24 lies in the rack's keep-out at pocket 3 (rack_keepout_margin 20): place it clear of the rack"},
};

const Hostile kBadStates[] = {
  {"overflow_length.json", "line 13, column 14: invalid JSON: number overflow parsing '1e309'"},
  {"overflow_spindle.json", "line 3, column 19: invalid JSON: number overflow parsing '-1e400'"},
  {"deep_nesting.json", "line 1, column 90: nested deeper than 64 levels"},
  {"duplicate_spindle.json", "spindle: appears twice"},
  {"duplicate_length.json", "lengths.3: appears twice"},
  {"nul_byte.json", "line 4, column 21: expected text, found a NUL byte"},
  {"length_huge.json", "lengths.1: must be from -100000 to 100000, got 1e+200"},
  {"spindle_fraction.json", "spindle: expected 0 or a tool number, got 2.5"},
  {"spindle_beyond_64_bits.json", "spindle: expected 0 or a tool number, got 18446744073709551615"},
  {"in_pocket_object.json", "in_pocket: expected an array of tool numbers, got an object"},
  {"in_progress_escape.json", "in_progress.step: expected one line of text without control characters, got \"\\x1b[2Jreturning\""},
  {"in_progress_c1.json", "in_progress.step: expected text without invisible or direction-changing characters, got \"\\u{009b}2Jreturning\""},
  {"in_progress_long.json", "in_progress.sequence: expected at most 200 characters, got 9000: \"M6 M6 M6"},
  {"in_progress_text.json", "in_progress: expected an object, got \"M6 T4\""},
  {"in_progress_unknown_key.json", "in_progress.tool: unknown key"},
  {"in_progress_bad_pocket.json", "in_progress.pocket: expected 0 or a pocket number, got -1"},
  {"in_progress_no_step.json", "in_progress.step: missing"},
  {"escape_sequence_key.json", "\\x1b]0;x\\x07: unknown key"},
  {"version_text.json", "version: expected 1 or 2, got \"1\""},
  {"pocket_not_in_config.json", "pockets.99: tool 99 is recorded in pocket 99, which config.json does not have"},
  {"length_key_padded.json", "lengths.01: the key must be a tool number"},
  {"empty.json", "line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of input"},
  {"torn_write.json", "line 11, column 3: invalid JSON: syntax error while parsing array - unexpected end of input"},
  {"top_level_array.json", "state: expected a JSON object, got an array"},
  {"in_progress_pocket_not_in_config.json", "in_progress.pocket: the sequence was cut off at pocket 99, which config.json does not have"},
  {"in_progress_bidi.json", "in_progress.step: expected text without invisible or direction-changing characters, got \"returning tool 3 \\u{202e}to pocket 3\""},
  {"in_progress_tag.json", "in_progress.sequence: expected text without invisible or direction-changing characters, got \"M6 T4\\u{e0001}\""},
};

const Hostile kBadInis[] = {
  {"min_nan.ini", "[AXIS_X]MIN_LIMIT (line 6): expected a finite number from -1e99 to 1e99, got \"nan\""},
  {"max_inf.ini", "[AXIS_Y]MAX_LIMIT (line 10): expected a finite number from -1e99 to 1e99, got \"inf\""},
  {"comma_decimal.ini", "[AXIS_X]MAX_LIMIT (line 7): expected a number, got \"0,5\""},
  {"unit_suffix.ini", "[AXIS_X]MAX_LIMIT (line 7): expected a number, got \"400 mm\""},
  {"trailing_junk.ini", "[AXIS_X]MAX_LIMIT (line 7): expected a number, got \"0abc\""},
  {"inline_comment.ini", "[AXIS_Z]MAX_LIMIT (line 13): expected a number, got \"0 # top of travel\""},
  {"furlong.ini", "[TRAJ]LINEAR_UNITS (line 4): expected mm, metric, in, inch, imperial or machine units per mm, got \"furlong\""},
  {"min_above_max.ini", "[AXIS_Z]MIN_LIMIT (line 12): must not be above MAX_LIMIT (-50), got 0"},
  {"no_linear_units.ini", "[TRAJ]LINEAR_UNITS: missing (LinuxCNC does not start without it"},
  {"no_axis_z.ini", "[AXIS_Z]MIN_LIMIT: missing or empty"},
  {"nul_byte.ini", "line 10, column 14: expected text, found a NUL byte"},
  {"lone_carriage_return.ini", "line 10, column 16: expected a line ending, found a carriage return inside a line"},
  {"overflow.ini", "[AXIS_Z]MIN_LIMIT (line 12): expected a number, got \"-1e999\""},
  {"beyond_no_limit.ini", "[AXIS_Z]MIN_LIMIT (line 12): expected a finite number from -1e99 to 1e99, got \"-1e200\""},
  {"escape_sequence_value.ini", "[AXIS_X]MAX_LIMIT (line 7): expected a number, got \"\\x1b[31m400\""},
  {"c1_control_value.ini", "[AXIS_X]MAX_LIMIT (line 7): expected a number, got \"\\u{009b}31m400\""},
  {"empty.ini", "[TRAJ]LINEAR_UNITS: missing (LinuxCNC does not start without it: mm, inch, ...)"},
  {"linear_units_zero.ini", "[TRAJ]LINEAR_UNITS (line 4): expected machine units per mm from 0.001 to 1000, got \"0\""},
  {"linear_units_nan.ini", "[TRAJ]LINEAR_UNITS (line 4): expected machine units per mm from 0.001 to 1000, got \"nan\""},
  {"linear_units_with_junk.ini", "[TRAJ]LINEAR_UNITS (line 4): expected mm, metric, in, inch, imperial or machine units per mm, got \"1.0 mm\""},
  {"empty_value.ini", "[AXIS_Y]MAX_LIMIT: missing or empty"},
  {"return_to_xy_bidi.ini", "[FIXED_ATC_PROBE]RETURN_TO_XY (line 17): expected 0 or 1 (halcmd setp of a bit), got \"\\u{202e}1\""},
  {"step_timeout_soft_hyphen.ini", "[FIXED_ATC_PROBE]STEP_TIMEOUT (line 24): expected seconds, 1 or more, got \"3\\u{00ad}0\""},
  {"analog_out_twice_escape.ini", "[FIXED_ATC_PROBE]PROBE_Z_OUT (line 21): expected two digits as in the motion pin names (03), got \"\\x1b[8m\""},
  // the INI as the linuxcnc script expands its #INCLUDE lines, each said at the INI's line
  {"include_missing.ini", "line 5: #INCLUDE " FATC_BAD_INIS "/gone_axes.inc: cannot open (No such file or directory): none of its keys are read"},
  {"include_nested.ini", "line 5: #INCLUDE \"nested_axes.inc\": its line 1 is an #INCLUDE, which the linuxcnc script expands only in the INI itself: LinuxCNC reads nothing of the file it names; move it into the INI"},
  {"include_shell.ini", "line 5: #INCLUDE \"$(cat axes.inc)\": the linuxcnc script evaluates the name with the shell (eval echo), which this reader does not: write the file's name plainly (~, $NAME and ${NAME} are read)"},
  {"include_no_line_end.ini", "line 5: #INCLUDE \"axes_no_line_end.inc\": its line 9 has no line end: the linuxcnc script writes its end mark onto it (\"#*** End\"); end the file with one"},
  {"include_itself.ini", "line 1: #INCLUDE \"include_itself.ini\": its line 1 is an #INCLUDE, which the linuxcnc script expands only in the INI itself"},
  {"include_indented.ini", "line 5: #INCLUDE after a blank, and no #INCLUDE at a line's start: the linuxcnc script takes the line for a comment and includes nothing; start the line with it"},
  {"include_dev_zero.ini", "line 5: #INCLUDE /dev/zero: expected a regular file, got a character device: none of its keys are read"},
  // LinuxCNC's own M6, which the changer's remap calls, moving after every change
  {"tool_change_position.ini", "[EMCIO]TOOL_CHANGE_POSITION (line 15): LinuxCNC's own M6, which fixed_atc_probe_m6 calls once the change is done, would rapid to \"0 0 0\" after every change, from safe; remove it: the changer ends its change at safe"},
};
// clang-format on

class BadConfigFiles : public ::testing::TestWithParam<Hostile> {};
class BadStateFiles : public ::testing::TestWithParam<Hostile> {};
class BadIniFiles : public ::testing::TestWithParam<Hostile> {};

TEST_P(BadConfigFiles, shouldBeRefusedInOneClearLineWithinASecond) {
  const std::string path = std::string(FATC_BAD_CONFIGS "/") + GetParam().file;
  expect_refused(read_within_a_second(read_config, path), path, GetParam().expected);
}

TEST_P(BadStateFiles, shouldBeRefusedInOneClearLineWithinASecond) {
  const std::string path = std::string(FATC_BAD_STATES "/") + GetParam().file;
  expect_refused(read_within_a_second(read_state, path), path, GetParam().expected);
}

TEST_P(BadIniFiles, shouldBeRefusedInOneClearLineWithinASecond) {
  const std::string path = std::string(FATC_BAD_INIS "/") + GetParam().file;
  expect_refused(read_within_a_second(read_ini, path), path, GetParam().expected);
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadConfigFiles, ::testing::ValuesIn(kBadConfigs), test_name);
INSTANTIATE_TEST_SUITE_P(Corpus, BadStateFiles, ::testing::ValuesIn(kBadStates), test_name);
INSTANTIATE_TEST_SUITE_P(Corpus, BadIniFiles, ::testing::ValuesIn(kBadInis), test_name);

template <std::size_t N>
std::set<std::string> listed(const Hostile (&table)[N]) {
  std::set<std::string> names;
  for (const auto& hostile : table) names.insert(hostile.file);
  return names;
}

std::set<std::string> files_in(const std::string& folder, const std::string& extension) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() == extension) names.insert(entry.path().filename().string());
  }
  return names;
}

TEST(HostileCorpus, shouldHaveAnExpectedMessageForEveryFile) {
  EXPECT_EQ(files_in(FATC_BAD_CONFIGS, ".json"), listed(kBadConfigs));
  EXPECT_EQ(files_in(FATC_BAD_STATES, ".json"), listed(kBadStates));
  EXPECT_EQ(files_in(FATC_BAD_INIS, ".ini"), listed(kBadInis));
  EXPECT_GE(std::size(kBadConfigs), 40u);
  EXPECT_GE(std::size(kBadStates), 15u);
  EXPECT_GE(std::size(kBadInis), 10u);
}

// ------------------------------------------- files that are not files, made here

class NotAFile : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_hostile_XXXXXX";
    folder_ = ::mkdtemp(pattern);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }

  std::string fifo() {
    const std::string path = folder_ + "/fifo";
    EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    return path;
  }
  std::string huge() {
    const std::string path = folder_ + "/huge";
    std::ofstream(path).close();
    EXPECT_EQ(::truncate(path.c_str(), 2 * 1024 * 1024), 0);  // sparse: nothing written
    return path;
  }
  std::string folder_;
};

const std::pair<const char*, ReadFile> kReaders[] = {
    {"config", read_config}, {"state", read_state}, {"ini", read_ini}};

TEST_F(NotAFile, shouldRefuseAFifoWithoutWaitingForAWriter) {
  const std::string path = fifo();
  for (const auto& [name, read] : kReaders) {
    SCOPED_TRACE(name);
    expect_refused(read_within_a_second(read, path), path, "expected a regular file, got a FIFO");
  }
}

TEST_F(NotAFile, shouldRefuseDevZeroWithoutReadingIt) {
  for (const auto& [name, read] : kReaders) {
    SCOPED_TRACE(name);
    expect_refused(read_within_a_second(read, "/dev/zero"), "/dev/zero",
                   "expected a regular file, got a character device");
  }
}

TEST_F(NotAFile, shouldRefuseADirectory) {
  for (const auto& [name, read] : kReaders) {
    SCOPED_TRACE(name);
    expect_refused(read_within_a_second(read, folder_), folder_,
                   "expected a regular file, got a directory");
  }
}

TEST_F(NotAFile, shouldRefuseAFileOverOneMebibyte) {
  const std::string path = huge();
  for (const auto& [name, read] : kReaders) {
    SCOPED_TRACE(name);
    expect_refused(read_within_a_second(read, path), path,
                   "expected a file of at most 1 MiB, got 2097152 bytes");
  }
}

TEST_F(NotAFile, shouldRefuseAnEmptyPath) {
  for (const auto& [name, read] : {kReaders[0], kReaders[2]}) {
    SCOPED_TRACE(name);
    const auto messages = read(std::string());
    ASSERT_EQ(messages.size(), 1u);
    EXPECT_EQ(messages[0], "\"\" (an empty path): expected a file path, got nothing");
  }
}

TEST_F(NotAFile, shouldEscapeControlCharactersInAPath) {
  const std::string path = folder_ + "/\x1b[2Jconfig.json";
  const auto messages = read_config(path);
  ASSERT_EQ(messages.size(), 1u);
  EXPECT_EQ(messages[0], folder_ + "/\\x1b[2Jconfig.json: cannot open (No such file or directory)");
}

// ------------------------------------------- megabyte cases, made here

/// A valid config with `extra` put in at the top level.
std::string config_with(const std::string& extra) {
  std::string text = test::kValidConfig;
  text.insert(text.rfind('}'), "," + extra);
  return text;
}

ConfigResult parse_within_a_second(const std::string& text) {
  const auto start = Clock::now();
  ConfigResult result = parse_config(text);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
  return result;
}

TEST(HugeInput, shouldCutAMegabyteKeyShortInTheMessage) {
  const auto result =
      parse_within_a_second(config_with("\"" + std::string(1000000, 'k') + "\": 1"));
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0], std::string(60, 'k') + "\u2026: unknown key");
}

TEST(HugeInput, shouldListTwentyOfAHundredThousandUnknownKeysAtOnce) {
  std::string keys;
  for (int i = 0; i < 100000; ++i) keys += (i ? ",\"k" : "\"k") + std::to_string(i) + "\":1";
  const auto result = parse_within_a_second(config_with(keys));
  ASSERT_EQ(result.errors.size(), 21u);
  EXPECT_EQ(result.errors.back(), "and 99980 more problems");
}

TEST(HugeInput, shouldFindDuplicatesInTimeLinearInTheText) {
  // 60 levels deep, 1,500 keys at each (a file just under 1 MiB): the old
  // tracking spelled out the whole path at every key.
  std::string text;
  for (int level = 0; level < 60; ++level) {
    text += "{";
    for (int k = 0; k < 1500; ++k) text += "\"k" + std::to_string(k) + "\":0,";
    text += "\"next\":";
  }
  text += "0" + std::string(60, '}');
  const auto start = Clock::now();
  const auto parsed = parse_json_text(text);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
  EXPECT_TRUE(parsed.value);
}

TEST(HugeInput, shouldNameTheDuplicateDeepDown) {
  std::string text;
  for (int level = 0; level < 50; ++level) text += "{\"a\":";
  text += "{\"x\":1,\"x\":2}" + std::string(50, '}');
  const auto parsed = parse_json_text(text);
  ASSERT_EQ(parsed.errors.size(), 1u);
  std::string path;
  for (int level = 0; level < 50; ++level) path += "a.";
  EXPECT_EQ(parsed.errors[0], path + "x: appears twice");
}

TEST(HugeInput, shouldNameArrayIndexesInTheDuplicatePath) {
  const auto parsed = parse_json_text(R"({"in_pocket": [1, {"a": 1, "a": 2}]})");
  ASSERT_EQ(parsed.errors.size(), 1u);
  EXPECT_EQ(parsed.errors[0], "in_pocket.1.a: appears twice");
}

TEST(HugeInput, shouldRefuseAMegabyteOfOpeningBracketsAtOnce) {
  const auto result = parse_within_a_second(std::string(1000000, '['));
  ASSERT_EQ(result.errors.size(), 1u);
  EXPECT_EQ(result.errors[0], "line 1, column 65: nested deeper than 64 levels");
}

TEST(HugeInput, shouldAcceptNestingUpToTheLimit) {
  const auto parsed =
      parse_json_text(std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']'));
  EXPECT_TRUE(parsed.value);
  EXPECT_FALSE(
      parse_json_text(std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']'))
          .value);
}

TEST(HugeInput, shouldReadAStateOfAHundredThousandToolsQuickly) {
  std::string tools;
  for (int t = 1; t <= 100000; ++t) tools += (t > 1 ? "," : "") + std::to_string(t);
  const std::string text = R"({"version": 1, "spindle": 0, "uncertain": false, "in_pocket": [)" +
                           tools + R"(], "lengths": {}})";
  const auto start = Clock::now();
  const auto result = tool_state_from_json(text);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
  EXPECT_TRUE(result.state);
}

TEST(HugeInput, shouldReadAnIniOfOneMegabyteLineQuickly) {
  std::string text = "[TRAJ]\nLINEAR_UNITS = mm\n# " + std::string(1000000, 'x') + "\n";
  text += "[AXIS_X]\nMIN_LIMIT = 0\nMAX_LIMIT = 1\n[AXIS_Y]\nMIN_LIMIT = 0\nMAX_LIMIT = 1\n";
  text += "[AXIS_Z]\nMIN_LIMIT = 0\nMAX_LIMIT = 1\n";
  const auto start = Clock::now();
  std::string error;
  const auto ini = io::IniFile::from_text(text, "big.ini", error);
  ASSERT_TRUE(ini) << error;
  EXPECT_TRUE(io::soft_limits(*ini, Units::mm, error)) << error;
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
}

// ------------------------------------------- what LinuxCNC's reader accepts

std::optional<SoftLimits> limits_of(const std::string& text, Units units, std::string& error) {
  const auto ini = io::IniFile::from_text(text, "machine.ini", error);
  if (!ini) return std::nullopt;
  return io::soft_limits(*ini, units, error);
}

std::string machine(const std::string& units, const std::string& x_max) {
  return "[TRAJ]\nLINEAR_UNITS = " + units + "\n[AXIS_X]\nMIN_LIMIT = -1\nMAX_LIMIT = " + x_max +
         "\n[AXIS_Y]\nMIN_LIMIT = -1\nMAX_LIMIT = 1\n[AXIS_Z]\nMIN_LIMIT = -1\nMAX_LIMIT = 1\n";
}

TEST(LinuxCncIni, shouldTakeEveryUnitNameLinuxCncTakes) {
  for (const char* inch : {"inch", "in", "imperial", "Inch", "INCH", "0.03937007874"}) {
    std::string error;
    const auto limits = limits_of(machine(inch, "10"), Units::mm, error);
    ASSERT_TRUE(limits) << inch << ": " << error;
    EXPECT_NEAR(limits->x.max, 254.0, 1e-6) << inch;
  }
  for (const char* mm : {"mm", "metric", "MM", "1.0", "1"}) {
    std::string error;
    const auto limits = limits_of(machine(mm, "10"), Units::inch, error);
    ASSERT_TRUE(limits) << mm << ": " << error;
    EXPECT_NEAR(limits->x.max, 10.0 / 25.4, 1e-9) << mm;
  }
}

TEST(LinuxCncIni, shouldReadTheFirstOfARepeatedKeyAsLinuxCncDoes) {
  std::string text = machine("mm", "10");
  text.insert(text.find("[AXIS_Y]"), "MAX_LIMIT = 99\n");
  std::string error;
  const auto limits = limits_of(text, Units::mm, error);
  ASSERT_TRUE(limits) << error;
  EXPECT_EQ(limits->x.max, 10.0);
}

TEST(LinuxCncIni, shouldAcceptDosLineEndings) {
  std::string text = machine("mm", "10");
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 2)) {
    text.insert(at, "\r");
  }
  std::string error;
  EXPECT_TRUE(limits_of(text, Units::mm, error)) << error;
}

TEST(LinuxCncIni, shouldGetAValueAsTheComponentAsksForNmlFile) {
  std::string error;
  const auto ini = io::IniFile::read(FATC_SOURCE_DIR "/config/sim/fixed_atc_sim.ini", error);
  ASSERT_TRUE(ini) << error;
  EXPECT_EQ(ini->get("EMC", "MACHINE"), "fixed_atc_probe simulated mill");
  EXPECT_FALSE(ini->get("EMC", "NML_FILE"));
  EXPECT_FALSE(ini->get("NO_SUCH_SECTION", "MACHINE"));
}

// ------------------------------------------- the one quoting helper

TEST(Quote, shouldShowControlCharactersAndEscapesVisibly) {
  EXPECT_EQ(quote("a\x1b[31mb\n\t\r\x7f"), "\"a\\x1b[31mb\\n\\t\\r\\x7f\"");
  EXPECT_EQ(quote("say \"hi\" \\o/"), "\"say \\\"hi\\\" \\\\o/\"");
  EXPECT_EQ(escape("say \"hi\""), "say \"hi\"");
}

TEST(Quote, shouldKeepUtf8AndEscapeWhatIsNot) {
  EXPECT_EQ(quote("Fräser ø6"), "\"Fräser ø6\"");
  EXPECT_EQ(quote("bad\xff\xc3"), "\"bad\\xff\\xc3\"");
  EXPECT_EQ(quote("\xc2\x9b"
                  "2J"),
            "\"\\u{009b}2J\"")
      << "C1 control (CSI)";
  EXPECT_EQ(quote("\u202emm"), "\"\\u{202e}mm\"") << "right-to-left override";
  EXPECT_EQ(quote("\xed\xa0\x80"), "\"\\xed\\xa0\\x80\"") << "an encoded surrogate";
  EXPECT_EQ(quote("\xe0\x80\xaf"), "\"\\xe0\\x80\\xaf\"") << "an overlong encoding";
}

/// A character that shows as nothing, hides or reorders text, and how quote() shows it.
struct Invisible {
  const char* name;
  const char* text;
  const char* shown;
};
std::ostream& operator<<(std::ostream& out, const Invisible& c) { return out << c.name; }

class InvisibleCharacter : public ::testing::TestWithParam<Invisible> {};

TEST_P(InvisibleCharacter, shouldBeShownAsAnEscape) {
  EXPECT_EQ(quote(std::string("a") + GetParam().text + "b"),
            std::string("\"a") + GetParam().shown + "b\"");
  EXPECT_TRUE(has_invisible_characters(GetParam().text));
}

// clang-format off
INSTANTIATE_TEST_SUITE_P(Quote, InvisibleCharacter, ::testing::Values(
    Invisible{"left_to_right_embedding", "\u202a", "\\u{202a}"},
    Invisible{"right_to_left_override", "\u202e", "\\u{202e}"},
    Invisible{"left_to_right_isolate", "\u2066", "\\u{2066}"},
    Invisible{"pop_directional_isolate", "\u2069", "\\u{2069}"},
    Invisible{"left_to_right_mark", "\u200e", "\\u{200e}"},
    Invisible{"right_to_left_mark", "\u200f", "\\u{200f}"},
    Invisible{"arabic_letter_mark", "\u061c", "\\u{061c}"},
    Invisible{"zero_width_space", "\u200b", "\\u{200b}"},
    Invisible{"zero_width_joiner", "\u200d", "\\u{200d}"},
    Invisible{"word_joiner", "\u2060", "\\u{2060}"},
    Invisible{"byte_order_mark", "\ufeff", "\\u{feff}"},
    Invisible{"soft_hyphen", "\u00ad", "\\u{00ad}"},
    Invisible{"tag_begin", "\U000e0001", "\\u{e0001}"},
    Invisible{"tag_latin_a", "\U000e0041", "\\u{e0041}"},
    Invisible{"cancel_tag", "\U000e007f", "\\u{e007f}"},
    Invisible{"variation_selector", "\ufe0f", "\\u{fe0f}"},
    Invisible{"hangul_filler", "\u3164", "\\u{3164}"}),
    [](const ::testing::TestParamInfo<Invisible>& info) { return std::string(info.param.name); });
// clang-format on

TEST(Quote, shouldKeepVisibleTextAsItIs) {
  EXPECT_FALSE(has_invisible_characters("Fräser ø6 → T3, 日本"));
  EXPECT_EQ(quote("Fräser ø6 → T3"), "\"Fräser ø6 → T3\"");
}

TEST(MessageLines, shouldCutALineOverFourHundredCharactersAndKeepTheOthers) {
  const std::string fits(400, 'a');
  EXPECT_EQ(capped_lines(fits), fits);
  EXPECT_EQ(capped_lines(std::string(401, 'a') + "\nshort\n"),
            std::string(399, 'a') + "\u2026\nshort\n");
  std::string umlauts;
  for (int i = 0; i < 500; ++i) umlauts += "\u00e4";
  std::string kept;
  for (int i = 0; i < 399; ++i) kept += "\u00e4";
  EXPECT_EQ(capped_lines(umlauts), kept + "\u2026") << "characters, not bytes";
}

TEST(MessageLines, shouldEndALongListWithHowManyMore) {
  using Items = std::vector<std::string>;
  EXPECT_EQ(fatc::listed(Items{"1", "2", "3"}, ", ", 2), "1, 2 \u2026 and 1 more");
  EXPECT_EQ(fatc::listed(Items{"1", "2"}, " ", 2), "1 2");
  EXPECT_EQ(fatc::listed(Items{}), "");
}

TEST(Quote, shouldCutLongTextAtSixtyCharacters) {
  EXPECT_EQ(quote(std::string(60, 'a')), "\"" + std::string(60, 'a') + "\"");
  EXPECT_EQ(quote(std::string(61, 'a')), "\"" + std::string(60, 'a') + "\u2026\"");
  std::string umlauts;
  for (int i = 0; i < 100; ++i) umlauts += "\u00e4";
  std::string sixty;
  for (int i = 0; i < 60; ++i) sixty += "\u00e4";
  EXPECT_EQ(quote(umlauts), "\"" + sixty + "\u2026\"") << "characters, not bytes";
}

}  // namespace
}  // namespace fatc
