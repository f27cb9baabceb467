#include "quote.hpp"

#include <cstdio>

namespace fatc {

std::size_t decode_utf8(std::string_view text, std::size_t at, char32_t& code) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  std::size_t length = 0;
  char32_t minimum = 0;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2, code = lead & 0x1F, minimum = 0x80;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3, code = lead & 0x0F, minimum = 0x800;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4, code = lead & 0x07, minimum = 0x10000;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  for (std::size_t i = 1; i < length; ++i) {
    if ((byte(at + i) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(at + i) & 0x3F);
  }
  if (code < minimum || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return 0;
  return length;
}

namespace {

/// Characters a terminal would act on, or that show as nothing, hide or
/// reorder text: C1 controls, Unicode's format characters (bidirectional
/// marks and isolates, zero-width characters, the soft hyphen, tags),
/// variation selectors and the fillers that draw as blank letters.
bool invisible(char32_t code) {
  struct Range {
    char32_t first, last;
  };
  static constexpr Range kInvisible[] = {
      {0x0080, 0x009F},    // C1 controls (CSI among them)
      {0x00AD, 0x00AD},    // soft hyphen
      {0x034F, 0x034F},    // combining grapheme joiner
      {0x0600, 0x0605},    // Arabic number signs
      {0x061C, 0x061C},    // Arabic letter mark
      {0x06DD, 0x06DD},    // Arabic end of ayah
      {0x070F, 0x070F},    // Syriac abbreviation mark
      {0x08E2, 0x08E2},    // Arabic disputed end of ayah
      {0x115F, 0x1160},    // Hangul fillers
      {0x17B4, 0x17B5},    // Khmer inherent vowels
      {0x180B, 0x180F},    // Mongolian variation selectors and vowel separator
      {0x200B, 0x200F},    // zero-width space, non-joiner, joiner; LRM, RLM
      {0x2028, 0x202E},    // line and paragraph separators; embeddings, overrides
      {0x2060, 0x206F},    // word joiner, invisible operators, isolates (2066-2069)
      {0x3164, 0x3164},    // Hangul filler
      {0xFE00, 0xFE0F},    // variation selectors
      {0xFEFF, 0xFEFF},    // zero-width no-break space (byte order mark)
      {0xFFA0, 0xFFA0},    // halfwidth Hangul filler
      {0xFFF9, 0xFFFB},    // interlinear annotation
      {0x110BD, 0x110BD},  // Kaithi number sign
      {0x110CD, 0x110CD},  // Kaithi number sign above
      {0x13430, 0x1343F},  // Egyptian hieroglyph format controls
      {0x1BCA0, 0x1BCA3},  // shorthand format controls
      {0x1D173, 0x1D17A},  // musical symbol format controls
      {0xE0000, 0xE0FFF},  // tags (E0000-E007F) and variation selectors supplement
  };
  for (const Range& range : kInvisible) {
    if (code >= range.first && code <= range.last) return true;
  }
  return false;
}

std::string escape(std::string_view text, std::size_t max_chars, bool in_quotes) {
  std::string out;
  std::size_t chars = 0;
  std::size_t at = 0;
  char buffer[16];
  while (at < text.size()) {
    if (chars == max_chars) {
      out += "\u2026";
      break;
    }
    ++chars;
    const unsigned char c = static_cast<unsigned char>(text[at]);
    if (c >= 0x20 && c < 0x7F) {
      if ((c == '"' && in_quotes) || c == '\\') out += '\\';
      out += static_cast<char>(c);
      ++at;
    } else if (c == '\n') {
      out += "\\n", ++at;
    } else if (c == '\r') {
      out += "\\r", ++at;
    } else if (c == '\t') {
      out += "\\t", ++at;
    } else if (c < 0x80) {
      std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
      out += buffer, ++at;
    } else {
      char32_t code = 0;
      const std::size_t length = decode_utf8(text, at, code);
      if (length == 0) {
        std::snprintf(buffer, sizeof buffer, "\\x%02x", c);
        out += buffer, ++at;
      } else if (invisible(code)) {
        std::snprintf(buffer, sizeof buffer, "\\u{%04x}", static_cast<unsigned>(code));
        out += buffer, at += length;
      } else {
        out.append(text.substr(at, length)), at += length;
      }
    }
  }
  return out;
}

}  // namespace

std::string escape(std::string_view text, std::size_t max_chars) {
  return escape(text, max_chars, false);
}

std::string quote(std::string_view text, std::size_t max_chars) {
  return "\"" + escape(text, max_chars, true) + "\"";
}

bool has_invisible_characters(std::string_view text) {
  for (std::size_t at = 0; at < text.size();) {
    char32_t code = 0;
    const std::size_t length = decode_utf8(text, at, code);
    if (length > 0 && invisible(code)) return true;
    at += length > 0 ? length : 1;
  }
  return false;
}

std::string capped_lines(std::string_view text) {
  std::string out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    // Where each character starts; past the limit the last one kept is "…".
    std::size_t chars = 0;
    std::size_t cut = line.size();
    for (std::size_t at = 0; at < line.size(); ++at) {
      if ((static_cast<unsigned char>(line[at]) & 0xC0) == 0x80) continue;
      if (++chars == kMaxMessageLine) cut = at;
      if (chars > kMaxMessageLine) break;
    }
    out +=
        chars > kMaxMessageLine ? std::string(line.substr(0, cut)) + "\u2026" : std::string(line);
    if (end < text.size()) out += '\n';
    start = end + 1;
  }
  return out;
}

std::string listed(const std::vector<std::string>& items, const char* separator,
                   std::size_t max_items) {
  std::string text;
  for (std::size_t i = 0; i < items.size() && i < max_items; ++i) {
    text += (i == 0 ? "" : separator) + items[i];
  }
  if (items.size() > max_items) {
    text += " \u2026 and " + std::to_string(items.size() - max_items) + " more";
  }
  return text;
}

TextPosition position_of(std::string_view text, std::size_t offset) {
  TextPosition position;
  const std::size_t end = offset < text.size() ? offset : text.size();
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else {
      ++position.column;
    }
  }
  return position;
}

std::string describe(const TextPosition& position) {
  return "line " + std::to_string(position.line) + ", column " + std::to_string(position.column);
}

std::string nul_byte_problem(std::string_view text) {
  const auto nul = text.find('\0');
  if (nul == std::string_view::npos) return "";
  return describe(position_of(text, nul)) +
         ": expected text, found a NUL byte (a binary or damaged file?)";
}

}  // namespace fatc
