#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "core/protocol/executor_link.hpp"
#include "core/machine/base/status.hpp"
#include "core/motion/step.hpp"

// The numeric codes the core shares with the NGC step executor and the panel
// are written once in each language; these tests hold the copies to the C++
// enums (docs/sequences.md#step-kinds and #codes).

namespace fatc {
namespace {

const char* const kExecutor = "nc_files/fixed_atc_probe_execute.ngc";
const char* const kRemap = "nc_files/fixed_atc_probe_m6.ngc";
const char* const kRelease = "nc_files/fixed_atc_probe_chuck_release.ngc";
const char* const kClamp = "nc_files/fixed_atc_probe_chuck_clamp.ngc";
const char* const kPanel = "hal/fixed_atc_probe_panel.py";

/// A code as the C++ side has it: the enumerator's spelling and its value.
struct Code {
  std::string cpp;
  int value;
};
using Codes = std::map<std::string, Code>;  ///< by the name the other file uses

// The names the NGC and the panel use, mapped explicitly to the enumerators.
const Codes kStepKinds = {
    {"resync", {"StepKind::resync", static_cast<int>(StepKind::resync)}},
    {"rapid", {"StepKind::rapid", static_cast<int>(StepKind::rapid)}},
    {"feed", {"StepKind::feed", static_cast<int>(StepKind::feed)}},
    {"probe", {"StepKind::probe", static_cast<int>(StepKind::probe)}},
    {"set_tool_length", {"StepKind::set_tool_length", static_cast<int>(StepKind::set_tool_length)}},
    {"set_spindle_tool",
     {"StepKind::set_spindle_tool", static_cast<int>(StepKind::set_spindle_tool)}},
    {"wait_operator", {"StepKind::wait_operator", static_cast<int>(StepKind::wait_operator)}},
    {"done", {"StepKind::done", static_cast<int>(StepKind::done)}},
    {"fail", {"StepKind::fail", static_cast<int>(StepKind::fail)}},
    {"spindle", {"StepKind::spindle", static_cast<int>(StepKind::spindle)}},
};
const Codes kAxes = {
    {"x", {"axis_x", static_cast<int>(axis_x)}},
    {"y", {"axis_y", static_cast<int>(axis_y)}},
    {"z", {"axis_z", static_cast<int>(axis_z)}},
    {"xy", {"axis_xy", static_cast<int>(axis_xy)}},
    {"xyz", {"axis_xyz", static_cast<int>(axis_xyz)}},
};
const Codes kVia = {
    {"up", {"Via::up", static_cast<int>(Via::up)}},
    {"across", {"Via::across", static_cast<int>(Via::across)}},
};
const Codes kPhases = {
    {"not_ready", {"Phase::not_ready", static_cast<int>(Phase::not_ready)}},
    {"idle", {"Phase::idle", static_cast<int>(Phase::idle)}},
    {"changing", {"Phase::changing", static_cast<int>(Phase::changing)}},
    {"loading", {"Phase::loading", static_cast<int>(Phase::loading)}},
    {"unloading", {"Phase::unloading", static_cast<int>(Phase::unloading)}},
    {"fault", {"Phase::fault", static_cast<int>(Phase::fault)}},
    {"measuring", {"Phase::measuring", static_cast<int>(Phase::measuring)}},
    {"verifying", {"Phase::verifying", static_cast<int>(Phase::verifying)}},
    {"chuck", {"Phase::chuck", static_cast<int>(Phase::chuck)}},
    {"air_run", {"Phase::air_run", static_cast<int>(Phase::air_run)}},
    {"touching", {"Phase::touching", static_cast<int>(Phase::touching)}},
};
const Codes kAwaiting = {
    {"nothing", {"Awaiting::nothing", static_cast<int>(Awaiting::nothing)}},
    {"motion", {"Awaiting::motion", static_cast<int>(Awaiting::motion)}},
    {"probe", {"Awaiting::probe", static_cast<int>(Awaiting::probe)}},
    {"timer", {"Awaiting::timer", static_cast<int>(Awaiting::timer)}},
    {"spindle", {"Awaiting::spindle", static_cast<int>(Awaiting::spindle)}},
    {"operator_choice", {"Awaiting::operator_choice", static_cast<int>(Awaiting::operator_choice)}},
    {"sensor", {"Awaiting::sensor", static_cast<int>(Awaiting::sensor)}},
};

/// One group of codes in a file: the prefix its names carry there, what they
/// mean in C++, and which of them the file must define.
struct Group {
  std::string prefix;  ///< as written in the file: "step_", "STEP_", "PHASE_" ...
  const Codes* codes;
  std::vector<std::string> required;
};

std::vector<std::string> all_of(const Codes& codes) {
  std::vector<std::string> names;
  for (const auto& entry : codes) names.push_back(entry.first);
  return names;
}

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

std::vector<std::string> read_lines(const std::string& relative) {
  std::ifstream in(std::string(FATC_SOURCE_DIR) + "/" + relative);
  std::vector<std::string> lines;
  if (!in) {
    ADD_FAILURE() << relative << ": cannot be read under " << FATC_SOURCE_DIR;
    return lines;
  }
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// How a file defines a code: the line's pattern (capturing the name with
/// its prefix, and the value) and how a name is shown in messages.
struct Syntax {
  std::regex definition;
  std::string open;   ///< written before the name: "#<" in NGC
  std::string close;  ///< written after it: ">" in NGC
};

// `#<step_rapid> = 1`, optionally followed by a comment. NGC names ignore case.
const Syntax kNgc{
    std::regex(R"(\s*#<\s*((?:step|axes|via)_\w+)\s*>\s*=\s*([-+]?[\w.]+)\s*(?:\(.*\))?\s*)",
               std::regex::icase),
    "#<", ">"};
// `STEP_RAPID = 1`, optionally followed by a comment.
const Syntax kPython{std::regex(R"(((?:STEP|PHASE|AWAITING)_\w+)\s*=\s*([-+]?[\w.]+)\s*(?:#.*)?)"),
                     "", ""};

/// A name defined in a file: `written` as the file shows it, its value text.
struct Definition {
  std::string written;
  std::string value;
};

/// Checks every definition `syntax` finds in `file` against `groups`, and
/// that each group's required names are there. The name after the group's
/// prefix, lowercased, is looked up in the group's codes.
void check_codes(const std::string& file, const Syntax& syntax, const std::vector<Group>& groups) {
  std::map<std::string, std::map<std::string, Definition>> found;  // prefix -> name -> definition
  for (const std::string& line : read_lines(file)) {
    std::smatch m;
    if (!std::regex_match(line, m, syntax.definition)) continue;
    const std::string written = syntax.open + m[1].str() + syntax.close;
    const std::string value = m[2];
    const Group* group = nullptr;
    for (const Group& g : groups) {
      if (lower(m[1].str()).rfind(lower(g.prefix), 0) == 0) group = &g;
    }
    if (group == nullptr) continue;
    const std::string name = lower(m[1].str().substr(group->prefix.size()));
    if (group->codes->count(name) == 0) {
      ADD_FAILURE() << file << ": " << written << " = " << value
                    << " names no code this test knows; map it to its C++ enumerator here";
      continue;
    }
    if (found[group->prefix].count(name) != 0) {
      ADD_FAILURE() << file << ": " << written << " is defined twice";
      continue;
    }
    found[group->prefix][name] = Definition{written, value};
  }

  for (const Group& group : groups) {
    for (const auto& [name, definition] : found[group.prefix]) {
      const Code& code = group.codes->at(name);
      std::size_t used = 0;
      int value = 0;
      try {
        value = std::stoi(definition.value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != definition.value.size()) {
        ADD_FAILURE() << file << ": " << definition.written << " = " << definition.value
                      << " is not a whole number; " << code.cpp << " is " << code.value;
      } else {
        EXPECT_EQ(value, code.value) << file << ": " << definition.written << " = " << value
                                     << ", but " << code.cpp << " is " << code.value;
      }
    }
    for (const std::string& name : group.required) {
      if (found[group.prefix].count(name) != 0) continue;
      const Code& code = group.codes->at(name);
      const bool capitals = std::isupper(static_cast<unsigned char>(group.prefix.at(0)));
      ADD_FAILURE() << file << ": " << syntax.open << group.prefix
                    << (capitals ? upper(name) : name) << syntax.close << " is not defined; "
                    << code.cpp << " is " << code.value;
    }
  }
}

TEST(Codes, shouldMatchTheCoreWhenTheExecutorNamesAStepKindOrAxes) {
  // Every step kind: the executor must know each one the component can publish.
  check_codes(kExecutor, kNgc,
              {{"step_", &kStepKinds, all_of(kStepKinds)},
               {"axes_", &kAxes, {"x", "y", "z", "xy"}},
               {"via_", &kVia, {"across"}}});
}

TEST(Codes, shouldMatchTheCoreWhenThePanelNamesAPhaseAwaitingOrStepKind) {
  check_codes(
      kPanel, kPython,
      {{"PHASE_", &kPhases, all_of(kPhases)},
       {"AWAITING_", &kAwaiting, all_of(kAwaiting)},
       {"STEP_", &kStepKinds,
        {"rapid", "feed", "probe", "set_tool_length", "set_spindle_tool", "spindle"}}});
}

TEST(Codes, shouldCompareByNameWhenTheExecutorTestsAStepKindOrAxes) {
  // A bare number in a comparison would be a second copy of the code.
  const std::regex bare(R"(#<\s*(kind|axes)\s*>\s*(EQ|NE)\s*-?[0-9])", std::regex::icase);
  int line_number = 0;
  for (const std::string& line : read_lines(kExecutor)) {
    ++line_number;
    EXPECT_FALSE(std::regex_search(line, bare))
        << kExecutor << ":" << line_number << ": compares with a bare number: " << line;
  }
}

/// One o<fixed_atc_probe_execute> call in `file`, with the code `expected`.
void expect_one_call(const std::string& file, ExecutorCall expected, const char* name) {
  const std::regex call(R"(\s*o<fixed_atc_probe_execute>\s+call\s+\[\s*(-?[0-9]+)\s*\].*)",
                        std::regex::icase);
  int calls = 0;
  for (const std::string& line : read_lines(file)) {
    std::smatch m;
    if (!std::regex_match(line, m, call)) continue;
    ++calls;
    EXPECT_EQ(std::stoi(m[1]), static_cast<int>(expected))
        << file << ": calls the executor with [" << m[1] << "], but " << name << " is "
        << static_cast<int>(expected);
  }
  EXPECT_EQ(calls, 1) << file << ": expected one o<fixed_atc_probe_execute> call";
}

TEST(Codes, shouldCallTheExecutorAsAToolChangeWhenM6RunsIt) {
  expect_one_call(kRemap, ExecutorCall::tool_change, "ExecutorCall::tool_change");
}

TEST(Codes, shouldCallTheExecutorAsAReleaseOrClampFromTheChuckAtoms) {
  expect_one_call(kRelease, ExecutorCall::chuck_release, "ExecutorCall::chuck_release");
  expect_one_call(kClamp, ExecutorCall::chuck_clamp, "ExecutorCall::chuck_clamp");
}

}  // namespace
}  // namespace fatc
