#include "tool_table.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "../config/quote.hpp"

namespace fatc {
namespace {

/// LinuxCNC reads the table with fgets into 256 bytes (CANON_TOOL_ENTRY_LEN):
/// 255 characters at a time, so a longer line is read as several, each
/// parsed as a line of its own.
constexpr std::size_t kLinuxCncRead = 255;
/// No offset, diameter or angle of a tool reaches this, in mm or inches.
constexpr double kLargestNumber = 100000.0;

/// sscanf("%d") of a field's number: nullopt when there is none; `wraps`
/// when it is beyond an int, which sscanf would read as another number.
std::optional<long> integer_of(const std::string& number, bool& wraps) {
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(number.c_str(), &end, 10);
  if (end == number.c_str()) return std::nullopt;
  wraps = errno == ERANGE || value < INT_MIN || value > INT_MAX;
  return value;
}

/// sscanf("%lf") of a field's number.
std::optional<double> real_of(const std::string& number) {
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (end == number.c_str()) return std::nullopt;
  return value;
}

/// Why `field` makes the line unusable, or empty when it is read as it
/// means. `skipped`: LinuxCNC itself skips the line; else it would read a
/// number that means nothing, and the line is left out here.
std::string field_problem(const std::string& field, ToolTableEntry& entry, bool& has_tool,
                          bool& skipped) {
  const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(field[0])));
  const std::string number = field.substr(1);
  skipped = true;
  if (std::strchr("TPQ", letter) != nullptr) {
    bool wraps = false;
    const auto value = integer_of(number, wraps);
    if (!value) return quote(field) + " is not a whole number after " + std::string(1, letter);
    skipped = false;
    if (wraps) {
      return quote(field) + " is beyond the largest whole number LinuxCNC reads (" +
             std::to_string(INT_MAX) + "): it would read another number";
    }
    if (letter == 'T') {
      entry.tool = static_cast<int>(*value);
      has_tool = true;
    }
    return "";
  }
  if (std::strchr("DXYZABCUVWIJ", letter) != nullptr) {
    const auto value = real_of(number);
    if (!value) return quote(field) + " is not a number after " + std::string(1, letter);
    skipped = false;
    // NaN fails every comparison: written so that it is caught.
    if (!(std::abs(*value) <= kLargestNumber)) {
      return quote(field) +
             " is no number a tool can have (NaN, infinite, or over 100000 either way), which "
             "LinuxCNC would read as it is";
    }
    if (letter == 'Z') entry.z = *value;
    return "";
  }
  return quote(field) + " is no tool table field (T P D X Y Z A B C U V W I J Q)";
}

/// Where one field of a table line is.
struct Token {
  std::size_t at = 0;
  std::size_t size = 0;
};

/// The fields of a table line as LinuxCNC's strtok finds them: before the
/// first ';', between spaces (a CR ends the last one).
std::vector<Token> tokens_of(std::string_view line) {
  std::vector<Token> tokens;
  const std::size_t end = std::min(line.find(';'), line.size());
  std::size_t at = 0;
  while (at < end) {
    const std::size_t stop = std::min(line.find_first_of(" \r", at), end);
    if (stop > at) tokens.push_back({at, stop - at});
    at = stop + 1;
  }
  return tokens;
}

/// The first field of `letter` (either case), if the line has one.
std::optional<Token> field_of(std::string_view line, const std::vector<Token>& tokens,
                              char letter) {
  for (const Token& token : tokens) {
    if (std::toupper(static_cast<unsigned char>(line[token.at])) == letter) return token;
  }
  return std::nullopt;
}

}  // namespace

namespace {

/// What LinuxCNC makes of one line as it reads it (one fgets).
struct LineRead {
  enum class Kind { nothing, tool, refused } kind = Kind::nothing;
  ToolTableEntry entry;
  std::string why;  ///< refused: why
  bool skipped = false;  ///< refused: LinuxCNC itself skips it (else it reads numbers that mean nothing)
};

LineRead read_line(std::string line, int line_number) {
  LineRead read;
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  if (line.empty() || line[0] == ';') return read;
  const std::string fields = line.substr(0, line.find(';'));
  if (fields.size() <= 1) return read;  // LinuxCNC's test for a blank line
  read.entry.line = line_number;
  bool has_tool = false;
  std::size_t at = 0;
  while (read.why.empty() && at < fields.size()) {
    const std::size_t space = fields.find(' ', at);
    const std::string field =
        fields.substr(at, space == std::string::npos ? std::string::npos : space - at);
    at = space == std::string::npos ? fields.size() : space + 1;
    if (field.empty()) continue;
    read.why = field_problem(field, read.entry, has_tool, read.skipped);
    read.entry.fields.push_back(field);
  }
  if (!read.why.empty()) {
    read.kind = LineRead::Kind::refused;
  } else if (has_tool) {
    read.kind = LineRead::Kind::tool;
  }
  return read;
}

/// What is said of a line LinuxCNC refuses, or of which it reads numbers that mean nothing.
std::string refusal(const LineRead& read) {
  return read.skipped ? "LinuxCNC skips this line: " + read.why
                      : read.why + "; the line is left out of the table here";
}

/// What LinuxCNC reads of a line over kLinuxCncRead characters, in one note:
/// the first kLinuxCncRead characters as the line (a field or the comment cut
/// there), the rest as lines of their own, each of which `reads` is told of.
template <class Reads>
std::string long_line(const std::string& line, int line_number, Reads reads) {
  std::string said = std::to_string(line.size()) + " characters, over the " +
                     std::to_string(kLinuxCncRead) + " LinuxCNC reads as one line: ";
  const LineRead first = read_line(line.substr(0, kLinuxCncRead), line_number);
  const std::size_t comment = line.find(';');
  if (first.kind == LineRead::Kind::tool) {
    said += "it reads tool " + std::to_string(first.entry.tool) + " from the first " +
            std::to_string(kLinuxCncRead);
    if (comment < kLinuxCncRead) {
      said += ", its comment cut there";
    } else {
      // The field the cut falls in, read short: Z40.1 of Z40.125.
      const std::size_t start = line.rfind(' ', kLinuxCncRead - 1);
      const std::size_t from = start == std::string::npos ? 0 : start + 1;
      const std::size_t end = std::min(line.find_first_of(" ;", from), line.size());
      if (from < kLinuxCncRead && end > kLinuxCncRead) {
        said += ", its field " + quote(line.substr(from, end - from)) + " read as " +
                quote(line.substr(from, kLinuxCncRead - from));
      }
      said += ", without what follows";
    }
  } else if (first.kind == LineRead::Kind::refused) {
    said += "it reads no tool from the first " + std::to_string(kLinuxCncRead) + " (" +
            refusal(first) + ")";
  } else {
    said += "the first " + std::to_string(kLinuxCncRead) + " hold no tool";
  }
  reads(first);
  // The rest, kLinuxCncRead characters at a time, each a line to LinuxCNC:
  // said in a few words however many there are.
  std::vector<std::string> tools;
  std::size_t pieces = 0;
  std::size_t skips = 0;
  for (std::size_t at = kLinuxCncRead; at < line.size(); at += kLinuxCncRead) {
    const LineRead piece = read_line(line.substr(at, kLinuxCncRead), line_number);
    reads(piece);
    ++pieces;
    if (piece.kind == LineRead::Kind::tool) tools.push_back("T" + std::to_string(piece.entry.tool));
    if (piece.kind == LineRead::Kind::refused) ++skips;
  }
  said += "; characters " + std::to_string(kLinuxCncRead + 1) + " on as ";
  if (pieces == 1) {
    return said + "a line of their own, " +
           (!tools.empty() ? "read as tool " + tools[0].substr(1)
                           : skips != 0 ? std::string("which it skips") : std::string("which holds nothing"));
  }
  return said + std::to_string(pieces) + " lines of their own: " + std::to_string(tools.size()) +
         " read as tools" + (tools.empty() ? "" : " (" + listed(tools, ", ", 5) + ")") + ", " +
         std::to_string(skips) + " skipped";
}

}  // namespace

ToolTable parse_tool_table(std::string_view text) {
  ToolTable table;
  int line_number = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string line(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (line.find('\0') != std::string::npos) {
      table.problems.push_back({line_number, "NUL byte: not a tool table; read no further"});
      break;
    }
    auto take = [&](const LineRead& read) {
      if (read.kind == LineRead::Kind::refused && line.size() <= kLinuxCncRead) {
        table.problems.push_back({line_number, refusal(read)});
      }
      if (read.kind != LineRead::Kind::tool) return;
      const auto [first, inserted] = table.tools.emplace(read.entry.tool, read.entry);
      if (!inserted) {
        table.problems.push_back({line_number, "tool " + std::to_string(read.entry.tool) +
                                                   " again (first on line " +
                                                   std::to_string(first->second.line) + ")"});
      }
    };
    if (line.size() > kLinuxCncRead) {
      // Said before what its pieces read: a tool twice is said after it.
      const std::size_t note = table.problems.size();
      const std::string said = long_line(line, line_number, take);
      table.problems.insert(table.problems.begin() + static_cast<std::ptrdiff_t>(note),
                            {line_number, said});
    } else {
      take(read_line(line, line_number));
    }
  }
  return table;
}

std::map<int, double> tool_lengths(const ToolTable& table, Units units, double machine_per_mm) {
  const double scale = machine_per_unit(units, machine_per_mm);
  std::map<int, double> lengths;
  for (const auto& [tool, entry] : table.tools) {
    if (entry.z) lengths[tool] = *entry.z / scale;
  }
  return lengths;
}

PocketRewrite with_rack_pockets(std::string_view text, const ToolState& tools) {
  PocketRewrite rewrite;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    end = end == std::string_view::npos ? text.size() : end + 1;
    std::string line(text.substr(start, end - start));
    start = end;
    // A line LinuxCNC skips, or reads as nothing a tool can have, is not ours to mend.
    const ToolTable one = parse_tool_table(line);
    if (one.tools.size() != 1 || !one.problems.empty()) {
      rewrite.text += line;
      continue;
    }
    const int tool = one.tools.begin()->first;
    const std::vector<Token> tokens = tokens_of(line);
    const auto p_field = field_of(line, tokens, 'P');
    std::optional<int> was;
    if (p_field) was = static_cast<int>(std::strtol(line.c_str() + p_field->at + 1, nullptr, 10));
    std::optional<int> pocket = tools.home_of(tool);
    if (!pocket && was && tools.pockets.count(*was) != 0) pocket = 0;
    if (pocket && pocket != was) {
      const std::string field = "P" + std::to_string(*pocket);
      if (p_field) {
        line.replace(p_field->at, p_field->size, field);
      } else {
        const Token t_field = *field_of(line, tokens, 'T');
        line.insert(t_field.at + t_field.size, " " + field);
      }
      rewrite.changes.push_back({tool, was, *pocket});
      was = pocket;
    }
    rewrite.p_of.emplace(tool, was);
    rewrite.text += line;
  }
  return rewrite;
}

std::string pocket_disagreement_words(const std::vector<PocketChange>& changes) {
  std::string where;
  for (const PocketChange& change : changes) {
    if (!where.empty()) where += ", ";
    where += "tool " + std::to_string(change.tool) + " is " +
             (change.pocket == 0 ? std::string("in no pocket of the rack")
                                 : "in pocket " + std::to_string(change.pocket)) +
             " (the table said " + (change.was ? "P" + std::to_string(*change.was) : "no P") + ")";
  }
  return "the tool table's P column disagreed with the changer's rack, which it shows: " + where +
         "; P written back as the changer has it. Editing P moves no tool: to put a tool into "
         "another pocket, unload it, then load it with the Pocket box (pocket-number) set to that "
         "pocket";
}

}  // namespace fatc
