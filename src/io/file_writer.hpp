#pragma once

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>

namespace fatc::io {

/// How long a command-line writer waits for another writer of the same file.
constexpr std::chrono::milliseconds kCommandLineWait{5000};
/// How long the component waits: its poll loop must keep the chuck guard's
/// heartbeat going (0.5 s), so it gives up early and says so.
constexpr std::chrono::milliseconds kComponentWait{200};

/// How a file is replaced.
struct ReplaceOptions {
  /// fsync the new file and its folder before calling it written; false only
  /// for a file whose loss loses nothing (the status file, rewritten often).
  bool durable = true;
  /// The new file's permissions; unset: the old file's, or 0666 less the umask.
  std::optional<mode_t> mode;
};

/// The one way this program writes a file: --plot's drawing, config.json and
/// its .bak on a teach, the state file and the status file.
///
/// A file is never written into, only replaced: a new file is created
/// exclusively (O_EXCL, O_NOFOLLOW) under an unpredictable name in the
/// target's folder, written, fsynced and renamed over the target, so a reader
/// sees the old file or the new one, and no link or FIFO planted at a name the
/// writer uses is ever followed or opened. What it does with a target, decided
/// once for every file (each refusal one line, nothing written):
/// - a symbolic link: refused, the rename would replace the link and leave what
///   it points to as it was;
/// - a file with more than one name (hard links): refused, the other names
///   would keep the old text;
/// - a read-only file (no write permission for anyone, or none for this
///   user): refused, replacing it would get round its mode;
/// - a FIFO, device or folder: refused without being opened for writing;
/// - a regular file: replaced, its permissions kept.
///
/// Writers of one file take turns: the target is locked (flock on the file,
/// checked to still be the one the path names once the lock is held) from
/// construction until the writer goes, so a writer that reads the file after
/// taking it, changes and replaces it loses no other writer's update. Under
/// the lock, the temporary files a killed writer of the same file left are
/// removed.
class FileWriter {
 public:
  /// Takes `path` for this writer alone, waiting at most `wait` for another
  /// writer of it. A file not there yet is not locked (nothing to read).
  /// Throws std::runtime_error with one line naming the file when the target
  /// is refused or another writer keeps it longer than `wait`.
  FileWriter(std::string path, std::chrono::milliseconds wait);
  ~FileWriter();
  FileWriter(const FileWriter&) = delete;
  FileWriter& operator=(const FileWriter&) = delete;

  /// Replaces the file with `text`. Throws std::runtime_error with one line
  /// naming the file on failure; the old file is then untouched.
  void replace(const std::string& text, const ReplaceOptions& how = {}) const;

  const std::string& path() const { return path_; }
  /// The permissions of the file taken, if it was there.
  std::optional<mode_t> mode() const { return mode_; }

 private:
  void remove_leftovers() const;

  std::string path_;
  int locked_ = -1;  ///< the target, flocked; -1 when it did not exist
  std::optional<mode_t> mode_;
};

/// One writer's turn in one go: takes `path` (waiting at most `wait`) and replaces it.
void write_file(const std::string& path, const std::string& text, std::chrono::milliseconds wait,
                const ReplaceOptions& how = {});

/// Whether `a` and `b` name one file: the same file once links are followed,
/// or, when neither exists, the same path.
bool same_file(const std::string& a, const std::string& b);

}  // namespace fatc::io
