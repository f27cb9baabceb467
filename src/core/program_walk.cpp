#include "program_walk.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

#include "quote.hpp"

namespace fatc::gcode {

std::optional<Remap> parse_remap(std::string_view line) {
  std::istringstream words{std::string(line)};
  std::string word;
  if (!(words >> word)) return std::nullopt;
  Remap remap;
  for (const char c : word) remap.code.push_back(static_cast<char>(std::toupper(c)));
  while (words >> word) {
    const auto equals = word.find('=');
    if (equals == std::string::npos) continue;
    std::string key = word.substr(0, equals);
    for (char& c : key) c = static_cast<char>(std::tolower(c));
    if (key == "ngc") remap.ngc = word.substr(equals + 1);
    if (key == "python") remap.python = word.substr(equals + 1);
  }
  for (char& c : remap.ngc) c = static_cast<char>(std::tolower(c));
  return remap;
}

namespace {

/// An open loop or conditional.
struct Flow {
  int line = 0;
  std::string name;
  OWord opener = OWord::if_block;
  bool has_tool_use = false;
};

/// A file being run: the main program, or a subroutine's body.
struct Frame {
  const SourceFile* file = nullptr;
  std::string sub;  ///< empty in the main program
  std::vector<Flow> flows;
};

const char* opener_word(OWord opener) {
  switch (opener) {
    case OWord::do_loop:
      return "do";
    case OWord::while_loop:
      return "while";
    case OWord::repeat:
      return "repeat";
    default:
      return "if";
  }
}

class Walker {
 public:
  Walker(const SourceFile& program, SubroutineFinder& finder, const WalkOptions& options)
      : program_(program), finder_(finder), options_(options) {}

  Walk run() {
    enter(program_);
    run_body(program_, 0, program_.scanned.events.size(), "");
    return std::move(result_);
  }

 private:
  void enter(const SourceFile& file) {
    if (!entered_.insert(&file).second) return;
    result_.files.push_back(file.name);
    for (const auto& note : file.scanned.problems) {
      result_.problems.push_back({{file.name, note.line}, note.text});
    }
  }

  void unknown(const Site& where, const std::string& text) {
    if (said_.insert(where.file + "\n" + std::to_string(where.line) + "\n" + text).second) {
      result_.unknowns.push_back({where, text});
    }
  }
  void problem(const Site& where, const std::string& text) {
    if (said_.insert(where.file + "\n" + std::to_string(where.line) + "\n" + text).second) {
      result_.problems.push_back({where, text});
    }
  }

  bool in_flow() const {
    return std::any_of(frames_.begin(), frames_.end(),
                       [](const Frame& frame) { return !frame.flows.empty(); });
  }

  /// Runs events [begin, end) of `file`; `sub` is the subroutine they belong to.
  void run_body(const SourceFile& file, std::size_t begin, std::size_t end,
                const std::string& sub) {
    frames_.push_back({&file, sub, {}});
    const auto& events = file.scanned.events;
    for (std::size_t i = begin; i < end && !stopped_; ++i) {
      const Event& event = events[i];
      const Site here{file.name, event.line};
      if (++blocks_ > options_.max_blocks) {
        unknown(here, "stopped following the program after " + std::to_string(options_.max_blocks) +
                          " blocks through its calls: what comes after is not known");
        stopped_ = true;
        break;
      }
      switch (event.kind) {
        case Event::Kind::select_tool:
          selected_ = event.value;
          if (event.block_delete) block_delete(here);
          remapped_once("T", here);
          break;
        case Event::Kind::change_tool:
          tool_use(ToolUse::Kind::change, here, event.block_delete, selected_);
          break;
        case Event::Kind::set_tool:
          tool_use(ToolUse::Kind::set, here, event.block_delete, event.value);
          break;
        case Event::Kind::code:
          code(file, here, event);
          break;
        case Event::Kind::end:
          if (!in_flow()) {
            if (event.name == "M99") {
              unknown(here, "M99: the program starts over from its first line: counted once");
            }
            stopped_ = true;
          }
          break;
        case Event::Kind::o_word:
          if (event.o_word == OWord::sub) {  // a definition: not run here
            const auto last = file.scanned.sub_ends.find(event.name);
            if (last != file.scanned.sub_ends.end() && last->second > i) i = last->second;
          } else if ((event.o_word == OWord::endsub || event.o_word == OWord::return_sub) &&
                     !sub.empty() && frames_.back().flows.empty()) {
            i = end;
          } else if (event.o_word == OWord::call) {
            call(file, here, event);
          } else {
            flow(here, event);
          }
          break;
      }
    }
    while (!frames_.back().flows.empty()) close_flow(file);
    frames_.pop_back();
  }

  void block_delete(const Site& here) {
    unknown(here, "a block-delete line (/): counted as if block delete is off");
  }

  /// A note, once, when the INI remaps `code`, which this walk reads as LinuxCNC's own.
  void remapped_once(const std::string& code, const Site& here) {
    const auto remap = options_.remaps.find(code);
    if (remap == options_.remaps.end()) {
      if (code == "M6" && options_.remaps_known && noted_remaps_.insert(code).second) {
        problem(here, "the INI remaps no M6: LinuxCNC's own M6 would run here, not " +
                          std::string(kOwnM6Remap));
      }
      return;
    }
    if (code == "M6" && remap->second.ngc == kOwnM6Remap) return;
    if (!noted_remaps_.insert(code).second) return;
    unknown(here, code + " is remapped in the INI (" + remap_target(remap->second) + ")" +
                      (code == "M6" ? ", not to " + std::string(kOwnM6Remap) : "") +
                      ": read here as LinuxCNC's own " + code);
  }

  static std::string remap_target(const Remap& remap) {
    return remap.ngc.empty() ? "python=" + escape(remap.python, 40)
                             : "ngc=" + escape(remap.ngc, 40);
  }

  void mark_tool_use() {
    for (Frame& frame : frames_) {
      for (Flow& open : frame.flows) open.has_tool_use = true;
    }
  }

  /// False, and the walk stops, when the program has more tool uses than it follows.
  bool room_for_a_tool_use(const Site& here) {
    if (result_.uses.size() < options_.max_tool_uses) return true;
    unknown(here, "more than " + std::to_string(options_.max_tool_uses) +
                      " tool changes: the rest are not counted");
    stopped_ = true;
    return false;
  }

  /// An M6 (with the T selected last, if any) or an M61 Q`value`.
  void tool_use(ToolUse::Kind kind, const Site& here, bool on_block_delete,
                const std::optional<Value>& value) {
    if (!room_for_a_tool_use(here)) return;
    const std::string code = kind == ToolUse::Kind::change ? "M6" : "M61";
    const std::string letter = kind == ToolUse::Kind::change ? "T" : "Q";
    remapped_once(code, here);
    if (on_block_delete) block_delete(here);
    ToolUse use;
    use.kind = kind;
    use.where = here;
    use.in_flow = in_flow();
    if (!value) {
      problem(here, "M6 without a T word since the start");
    } else if (value->literal) {
      use.tool = static_cast<int>(std::floor(value->number + 0.5));
      use.written = letter + std::to_string(*use.tool);
    } else {
      use.written = letter + escape(value->text, 40);
      unknown(here, code + " " + use.written +
                        ": the tool number is computed when the program runs: not known");
    }
    mark_tool_use();
    result_.uses.push_back(use);
  }

  void code(const SourceFile& file, const Site& here, const Event& event) {
    const auto remap = options_.remaps.find(event.name);
    if (remap != options_.remaps.end()) {
      if (remap->second.ngc.empty()) {
        unknown(here, event.name + " is remapped in the INI (" + remap_target(remap->second) +
                          "): what it does is not known");
        return;
      }
      Event as_call = event;
      as_call.name = remap->second.ngc;
      as_call.value.literal = true;
      call(file, here, as_call,
           event.name + " (remapped to ngc=" + escape(remap->second.ngc, 40) + ")");
      return;
    }
    const bool user_m = event.name.size() == 4 && event.name[0] == 'M' && event.name[1] == '1';
    if (user_m) {
      unknown(here, event.name + " runs the user program " + event.name +
                        " (PROGRAM_PREFIX or USER_M_PATH): what it does is not known");
    } else if (event.name.find('#') != std::string::npos ||
               event.name.find('[') != std::string::npos) {
      unknown(here, event.name + ": the M code is computed when the program runs: not known");
    } else if (options_.remaps_known) {
      problem(here, event.name +
                        " is no LinuxCNC code and the INI remaps none: LinuxCNC refuses the line");
    } else {
      unknown(here, event.name +
                        " is no LinuxCNC code: a remap in the machine's INI (--ini follows it) "
                        "or an error: not known");
    }
  }

  void call(const SourceFile& file, const Site& here, const Event& event,
            const std::string& shown = "") {
    const std::string name = !shown.empty()        ? shown
                             : event.value.literal ? o_word_name(event.name) + " call"
                                                   : "o" + escape(event.name, 40) + " call";
    if (!event.value.literal) {
      unknown(here, name + ": the subroutine is computed when the program runs: not known");
      return;
    }
    for (const Frame& frame : frames_) {
      if (frame.sub == event.name) {
        unknown(here, name + ": " + o_word_name(event.name) +
                          " calls itself (recursion): its body is followed once");
        return;
      }
    }
    if (static_cast<int>(frames_.size()) > kMaxCallDepth) {
      problem(here, name + ": calls nested " + std::to_string(frames_.size()) +
                        " deep: LinuxCNC allows " + std::to_string(kMaxCallDepth) +
                        " (too many subroutine levels)");
      return;
    }
    const SourceFile* target = nullptr;
    for (const SourceFile* defined_in : {&file, &program_}) {
      if (defined_in->scanned.subs.count(event.name) != 0) {
        target = defined_in;
        break;
      }
    }
    if (target == nullptr) {
      std::string why_not;
      target = finder_.find(event.name, why_not);
      if (target == nullptr) {
        unknown(here, name + ": " + why_not + ": what it does is not known");
        return;
      }
      enter(*target);
      if (target->scanned.subs.count(event.name) == 0) {
        problem(here, name + ": " + target->name + " has no " + o_word_name(event.name) +
                          " sub: LinuxCNC stops the program");
        return;
      }
    }
    const std::size_t begin = target->scanned.subs.at(event.name) + 1;
    const std::size_t end = target->scanned.sub_ends.at(event.name);
    run_body(*target, begin, end, event.name);
  }

  void flow(const Site& here, const Event& event) {
    auto& flows = frames_.back().flows;
    const auto open = [&](OWord opener) {
      flows.push_back({here.line, event.name, opener, false});
    };
    // Closes the innermost open `opener` of this name, and what was left open inside it.
    const auto close = [&](OWord opener) {
      const auto match = std::find_if(flows.rbegin(), flows.rend(), [&](const Flow& f) {
        return f.name == event.name && f.opener == opener;
      });
      if (match == flows.rend()) return false;
      const std::size_t keep = flows.size() - 1 - static_cast<std::size_t>(match - flows.rbegin());
      while (flows.size() > keep) close_flow(*frames_.back().file);
      return true;
    };
    switch (event.o_word) {
      case OWord::do_loop:
      case OWord::repeat:
      case OWord::if_block:
        open(event.o_word);
        break;
      case OWord::while_loop:
        if (!close(OWord::do_loop)) open(OWord::while_loop);
        break;
      case OWord::endwhile:
        close(OWord::while_loop);
        break;
      case OWord::endrepeat:
        close(OWord::repeat);
        break;
      case OWord::endif:
        close(OWord::if_block);
        break;
      default:  // else, elseif, break, continue; endsub or return in the main program
        break;
    }
  }

  void close_flow(const SourceFile& file) {
    auto& flows = frames_.back().flows;
    const Flow done = flows.back();
    flows.pop_back();
    if (!done.has_tool_use) return;
    const std::string what = o_word_name(done.name) + " " + opener_word(done.opener);
    unknown({file.name, done.line},
            done.opener == OWord::if_block
                ? "tool changes inside a conditional (" + what +
                      "): counted once, every branch as if it ran"
                : "tool changes inside a loop (" + what + "): counted once");
  }

  const SourceFile& program_;
  SubroutineFinder& finder_;
  const WalkOptions& options_;
  Walk result_;
  std::vector<Frame> frames_;
  std::optional<Value> selected_;
  std::size_t blocks_ = 0;
  bool stopped_ = false;
  std::set<const SourceFile*> entered_;
  std::set<std::string> said_;
  std::set<std::string> noted_remaps_;
};

}  // namespace

Walk walk(const SourceFile& program, SubroutineFinder& finder, const WalkOptions& options) {
  return Walker(program, finder, options).run();
}

}  // namespace fatc::gcode
