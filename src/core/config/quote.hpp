#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace fatc {

/// How many characters of user text a message shows before "…".
constexpr std::size_t kQuotedLength = 60;

/// User text made safe to print inside a message: control characters, escape
/// sequences, invalid UTF-8 and the characters that show as nothing or
/// reorder text (bidirectional marks, zero-width characters, the soft hyphen,
/// tags) become visible escapes (\n, \x1b, \u{202e}), a backslash is doubled, and anything past
/// `max_chars` characters is cut off with "…". No quotes around it: for JSON
/// paths and file paths.
std::string escape(std::string_view text, std::size_t max_chars = kQuotedLength);

/// The length (2 to 4) of the valid UTF-8 sequence of a character beyond
/// ASCII at `at` in `text`, its code point in `code`; 0 when the bytes there
/// are none (ASCII, a stray byte, an overlong form, a surrogate).
std::size_t decode_utf8(std::string_view text, std::size_t at, char32_t& code);

/// escape() in double quotes, a double quote inside escaped: every piece of user text a message
/// repeats (values, arguments, INI values) goes through here.
std::string quote(std::string_view text, std::size_t max_chars = kQuotedLength);

/// Whether `text` holds a character escape() shows as \u{...}: one that shows
/// as nothing, hides or reorders text (bidirectional marks, tags ...).
bool has_invisible_characters(std::string_view text);

/// The longest line of a message, in characters: a list longer than fits
/// ends "… and N more", anything else is cut with "…".
constexpr std::size_t kMaxMessageLine = 400;

/// `text` cut to kMaxMessageLine characters (the last one "…"), each of its lines.
std::string capped_lines(std::string_view text);

/// `items` joined by `separator`, at most `max_items` of them, then "… and N more".
std::string listed(const std::vector<std::string>& items, const char* separator = ", ",
                   std::size_t max_items = 20);

/// Line and column (both from 1, the column counted in bytes) of `offset` in `text`.
struct TextPosition {
  std::size_t line = 1;
  std::size_t column = 1;
};
TextPosition position_of(std::string_view text, std::size_t offset);
/// "line 3, column 7"
std::string describe(const TextPosition& position);

/// "line L, column C: NUL byte, ..." when `text` has a NUL byte (readers in C
/// would silently stop there); empty otherwise.
std::string nul_byte_problem(std::string_view text);

}  // namespace fatc
