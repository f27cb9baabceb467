#include "quote.hpp"

#include <cstdio>

namespace fatc {
namespace {

/// The length of the valid UTF-8 sequence at `at` and its code point, or 0.
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

/// Characters a terminal would act on or that hide or reorder text.
bool invisible(char32_t code) {
  return (code >= 0x80 && code <= 0x9F) || (code >= 0x200B && code <= 0x200F) ||
         (code >= 0x2028 && code <= 0x202E) || (code >= 0x2060 && code <= 0x206F) || code == 0xFEFF;
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
