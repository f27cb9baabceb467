#include "usage.hpp"

#include "command_line.hpp"
#include "io/man_text.hpp"

namespace fatc::io {
namespace {

using Mode = Options::Mode;

std::string synopsis(const ModeDeclaration& mode) {
  std::string line = "fixed_atc_probe";
  if (*mode.flag) line += std::string(" ") + mode.flag;
  if (*mode.value) line += std::string(" ") + mode.value;
  for (const char* name : mode.needs) line += std::string(" ") + name + " " + option(name).value;
  for (const char* name : mode.may) line += std::string(" [") + named_value(name) + "]";
  return line;
}

}  // namespace

std::string usage() {
  std::string out;
  for (const ModeDeclaration& mode : modes()) {
    out += (out.empty() ? "usage: " : "       ") + synopsis(mode) + "\n";
    out += "           " + std::string(mode.summary) + "\n";
  }
  out += "options:\n";
  for (const OptionDeclaration& o : options()) {
    out += std::string("  ") + named_value(o.name) + "\n      " + o.doc + "\n";
  }
  return out;
}

std::string synopsis_man() {
  std::string out;
  for (const ModeDeclaration& mode : modes()) {
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
  for (const ModeDeclaration& mode : modes()) {
    if (!*mode.flag) continue;
    out += ".TP\n.B " + std::string(mode.flag) + (*mode.value ? std::string(" ") + mode.value : "") +
           "\n" + man_text(mode.doc) + ".\n";
  }
  for (const OptionDeclaration& o : options()) {
    out += ".TP\n.B " + named_value(o.name) + "\n" + man_text(o.doc) + ".\n";
  }
  return out;
}

std::string command_line_markdown() {
  std::string out = "```\n";
  for (const ModeDeclaration& mode : modes()) out += synopsis(mode) + "\n";
  out += "```\n\n| mode | what it does |\n| --- | --- |\n";
  for (const ModeDeclaration& mode : modes()) {
    out += "| `" + std::string(*mode.flag ? mode.flag : "(none)") + "` | " + mode.doc + " |\n";
  }
  out += "\n| option | what it is |\n| --- | --- |\n";
  for (const OptionDeclaration& o : options()) {
    out += "| `" + named_value(o.name) + "` | " + o.doc + " |\n";
  }
  return out;
}

}  // namespace fatc::io
