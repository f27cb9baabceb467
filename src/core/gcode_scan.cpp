#include "gcode_scan.hpp"

#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "quote.hpp"

namespace fatc::gcode {
namespace {

bool is_letter(char c) { return c >= 'a' && c <= 'z'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_number_char(char c) { return is_digit(c) || c == '.'; }

/// LinuxCNC's own M codes (its table `ems`); M98 and M99 are read as o-words.
bool is_builtin_m(long long m) {
  return (m >= 0 && m <= 9) || m == 19 || m == 30 || (m >= 48 && m <= 53) || (m >= 60 && m <= 68) ||
         (m >= 70 && m <= 73) || m == 99;
}

/// LinuxCNC's own G codes, in tenths (its table `gees`).
bool is_builtin_g(long long tenths) {
  static const auto codes = [] {
    std::array<bool, 1000> known{};
    for (const int code :
         {0,   10,  20,  30,  40,  50,  51,  52,  53,  60,  61,  62,  63,  70,  80,  100,
          170, 171, 180, 181, 190, 191, 200, 210, 280, 281, 300, 301, 330, 331, 382, 383,
          384, 385, 400, 410, 411, 420, 421, 430, 431, 432, 490, 520, 530, 540, 550, 560,
          570, 580, 590, 591, 592, 593, 610, 611, 640, 700, 710, 711, 712, 720, 721, 722,
          730, 740, 760, 800, 810, 820, 830, 840, 850, 860, 870, 880, 890, 900, 901, 910,
          911, 920, 921, 922, 923, 930, 940, 950, 960, 970, 980, 990}) {
      known[static_cast<std::size_t>(code)] = true;
    }
    return known;
  }();
  return tenths >= 0 && tenths < 1000 && codes[static_cast<std::size_t>(tenths)];
}

/// LinuxCNC's read_integer_value: a value within 0.0001 of a whole number.
std::optional<long long> whole_number(double value) {
  if (!std::isfinite(value) || std::fabs(value) > 1e15) return std::nullopt;
  const double below = std::floor(value);
  const double fraction = value - below;
  if (fraction > 0.9999) return static_cast<long long>(below) + 1;
  if (fraction > 0.0001) return std::nullopt;
  return static_cast<long long>(below);
}

/// A character LinuxCNC refuses, as a message shows it.
std::string bad_character(char c) {
  const auto byte = static_cast<unsigned char>(c);
  char buffer[48];
  if (byte < 0x20 || byte >= 0x7f) {
    std::snprintf(buffer, sizeof buffer, "byte 0x%02X", byte);
  } else {
    std::snprintf(buffer, sizeof buffer, "character '%c'", c);
  }
  return buffer;
}

/// The line as LinuxCNC's close_and_downcase leaves it: letters in lower
/// case, no spaces or tabs; each (comment) becomes a single '(' that ends a
/// word, a ; comment ends the line. `problem` is null when the comments are
/// sound. Lines are at most kMaxLineLength long here.
struct Normalized {
  char text[kMaxLineLength + 1];
  std::size_t size = 0;
  const char* problem = nullptr;

  std::string_view code() const { return {text, size}; }
};

void normalize(std::string_view raw, Normalized& out) {
  out.size = 0;
  out.problem = nullptr;
  bool comment = false;
  for (const char c : raw) {
    if (comment) {
      if (c == ')') {
        comment = false;
      } else if (c == '(') {
        out.problem = "'(' inside a comment: LinuxCNC refuses the line (nested comment)";
        return;
      }
      continue;
    }
    if (c == ';') break;
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (c == '(') comment = true;
    out.text[out.size++] = c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  }
  if (comment) out.problem = "comment without its ')': LinuxCNC refuses the line";
}

/// A word's value while its line is read: `text` points into the line.
struct WordValue {
  bool literal = false;
  std::string_view text;

  /// The literal's value, read only for the words that matter (T, M, G, Q, P).
  double number() const {
    if (!literal) return 0.0;
    char digits[64];
    text.copy(digits, text.size());
    digits[text.size()] = '\0';
    return std::strtod(digits, nullptr);
  }
  /// number() as a whole number, as read_integer_value takes it; digits alone
  /// (most words: G1, M6, T3) without strtod.
  std::optional<long long> whole() const {
    if (!literal) return std::nullopt;
    if (!text.empty() && text.size() <= 15 &&
        text.find_first_not_of("0123456789") == std::string_view::npos) {
      long long value = 0;
      for (const char c : text) value = value * 10 + (c - '0');
      return value;
    }
    return whole_number(number());
  }
  Value kept() const { return Value{literal, number(), std::string(text)}; }
};

/// Reads the words of one normalized line.
class LineParser {
 public:
  explicit LineParser(std::string_view code) : code_(code) {}

  char peek(std::size_t ahead = 0) const {
    return pos_ + ahead < code_.size() ? code_[pos_ + ahead] : '\0';
  }
  bool done() const { return pos_ >= code_.size(); }
  std::size_t pos() const { return pos_; }
  void advance(std::size_t n = 1) { pos_ += n; }
  bool starts_with(std::string_view word) const { return rest().substr(0, word.size()) == word; }
  std::string_view rest() const {
    return pos_ < code_.size() ? code_.substr(pos_) : std::string_view();
  }

  /// Skips a bracketed expression from its '['; false when it is not closed.
  bool skip_brackets() {
    int depth = 0;
    for (; pos_ < code_.size(); ++pos_) {
      if (code_[pos_] == '[') ++depth;
      if (code_[pos_] == ']' && --depth == 0) {
        ++pos_;
        return true;
      }
    }
    return false;
  }

  /// Skips a value LinuxCNC computes (read_real_value): signs, then a
  /// number, a parameter, an expression or a function; false when none.
  bool skip_value(int depth = 0) {
    if (depth > 64) return false;
    while ((peek() == '+' || peek() == '-') && !is_number_char(peek(1))) advance();
    const char c = peek();
    if (c == '[') return skip_brackets();
    if (c == '#') {
      advance();
      if (peek() == '<') {
        const auto close = code_.find('>', pos_);
        if (close == std::string_view::npos) return false;
        pos_ = close + 1;
        return true;
      }
      return skip_value(depth + 1);
    }
    if (is_letter(c)) {
      const std::size_t start = pos_;
      while (is_letter(peek())) advance();
      if (peek() != '[') return false;
      const bool atan = code_.substr(start, pos_ - start) == "atan";
      if (!skip_brackets()) return false;
      if (atan && peek() == '/' && peek(1) == '[') {
        advance();
        return skip_brackets();
      }
      return true;
    }
    const std::size_t start = pos_;
    while (peek() == '+' || peek() == '-') advance();
    while (is_number_char(peek())) advance();
    return pos_ > start;
  }

  /// A word's value, its text a view into the line; nullopt when there is
  /// none LinuxCNC could read.
  std::optional<WordValue> read_value() {
    const std::size_t start = pos_;
    // read_real_number: signs, digits and dots, all of it a number.
    std::size_t end = start;
    while (end < code_.size() && (code_[end] == '+' || code_[end] == '-')) ++end;
    const std::size_t digits = end;
    while (end < code_.size() && is_number_char(code_[end])) ++end;
    if (end > digits) {
      const std::string_view text = code_.substr(start, end - start);
      // Only one sign may lead, one dot at most ("+-3", "3.5.1" are bad to LinuxCNC).
      if (digits - start > 1 || text.find('.') != text.rfind('.') || text == "." ||
          text.size() >= 64) {
        return std::nullopt;
      }
      pos_ = end;
      return WordValue{true, text};
    }
    if (!skip_value()) {
      pos_ = start;
      return std::nullopt;
    }
    return WordValue{false, code_.substr(start, pos_ - start)};
  }

 private:
  std::string_view code_;
  std::size_t pos_ = 0;
};

/// The words of one line that matter, and its first problem.
struct ParsedLine {
  std::vector<Event> events;
  std::string problem;
};

/// Where a line's events come from.
struct Origin {
  int line = 0;
  bool block_delete = false;
};

Event start(const Origin& origin) {
  Event event;
  event.line = origin.line;
  event.block_delete = origin.block_delete;
  return event;
}

/// "T3.5" for a message: the letter in capitals, the value as written.
std::string word(char letter, const WordValue& value) {
  return std::string(1, static_cast<char>(letter - 'a' + 'A')) + escape(value.text, 40);
}

class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  ScannedFile run() {
    if (const void* nul = std::memchr(text_.data(), '\0', text_.size())) {
      const auto offset = static_cast<std::size_t>(static_cast<const char*>(nul) - text_.data());
      const TextPosition at = position_of(text_, offset);
      // One line for the whole file: a binary file would give one per line.
      result_.problems.push_back(
          {static_cast<int>(at.line),
           "NUL byte at column " + std::to_string(at.column) +
               ": not a G-code text file (LinuxCNC stops reading a line at a NUL); nothing of "
               "it read"});
      return std::move(result_);
    }
    std::size_t start = 0;
    while (start < text_.size()) {
      const void* newline = std::memchr(text_.data() + start, '\n', text_.size() - start);
      const std::size_t end =
          newline == nullptr
              ? text_.size()
              : static_cast<std::size_t>(static_cast<const char*>(newline) - text_.data());
      ++line_;
      const bool go_on = read_line(text_.substr(start, end - start));
      start = end + 1;
      result_.lines = line_;
      if (!go_on) break;
      if (result_.problems.size() >= kMaxProblemsPerFile && start < text_.size()) {
        result_.problems.push_back(
            {line_, std::to_string(kMaxProblemsPerFile) +
                        " problems so far: the rest of the file is not read"});
        break;
      }
    }
    for (const auto& [name, begin] : result_.subs) {
      if (result_.sub_ends.count(name) == 0) result_.sub_ends[name] = result_.events.size();
    }
    return std::move(result_);
  }

 private:
  /// False when the file ends here (the closing %).
  bool read_line(std::string_view raw) {
    if (raw.size() > kMaxLineLength) {
      problem(std::to_string(raw.size()) + " characters: LinuxCNC reads at most " +
              std::to_string(kMaxLineLength) + " in a line (command too long)");
      seen_text_ = true;
      return true;
    }
    std::size_t length = raw.size();
    while (length > 0 &&
           (raw[length - 1] == ' ' || (raw[length - 1] >= '\t' && raw[length - 1] <= '\r'))) {
      --length;
    }
    raw = raw.substr(0, length);
    normalize(raw, normalized_);
    const bool first_text = !seen_text_ && !raw.empty();
    if (!raw.empty()) seen_text_ = true;
    const std::string_view code = normalized_.code();
    if (first_text && code == "%") {
      percent_ = true;
      return true;
    }
    if (percent_ && code == "%") return false;
    if (normalized_.problem != nullptr) {
      problem(normalized_.problem);
      return true;
    }
    if (code.empty()) return true;
    ParsedLine parsed = parse(code);
    const bool in_definition = !defining_.empty();
    for (const Event& event : parsed.events) {
      const bool opens_sub = event.kind == Event::Kind::o_word && event.o_word == OWord::sub;
      // After M2 only subroutine definitions are read (a call may look for them).
      if (ended_ && !in_definition && !opens_sub) continue;
      record(event);
    }
    if (!parsed.problem.empty() && (!ended_ || in_definition)) problem(parsed.problem);
    return true;
  }

  void record(const Event& event) {
    if (event.kind == Event::Kind::o_word && event.o_word == OWord::sub) {
      if (result_.subs.count(event.name) == 0) result_.subs[event.name] = result_.events.size();
      defining_.push_back(event.name);
    } else if (event.kind == Event::Kind::o_word && event.o_word == OWord::endsub &&
               !defining_.empty()) {
      if (result_.sub_ends.count(defining_.back()) == 0) {
        result_.sub_ends[defining_.back()] = result_.events.size();
      }
      defining_.pop_back();
    } else if (event.kind == Event::Kind::end && defining_.empty()) {
      ended_ = true;
    }
    result_.events.push_back(event);
  }

  void problem(const std::string& text) { result_.problems.push_back({line_, text}); }

  ParsedLine parse(std::string_view code) {
    ParsedLine parsed;
    LineParser p(code);
    Origin base{line_, false};
    if (p.peek() == '/') {
      base.block_delete = true;
      p.advance();
    }
    if (p.peek() == 'n') {
      p.advance();
      while (is_number_char(p.peek())) p.advance();
    }
    if (p.peek() == 'o' || is_m_word(p, "98") || is_m_word(p, "99")) {
      parse_o_word(p, base, parsed);
      return parsed;
    }
    std::optional<WordValue> t, q;
    bool m6 = false, m61 = false, end = false;
    std::string end_code;
    std::vector<Event> codes;
    while (!p.done()) {
      const char c = p.peek();
      if (c == '(') {
        p.advance();
        continue;
      }
      if (c == '#') {  // a parameter setting: #1=..., #<name>=..., #[...]=...
        p.advance();
        bool read = false;
        if (p.peek() == '<') {
          const auto close = p.rest().find('>');
          read = close != std::string_view::npos;
          if (read) p.advance(close + 1);
        } else {
          read = p.skip_value();
        }
        if (!read || p.peek() != '=') {
          parsed.problem = "a parameter setting LinuxCNC cannot read (#... = value)";
          return parsed;
        }
        p.advance();
        if (!p.skip_value()) {
          parsed.problem = "a parameter setting without a value: LinuxCNC refuses the line";
          return parsed;
        }
        continue;
      }
      const bool item = (is_letter(c) && c != 'n' && c != 'o') || c == '$' || c == '@' || c == '^';
      if (!item) {
        parsed.problem = bad_character(c) + ": LinuxCNC refuses the line (bad character)";
        return parsed;
      }
      p.advance();
      const auto value = p.read_value();
      if (!value) {
        parsed.problem = std::string(1, static_cast<char>(std::toupper(c))) +
                         " without a number LinuxCNC can read: LinuxCNC refuses the line";
        return parsed;
      }
      if (c == 't') {
        if (t) {
          parsed.problem = "two T words in one line: LinuxCNC refuses the line";
          return parsed;
        }
        if (value->literal) {
          const auto tool = value->whole();
          if (!tool) {
            parsed.problem = word('t', *value) +
                             ": a tool number must be a whole number: LinuxCNC refuses the line";
            return parsed;
          }
          if (*tool < 0) {
            parsed.problem =
                word('t', *value) + ": a negative tool number: LinuxCNC refuses the line";
            return parsed;
          }
          if (*tool > INT_MAX) {
            parsed.problem = word('t', *value) +
                             ": beyond the tool numbers LinuxCNC reads (up to " +
                             std::to_string(INT_MAX) + ")";
            return parsed;
          }
        }
        t = value;
      } else if (c == 'q') {
        q = value;
      } else if (c == 'm') {
        const auto m = value->whole();
        if (value->literal && (!m || *m < 0)) {
          parsed.problem = word('m', *value) + ": not an M code: LinuxCNC refuses the line";
          return parsed;
        }
        if (!m) {
          codes.push_back(code_event(base, word('m', *value)));
        } else if (*m == 6) {
          m6 = true;
        } else if (*m == 61) {
          m61 = true;
        } else if (*m == 2 || *m == 30) {
          end = true;
          end_code = "M" + std::to_string(*m);
        } else if (!is_builtin_m(*m) || (*m >= 100 && *m <= 199)) {
          codes.push_back(code_event(base, "M" + std::to_string(*m)));
        }
      } else if (c == 'g' && value->literal) {
        const auto whole = value->whole();
        const auto tenths =
            whole ? std::optional<long long>(*whole * 10) : whole_number(value->number() * 10.0);
        if (tenths && *tenths >= 0 && !is_builtin_g(*tenths)) {
          codes.push_back(
              code_event(base, "G" + std::to_string(*tenths / 10) +
                                   (*tenths % 10 != 0 ? "." + std::to_string(*tenths % 10) : "")));
        }
      }
    }
    if (m6 && m61) {
      parsed.problem = "M6 and M61 in one line: LinuxCNC refuses the line (same modal group)";
      return parsed;
    }
    if (t) {
      Event select = start(base);
      select.kind = Event::Kind::select_tool;
      select.value = t->kept();
      parsed.events.push_back(select);
    }
    if (m6) {
      Event change = start(base);
      change.kind = Event::Kind::change_tool;
      parsed.events.push_back(change);
    }
    if (m61) {
      if (!q) {
        parsed.problem = "M61 without a Q word: LinuxCNC refuses the line";
        parsed.events.clear();
        return parsed;
      }
      if (q->literal && std::floor(q->number() + 0.5) < 0) {
        parsed.problem =
            "M61 " + word('q', *q) + ": a negative tool number: LinuxCNC refuses the line";
        parsed.events.clear();
        return parsed;
      }
      Event set = start(base);
      set.kind = Event::Kind::set_tool;
      set.value = q->kept();
      if (q->literal) set.value.number = std::floor(q->number() + 0.5);  // round_to_int
      parsed.events.push_back(set);
    }
    for (const Event& code_use : codes) parsed.events.push_back(code_use);
    if (end) {
      Event stop = start(base);
      stop.kind = Event::Kind::end;
      stop.name = end_code;
      parsed.events.push_back(stop);
    }
    return parsed;
  }

  static bool is_m_word(const LineParser& p, std::string_view number) {
    if (p.peek() != 'm') return false;
    std::size_t i = 1;
    while (p.peek(i) == '0') ++i;
    return p.rest().substr(i, number.size()) == number &&
           !is_number_char(p.peek(i + number.size()));
  }

  static Event code_event(const Origin& base, const std::string& name) {
    Event event = start(base);
    event.kind = Event::Kind::code;
    event.name = name;
    return event;
  }

  /// o-words, and the Fanuc forms M98 P (call), bare O (sub) and M99 (its end).
  void parse_o_word(LineParser& p, const Origin& base, ParsedLine& parsed) {
    Event event = start(base);
    event.kind = Event::Kind::o_word;
    if (p.peek() == 'm') {
      const bool call = is_m_word(p, "98");
      p.advance();
      p.read_value();
      if (!call) {
        if (!defining_.empty()) {
          event.o_word = OWord::endsub;
          event.name = defining_.back();
        } else {
          event.kind = Event::Kind::end;
          event.name = "M99";
        }
        parsed.events.push_back(event);
        return;
      }
      std::optional<WordValue> target;
      while (!p.done()) {
        const char c = p.peek();
        p.advance();
        if (c == '(') continue;
        const auto value = p.read_value();
        if (!value) break;
        if (c == 'p') target = value;
      }
      if (!target) {
        parsed.problem = "M98 without a P word: LinuxCNC refuses the line";
        return;
      }
      const auto number = target->whole();
      event.o_word = OWord::call;
      event.value = target->kept();
      event.value.literal = number.has_value();
      event.name = number ? std::to_string(*number) : std::string(target->text);
      parsed.events.push_back(event);
      return;
    }
    p.advance();  // the o
    if (p.peek() == '<') {
      const auto close = p.rest().find('>');
      if (close == std::string_view::npos) {
        parsed.problem =
            "o<" + escape(p.rest().substr(1), 40) + " without its '>': LinuxCNC refuses the line";
        return;
      }
      event.name = std::string(p.rest().substr(1, close - 1));
      event.value.literal = true;
      p.advance(close + 1);
    } else {
      const auto value = p.read_value();
      const auto number = value ? value->whole() : std::nullopt;
      if (!value || (value->literal && !number)) {
        parsed.problem = "an o-word without a name or number: LinuxCNC refuses the line";
        return;
      }
      event.value = value->kept();
      event.value.literal = number.has_value();
      event.name = number ? std::to_string(*number) : std::string(value->text);
    }
    static const std::pair<const char*, OWord> keywords[] = {
        {"sub", OWord::sub},           {"endsub", OWord::endsub},
        {"call", OWord::call},         {"do", OWord::do_loop},
        {"while", OWord::while_loop},  {"repeat", OWord::repeat},
        {"if", OWord::if_block},       {"elseif", OWord::elseif},
        {"else", OWord::else_block},   {"endif", OWord::endif},
        {"break", OWord::break_loop},  {"continue", OWord::continue_loop},
        {"endwhile", OWord::endwhile}, {"endrepeat", OWord::endrepeat},
        {"return", OWord::return_sub}};
    for (const auto& [keyword, kind] : keywords) {
      if (p.starts_with(keyword)) {
        event.o_word = kind;
        parsed.events.push_back(event);
        return;
      }
    }
    if (p.done() || p.peek() == '(') {  // Fanuc: "O100" alone opens a subroutine, M99 ends it
      event.o_word = OWord::sub;
      parsed.events.push_back(event);
      return;
    }
    parsed.problem = o_word_name(event.name) + " " + escape(p.rest(), 40) +
                     ": not an o-word LinuxCNC knows (sub, call, if, while, ...)";
  }

  std::string_view text_;
  ScannedFile result_;
  Normalized normalized_;
  int line_ = 0;
  bool seen_text_ = false;
  bool percent_ = false;
  bool ended_ = false;
  std::vector<std::string> defining_;
};

}  // namespace

ScannedFile scan(std::string_view text) { return Scanner(text).run(); }

std::string o_word_name(const std::string& name) {
  const bool number = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return number ? "o" + name : "o<" + escape(name, 40) + ">";
}

}  // namespace fatc::gcode
