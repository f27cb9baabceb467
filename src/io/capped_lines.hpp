#pragma once

#include <ostream>
#include <streambuf>
#include <string>

#include "core/config/quote.hpp"

namespace fatc::io {

/// Passes text on to `out` a line at a time, each line cut to
/// kMaxMessageLine characters: no line the command line prints is longer,
/// whatever a file held.
class CappedLines : public std::streambuf {
 public:
  explicit CappedLines(std::ostream& out) : out_(out) {}
  ~CappedLines() override { sync(); }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_ += traits_type::to_char_type(c);
    if (c == '\n') sync();
    return c;
  }
  int sync() override {
    out_ << capped_lines(line_);
    line_.clear();
    return out_.flush() ? 0 : -1;
  }

 private:
  std::ostream& out_;
  std::string line_;
};

}  // namespace fatc::io
