#pragma once

#include <memory>
#include <streambuf>
#include <string>

namespace fatc::io {

/// The component's log, STATE.log beside the state file: every line it says
/// on stderr, with the time. LinuxCNC started without a terminal writes the
/// component's stderr to a temporary file and deletes it on exit; this one
/// stays where the state file is. Lines are appended (O_APPEND), never
/// through a symbolic link or into anything but a regular file with one name;
/// past 1 MiB the log moves to STATE.log.1 (one old log kept) and starts anew.
/// A log that cannot be written is said once and then left alone: the
/// machine runs on without it.
class MessageLog : public std::streambuf {
 public:
  /// A log at `path` whose lines also go on to `also` (stderr's own buffer).
  MessageLog(std::string path, std::streambuf* also);
  ~MessageLog() override;
  MessageLog(const MessageLog&) = delete;
  MessageLog& operator=(const MessageLog&) = delete;

  static constexpr long kLimit = 1 << 20;

 protected:
  int overflow(int c) override;
  int sync() override;

 private:
  void write_line();
  bool open();

  std::string path_;
  std::streambuf* also_;
  std::string line_;
  int fd_ = -1;
  bool failed_ = false;  ///< said once; no more tries
};

}  // namespace fatc::io
