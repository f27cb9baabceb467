#include "json_text.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include "quote.hpp"

namespace fatc {
namespace {

/// The end of a long JSON path, "…" before it: deep down the path repeats
/// every key on the way, and its end says where.
std::string path_end(const std::string& path) {
  constexpr std::size_t kLongest = 200;
  if (path.size() <= kLongest) return path;
  std::size_t start = path.size() - kLongest;
  while (start < path.size() && (static_cast<unsigned char>(path[start]) & 0xC0) == 0x80) ++start;
  return "\u2026" + path.substr(start);
}

using Json = nlohmann::json;

/// Most duplicate keys named; the rest are only counted.
constexpr std::size_t kMaxDuplicatesNamed = 10;

/// Where the bracket that opens nesting level `level` is, scanning the text
/// as JSON (strings skipped). Only asked once the parser stopped there, so
/// the text up to it is valid JSON.
std::size_t offset_of_level(const std::string& text, std::size_t level) {
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth == level) return i;
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
    }
  }
  return text.size();
}

/// nlohmann's message without its prefix, the token it repeats escaped and
/// cut short: "syntax error while parsing value - invalid literal; last read: 'tru!'".
std::string what_of(const Json::exception& e, const std::string& last_token) {
  std::string what = e.what();
  if (const auto bracket = what.find("] ");
      what.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos) {
    what.erase(0, bracket + 2);
  }
  if (what.rfind("parse error", 0) == 0) {
    if (const auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
  }
  if (!last_token.empty()) {
    const std::string verbatim = "'" + last_token + "'";
    if (const auto at = what.find(verbatim); at != std::string::npos) {
      what.replace(at, verbatim.size(), "'" + escape(last_token) + "'");
    }
  }
  return what;
}

/// Builds the DOM like nlohmann's own SAX DOM parser, and on the way refuses
/// nesting deeper than kMaxJsonDepth and notes keys an object already had.
/// Each open container keeps its own key set, so the work is linear in the
/// text; a path is only spelled out for a duplicate.
class StrictBuilder {
 public:
  explicit StrictBuilder(Json& root) : root_(root) {}

  std::vector<std::string> duplicates;
  std::size_t more_duplicates = 0;
  bool too_deep = false;
  std::string syntax_error;  ///< set by parse_error(): "line L, column C: invalid JSON: ..."
  const std::string* text = nullptr;

  bool null() { return put(nullptr); }
  bool boolean(bool value) { return put(value); }
  bool number_integer(Json::number_integer_t value) { return put(value); }
  bool number_unsigned(Json::number_unsigned_t value) { return put(value); }
  bool number_float(Json::number_float_t value, const std::string&) { return put(value); }
  bool string(std::string& value) { return put(std::move(value)); }
  bool binary(Json::binary_t&) { return false; }  // never in JSON text

  bool start_object(std::size_t) { return open(Json::value_t::object); }
  bool start_array(std::size_t) { return open(Json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& key) {
    Frame& frame = open_.back();
    if (!frame.keys.insert(key).second) {
      if (duplicates.size() < kMaxDuplicatesNamed) {
        duplicates.push_back(path_end(join_path(path(), key)) + ": appears twice");
      } else {
        ++more_duplicates;
      }
    }
    frame.key = std::move(key);
    return true;
  }

  bool parse_error(std::size_t position, const std::string& last_token, const Json::exception& e) {
    // nlohmann counts the byte that failed as read: the error is at the one before.
    syntax_error = describe(position_of(*text, position == 0 ? 0 : position - 1)) +
                   ": invalid JSON: " + what_of(e, last_token);
    return false;
  }

 private:
  struct Frame {
    Json* value;
    std::set<std::string> keys;  ///< objects: the keys so far
    std::string key;             ///< objects: the key being read
  };

  /// The path to the value being read: keys of objects, indexes of arrays.
  std::string path() const {
    std::string out;
    for (std::size_t i = 0; i + 1 < open_.size(); ++i) {
      const Frame& frame = open_[i];
      out = join_path(
          out, frame.value->is_object() ? frame.key : std::to_string(frame.value->size() - 1));
    }
    return out;
  }

  template <typename Value>
  Json* place(Value&& value) {
    if (open_.empty()) {
      root_ = Json(std::forward<Value>(value));
      return &root_;
    }
    Frame& frame = open_.back();
    if (frame.value->is_object()) {
      Json& slot = (*frame.value)[frame.key];
      slot = Json(std::forward<Value>(value));  // a duplicate: reported, the last kept
      return &slot;
    }
    frame.value->push_back(Json(std::forward<Value>(value)));
    return &frame.value->back();
  }

  template <typename Value>
  bool put(Value&& value) {
    place(std::forward<Value>(value));
    return true;
  }

  bool open(Json::value_t type) {
    if (open_.size() >= kMaxJsonDepth) {
      too_deep = true;
      return false;
    }
    Json* value = place(type);
    open_.push_back(Frame{value, {}, {}});
    return true;
  }

  bool close() {
    open_.pop_back();
    return true;
  }

  Json& root_;
  std::vector<Frame> open_;
};

}  // namespace

std::string join_path(const std::string& parent, const std::string& key) {
  const std::string shown = escape(key);
  return parent.empty() ? shown : parent + "." + shown;
}

std::string describe(const Json& value) {
  switch (value.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::object:
      return "an object";
    case Json::value_t::array:
      return "an array";
    case Json::value_t::string:
      return quote(value.get_ref<const std::string&>());
    default:
      return value.dump();
  }
}

std::optional<int> tool_number_key(const std::string& key) {
  if (key.empty() || key.size() > 9 || key[0] == '0') return std::nullopt;
  if (!std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  return std::stoi(key);
}

bool is_tool_number(const Json& value) {
  if (value.is_number_unsigned()) {
    return value.get<std::uint64_t>() >= 1 && value.get<std::uint64_t>() <= 999999999;
  }
  return value.is_number_integer() && value.get<std::int64_t>() >= 1 &&
         value.get<std::int64_t>() <= 999999999;
}

JsonText parse_json_text(const std::string& text) {
  JsonText result;
  if (const std::string nul = nul_byte_problem(text); !nul.empty()) {
    result.errors.push_back(nul);
    return result;
  }
  Json root;
  StrictBuilder builder(root);
  builder.text = &text;
  const bool complete = Json::sax_parse(text, &builder);
  if (builder.too_deep) {
    result.errors.push_back(describe(position_of(text, offset_of_level(text, kMaxJsonDepth + 1))) +
                            ": nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    return result;
  }
  if (!builder.syntax_error.empty() || !complete) {
    result.errors.push_back(builder.syntax_error.empty() ? "invalid JSON" : builder.syntax_error);
    return result;
  }
  if (!builder.duplicates.empty()) {
    result.errors = builder.duplicates;
    if (builder.more_duplicates > 0) {
      result.errors.push_back("and " + std::to_string(builder.more_duplicates) +
                              " more keys that appear twice");
    }
    return result;
  }
  result.value = std::move(root);
  return result;
}

}  // namespace fatc
