#include "file_writer.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include "paths.hpp"

namespace fatc::io {
namespace {

using Clock = std::chrono::steady_clock;

std::string why(int error) { return std::string("(") + std::strerror(error) + ")"; }

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw std::runtime_error(shown_path(path) + ": " + what);
}

/// The name after the last '/'.
std::string name_of(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// "FOLDER/.NAME." : every temporary file of `path` starts so. The name is
/// cut short so that the whole stays within a file name's 255 bytes.
std::string temporary_prefix(const std::string& path) {
  const std::string folder = folder_of(path);
  return (folder == "/" ? "" : folder) + "/." + name_of(path).substr(0, 200) + ".";
}
constexpr std::size_t kRandomChars = 12;
constexpr const char* kTemporarySuffix = ".tmp";

/// Twelve letters and digits from the kernel's random source: a name nobody
/// can plant a link or a FIFO at ahead of time.
std::string random_word() {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
  unsigned char bytes[kRandomChars];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error("no random name for a temporary file " + why(errno));
    got += static_cast<std::size_t>(n);
  }
  std::string word;
  for (const unsigned char b : bytes) word += kAlphabet[b % (sizeof kAlphabet - 1)];
  return word;
}

/// One line when `path` (lstat'ed as `st`) is a target this writer refuses.
void refuse_target(const std::string& path, const struct stat& st) {
  if (S_ISLNK(st.st_mode)) {
    std::string target(4096, '\0');
    const ssize_t n = ::readlink(path.c_str(), &target[0], target.size());
    target.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    refuse(path, "a symbolic link (to " + shown_path(target) +
                     "): not written, the link would become a file of its own; give the file it "
                     "points to");
  }
  if (const std::string refused = not_a_regular_file(path, st.st_mode); !refused.empty()) {
    throw std::runtime_error(refused + ": not written");
  }
  if (st.st_nlink > 1) {
    refuse(path, "has " + std::to_string(st.st_nlink) +
                     " names (hard links): not written, the other names would keep the old text");
  }
  // Marked read-only (even root is stopped), or not this user's to write.
  if ((st.st_mode & 0222) == 0) {
    char mode[16];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    refuse(path, std::string("read-only (mode ") + mode + "): not written");
  }
  if (::faccessat(AT_FDCWD, path.c_str(), W_OK, AT_EACCESS) != 0) {
    refuse(path, "read-only for this user " + why(errno) + ": not written");
  }
}

}  // namespace

FileWriter::FileWriter(std::string path, std::chrono::milliseconds wait) : path_(std::move(path)) {
  if (path_.empty()) refuse(path_, "expected a file path, got nothing");
  const auto deadline = Clock::now() + wait;
  for (;;) {
    struct stat st;
    if (::lstat(path_.c_str(), &st) != 0) {
      if (errno == ENOENT) return;  // a new file: nothing to lock or keep
      refuse(path_, "cannot write " + why(errno));
    }
    refuse_target(path_, st);
    // O_NONBLOCK, O_NOFOLLOW: a FIFO or a link swapped in since the lstat
    // neither blocks nor is followed (and is refused by the fstat below).
    const int fd = ::open(path_.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) {
      if (errno == ENOENT) continue;
      refuse(path_, "cannot open " + why(errno) + ": not written");
    }
    struct stat held;
    if (::fstat(fd, &held) != 0 || !S_ISREG(held.st_mode)) {
      ::close(fd);
      continue;  // changed under us: look again
    }
    while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      if (errno != EWOULDBLOCK && errno != EINTR) {
        const int error = errno;
        ::close(fd);
        refuse(path_, "cannot lock " + why(error) + ": not written");
      }
      if (Clock::now() >= deadline) {
        ::close(fd);
        char waited[32];
        std::snprintf(waited, sizeof waited, "%g", wait.count() / 1000.0);
        refuse(path_,
               std::string("another program is writing it (waited ") + waited + " s): not written");
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    // The writer before may have replaced the file while we waited: the lock
    // counts only on the file the path names now.
    struct stat now;
    if (::lstat(path_.c_str(), &now) == 0 && now.st_dev == held.st_dev &&
        now.st_ino == held.st_ino) {
      try {
        refuse_target(path_, now);  // what it is now, with the lock held
      } catch (...) {
        ::close(fd);  // a constructor that throws has no destructor to do it
        throw;
      }
      locked_ = fd;
      mode_ = now.st_mode & 07777;
      remove_leftovers();
      return;
    }
    ::close(fd);
  }
}

FileWriter::~FileWriter() {
  if (locked_ >= 0) ::close(locked_);  // closing releases the lock
}

void FileWriter::remove_leftovers() const {
  const std::string prefix = temporary_prefix(path_);
  const std::string start = prefix.substr(prefix.rfind('/') + 1);
  const std::size_t length = start.size() + kRandomChars + std::strlen(kTemporarySuffix);
  DIR* folder = ::opendir(folder_of(path_).c_str());
  if (folder == nullptr) return;  // the write itself will say what is wrong
  while (const dirent* entry = ::readdir(folder)) {
    const std::string name = entry->d_name;
    if (name.size() == length && name.compare(0, start.size(), start) == 0 &&
        name.compare(length - std::strlen(kTemporarySuffix), std::string::npos, kTemporarySuffix) ==
            0) {
      ::unlinkat(::dirfd(folder), name.c_str(), 0);  // a link is removed, not followed
    }
  }
  ::closedir(folder);
}

void FileWriter::replace(const std::string& text, const ReplaceOptions& how) const {
  const std::optional<mode_t> mode = how.mode ? how.mode : mode_;
  std::string temporary;
  int fd = -1;
  for (int attempt = 0; fd < 0; ++attempt) {
    temporary = temporary_prefix(path_) + random_word() + kTemporarySuffix;
    // Never more open than the file it replaces, not even for a moment.
    fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                mode ? *mode & 0666 : 0666);
    if (fd < 0 && (errno != EEXIST || attempt == 20)) {
      refuse(path_, "cannot create a temporary file in " + shown_path(folder_of(path_)) + " " +
                        why(errno) + ": not written");
    }
  }
  try {
    if (mode && ::fchmod(fd, *mode) != 0) {
      refuse(path_, "cannot set the mode " + why(errno) + ": not written");
    }
    std::size_t written = 0;
    while (written < text.size()) {
      const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) refuse(path_, "cannot write " + why(errno) + ": not written");
      written += static_cast<std::size_t>(n);
    }
    if (how.durable && ::fsync(fd) != 0) {
      refuse(path_, "fsync failed " + why(errno) + ": not written");
    }
  } catch (...) {
    ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  ::close(fd);
  if (::rename(temporary.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    refuse(path_, "cannot replace " + why(error) + ": not written");
  }
  if (!how.durable) return;
  // The rename itself must reach the disk before the file is called written.
  const int folder = ::open(folder_of(path_).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder >= 0) {
    ::fsync(folder);
    ::close(folder);
  }
}

void write_file(const std::string& path, const std::string& text, std::chrono::milliseconds wait,
                const ReplaceOptions& how) {
  FileWriter(path, wait).replace(text, how);
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat first, second;
  const bool has_first = ::stat(a.c_str(), &first) == 0;
  const bool has_second = ::stat(b.c_str(), &second) == 0;
  if (has_first && has_second)
    return first.st_dev == second.st_dev && first.st_ino == second.st_ino;
  if (has_first || has_second) return false;
  std::error_code failed;
  const auto normal = [&](const std::string& path) {
    return std::filesystem::absolute(path, failed).lexically_normal();
  };
  return normal(a) == normal(b);
}

}  // namespace fatc::io
