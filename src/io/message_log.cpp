#include "message_log.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

namespace fatc::io {

MessageLog::MessageLog(std::string path, std::streambuf* also)
    : path_(std::move(path)), also_(also) {}

MessageLog::~MessageLog() {
  if (!line_.empty()) write_line();
  if (fd_ >= 0) ::close(fd_);
}

bool MessageLog::open() {
  if (fd_ >= 0) return true;
  if (failed_) return false;
  fd_ = ::open(path_.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC,
               0644);
  struct stat st;
  std::string why;
  if (fd_ < 0) {
    why = errno == ELOOP ? "a symbolic link" : std::strerror(errno);
  } else if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    why = "not a regular file";
  } else if (st.st_nlink > 1) {
    why = "it has a second name (hard link)";
  }
  if (why.empty()) return true;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  failed_ = true;
  const std::string said = "fixed_atc_probe: " + path_ + ": no log kept (" + why + ")\n";
  if (also_) also_->sputn(said.data(), static_cast<std::streamsize>(said.size()));
  return false;
}

void MessageLog::write_line() {
  if (also_) also_->sputn(line_.data(), static_cast<std::streamsize>(line_.size()));
  if (open()) {
    struct stat st;
    if (::fstat(fd_, &st) == 0 && st.st_size > kLimit) {
      // One old log kept: a rename replaces whatever is at .1, a link included, never its target.
      ::rename(path_.c_str(), (path_ + ".1").c_str());
      ::close(fd_);
      fd_ = -1;
    }
  }
  if (open()) {
    char stamp[32];
    const std::time_t now = std::time(nullptr);
    std::tm local{};
    ::localtime_r(&now, &local);
    std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M:%S ", &local);
    const std::string entry = stamp + line_;
    if (::write(fd_, entry.data(), entry.size()) < 0) {
      // A full disk: the machine runs on; stderr still has the line.
    }
  }
  line_.clear();
}

int MessageLog::overflow(int c) {
  if (c == traits_type::eof()) return traits_type::not_eof(c);
  line_ += static_cast<char>(c);
  if (c == '\n') write_line();
  return c;
}

int MessageLog::sync() {
  if (also_) also_->pubsync();
  return 0;
}

}  // namespace fatc::io
