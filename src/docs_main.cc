// fatc_docs: the references generated from the code (the pins of
// pin_list.hpp, the config keys of keys.cpp, the command line of
// command_line.cpp), so documentation cannot drift
// from it. Not installed;
// `cmake --build build --target references` writes them into the tree and
// the unit test references_are_current compares.
//   fatc_docs pins-md | config-md | cli-md | pins-golden CONFIG | man TEMPLATE
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli/usage.hpp"
#include "core/config/keys.hpp"
#include "io/files.hpp"
#include "linuxcnc/live/pin_reference.hpp"

namespace {

int usage() {
  std::cerr << "usage: fatc_docs pins-md | config-md | cli-md | pins-golden CONFIG | man TEMPLATE\n";
  return 2;
}

/// A generated page of docs/: its title, where it comes from, a word on it, the table.
std::string page(const std::string& title, const std::string& source, const std::string& intro,
                 const std::string& table) {
  return "# " + title + "\n\n<!-- Generated from " + source +
         " by fatc_docs: edit that, then\n     cmake --build build --target references -->\n\n" +
         intro + "\n" + table;
}

/// `text` with each line that is only `marker` replaced by `with`.
std::string fill(const std::string& text, const std::string& marker, const std::string& with) {
  std::istringstream in(text);
  std::string out;
  std::string line;
  while (std::getline(in, line)) out += line == marker ? with : line + "\n";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 1 && args[0] == "pins-md") {
    std::cout << page("HAL pins", "src/linuxcnc/live/pin_list.hpp",
                      "The component's pins, all `fixed_atc_probe.*`, in the order the component\n"
                      "creates them; `man fixed_atc_probe` lists the same.\n",
                      fatc::linuxcnc::pins_markdown());
    return 0;
  }
  if (args.size() == 1 && args[0] == "cli-md") {
    std::cout << page("The command line", "src/cli/command_line.cpp",
                      "Every mode and option `fixed_atc_probe` accepts (`--help` and the man page "
                      "say\nthe same). A usage mistake (an unknown option, one given twice, two "
                      "modes, an\nempty value, an option the mode does not read) is one line and "
                      "exit 2.\n",
                      fatc::io::command_line_markdown());
    return 0;
  }
  if (args.size() == 1 && args[0] == "config-md") {
    std::cout << page("config.json keys", "src/core/config/keys.cpp",
                      "Every key config.json may hold; the reader refuses any other and checks "
                      "each\nnumber against the range here. All coordinates are machine "
                      "coordinates (G53).\n*length* is in `units`, *feed* in `units` per minute, "
                      "*s* in seconds. A range\nholds in mm and in inch alike unless it says "
                      "otherwise.\n",
                      fatc::config_markdown());
    return 0;
  }
  if (args.size() == 2 && args[0] == "pins-golden") {
    const auto loaded = fatc::io::load_config_file(args[1]);
    if (!loaded.config) {
      for (const auto& error : loaded.errors) std::cerr << "fatc_docs: " << error << "\n";
      return 1;
    }
    std::vector<int> pockets;
    for (const auto& entry : loaded.config->pockets) pockets.push_back(entry.first);
    std::cout << fatc::linuxcnc::pins_golden(pockets);
    return 0;
  }
  if (args.size() == 2 && args[0] == "man") {
    std::ifstream in(args[1]);
    if (!in) {
      std::cerr << "fatc_docs: cannot read " << args[1] << "\n";
      return 1;
    }
    std::stringstream text;
    text << in.rdbuf();
    std::string page = text.str();
    page = page.substr(page.find('\n') + 1);  // the template's own comment
    page = fill(page, "@TH@",
                ".TH FIXED_ATC_PROBE \"1\" \"2026\" \"fixed_atc_probe " FATC_PROJECT_VERSION
                "\" \"LinuxCNC HAL userspace components\"\n");
    page = fill(page, "@SYNOPSIS@", fatc::io::synopsis_man());
    page = fill(page, "@OPTIONS@", fatc::io::options_man());
    std::cout << fill(page, "@PINS@", fatc::linuxcnc::pins_man());
    return 0;
  }
  return usage();
}
