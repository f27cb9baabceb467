#pragma once

#include <streambuf>
#include <vector>

namespace fatc::io {

/// A stream buffer onto a file descriptor (standard output) that keeps the
/// first write error: a full disk (`> /dev/full`) or a closed pipe is
/// reported once at the end, never lost in a stream's fail bit.
class StandardOutput : public std::streambuf {
 public:
  explicit StandardOutput(int fd);
  ~StandardOutput() override;
  StandardOutput(const StandardOutput&) = delete;
  StandardOutput& operator=(const StandardOutput&) = delete;

  /// The errno of the first write that failed, 0 while all went out.
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override;
  int sync() override;

 private:
  /// Writes what is buffered; false once a write has failed.
  bool drain();
  int fd_;
  int error_ = 0;
  std::vector<char> buffer_;
};

}  // namespace fatc::io
