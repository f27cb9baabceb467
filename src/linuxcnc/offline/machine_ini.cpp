#include "machine_ini.hpp"

#include <strings.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "core/config/quote.hpp"
#include "core/dry_run/simulator.hpp"
#include "ini.hpp"
#include "io/files.hpp"

namespace fatc::io {

std::vector<std::string> executor_problems(const IniFile& ini, const Config* config) {
  const char* const section = "FIXED_ATC_PROBE";
  struct Key {
    const char* name;
    const char* reader;
  };
  const Key keys[] = {{"CONFIG", "hal/fixed_atc_probe.hal"},
                      {"STATE", "hal/fixed_atc_probe.hal"},
                      {"RETURN_TO_XY", "hal/fixed_atc_probe.hal"},
                      {"MACHINE_ON_SIGNAL", "hal/fixed_atc_probe.hal"},
                      {"STEP_READY_IN", "the HAL snippet and the executor"},
                      {"STEP_REQUEST_OUT", "the HAL snippet and the executor"},
                      {"PROBE_Z_OUT", "the HAL snippet and the executor"},
                      {"PROBE_RESULT_OUT", "the HAL snippet and the executor"},
                      {"EXECUTOR_CALL_OUT", "the HAL snippet and the executor"},
                      {"STEP_TIMEOUT", "the executor (fixed_atc_probe_execute.ngc)"}};
  std::vector<std::string> problems;
  bool any = false;
  for (const Key& key : keys) any = any || ini.get(section, key.name).has_value();
  if (!any) return problems;
  auto where = [&](const char* name) {
    int line = 0;
    ini.get(section, name, line);
    return ini.path() + ": " + key_name(ini, section, name, line);
  };
  for (const Key& key : keys) {
    if (!ini.get(section, key.name)) {
      problems.push_back(where(key.name) + ": missing; " + key.reader + " reads it");
    }
  }
  const char* const pins[] = {"STEP_READY_IN", "STEP_REQUEST_OUT", "PROBE_Z_OUT",
                              "PROBE_RESULT_OUT", "EXECUTOR_CALL_OUT"};
  for (const char* pin : pins) {
    const auto text = ini.get(section, pin);
    if (!text) continue;
    const bool two_digits = text->size() == 2 &&
                            std::isdigit(static_cast<unsigned char>((*text)[0])) &&
                            std::isdigit(static_cast<unsigned char>((*text)[1]));
    if (!two_digits) {
      problems.push_back(where(pin) +
                         ": expected two digits as in the motion pin names (03), got " +
                         quote(*text));
    }
  }
  const char* const analog[] = {"PROBE_Z_OUT", "PROBE_RESULT_OUT", "EXECUTOR_CALL_OUT"};
  for (int a = 0; a < 3; ++a) {
    for (int b = a + 1; b < 3; ++b) {
      const auto first = ini.get(section, analog[a]);
      const auto second = ini.get(section, analog[b]);
      if (first && second && *first == *second) {
        problems.push_back(where(analog[b]) + ": motion.analog-out-" + escape(*second) + " is " +
                           analog[a] + "'s too; each needs its own");
      }
    }
  }
  if (const auto back = ini.get(section, "RETURN_TO_XY"); back && *back != "0" && *back != "1" &&
                                                          strcasecmp(back->c_str(), "true") != 0 &&
                                                          strcasecmp(back->c_str(), "false") != 0) {
    problems.push_back(where("RETURN_TO_XY") + ": expected 0 or 1 (halcmd setp of a bit), got " +
                       quote(*back));
  }
  const auto timeout_text = ini.get(section, "STEP_TIMEOUT");
  if (!timeout_text) return problems;
  const auto timeout = ini.number(section, "STEP_TIMEOUT");
  if (!timeout || !std::isfinite(*timeout) || *timeout < 1.0) {
    problems.push_back(where("STEP_TIMEOUT") + ": expected seconds, 1 or more, got " +
                       quote(*timeout_text));
    return problems;
  }
  if (!config) return problems;
  const double stretch = longest_executor_wait(*config);
  if (stretch >= *timeout) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer,
                  ": %g s is not longer than %g s, the longest the changer may keep the executor "
                  "waiting for a step (its plans with every sensor answering at its timeout, "
                  "spindle_stop_timeout_seconds %g s, and a first grip that fails): the executor "
                  "would stop the program while the changer waits; raise it",
                  *timeout, stretch, config->spindle_stop_timeout_seconds);
    problems.push_back(where("STEP_TIMEOUT") + buffer);
  }
  return problems;
}

std::vector<std::string> builtin_m6_moves(const IniFile& ini) {
  std::vector<std::string> lines;
  auto name = [&](const char* key, const std::string& move) {
    int line = 0;
    ini.get("EMCIO", key, line);
    lines.push_back(key_name(ini, "EMCIO", key, line) +
                    ": LinuxCNC's own M6, which fixed_atc_probe_m6 calls once the change is done, "
                    "would " + move + " after every change, from safe; remove it: the changer "
                    "ends its change at safe");
  };
  if (const auto position = ini.get("EMCIO", "TOOL_CHANGE_POSITION")) {
    name("TOOL_CHANGE_POSITION", "rapid to " + quote(*position));
  }
  // 2.9 reads the switches as whole numbers, 2.10 also as words: one off moves nothing.
  auto on = [&](const char* key) {
    const auto value = ini.get("EMCIO", key);
    if (!value) return false;
    for (const char* off : {"0", "false", "no", "off"}) {
      if (strcasecmp(value->c_str(), off) == 0) return false;
    }
    return true;
  };
  if (on("TOOL_CHANGE_QUILL_UP")) name("TOOL_CHANGE_QUILL_UP", "rapid Z up to machine zero (G53 Z0)");
  if (on("TOOL_CHANGE_AT_G30")) name("TOOL_CHANGE_AT_G30", "rapid to the G30 position");
  return lines;
}

std::string tilde_expanded(const std::string& folder) {
  const char* home = std::getenv("HOME");
  return folder.rfind("~/", 0) == 0 && home ? home + folder.substr(1) : folder;
}

std::vector<int> user_m_codes(const IniFile& ini, const std::string& folder) {
  std::vector<std::string> folders{ini.get("DISPLAY", "PROGRAM_PREFIX").value_or("nc_files")};
  if (const auto path = ini.get("RS274NGC", "USER_M_PATH")) {
    // emctask.cc: strtok on ':' (empty folders skipped), at most five.
    std::size_t start = 0;
    while (start <= path->size() && folders.size() < 6) {
      const std::size_t colon = std::min(path->find(':', start), path->size());
      if (colon > start) folders.push_back(path->substr(start, colon - start));
      start = colon + 1;
    }
  }
  for (std::string& each : folders) {
    each = tilde_expanded(each);
    if (each.empty() || each[0] != '/') each = folder + "/" + each;
  }
  std::vector<int> codes;
  for (int code = 100; code <= 199; ++code) {
    for (const std::string& each : folders) {
      struct stat st;
      const std::string path = each + "/M" + std::to_string(code);
      if (::stat(path.c_str(), &st) == 0 && (st.st_mode & S_IXUSR)) {
        codes.push_back(code);
        break;
      }
    }
  }
  return codes;
}

}  // namespace fatc::io
