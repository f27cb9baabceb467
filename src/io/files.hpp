#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/config/config.hpp"
#include "core/rack/tool_state.hpp"
#include "file_writer.hpp"
#include "paths.hpp"

namespace fatc::io {

/// Largest config, state or INI file read: real ones are a few kilobytes.
constexpr std::size_t kMaxFileBytes = 1024 * 1024;

/// The whole text of a regular file of at most kMaxFileBytes; nullopt and one
/// line in `error` ("PATH: expected a regular file, got a FIFO") otherwise.
/// Never blocks: a FIFO is opened non-blocking and refused before any read.
std::optional<std::string> read_small_file(const std::string& path, std::string& error);

/// When a file was last written and how long it is: a file LinuxCNC rewrites
/// in place (the tool table) has changed when its stamp has.
struct FileStamp {
  std::int64_t seconds = 0;
  long nanoseconds = 0;
  std::int64_t size = 0;
  bool operator==(const FileStamp& other) const {
    return seconds == other.seconds && nanoseconds == other.nanoseconds && size == other.size;
  }
  bool operator!=(const FileStamp& other) const { return !(*this == other); }
};
/// The file's stamp, or nothing if it cannot be looked at.
std::optional<FileStamp> stamp_of(const std::string& path);

/// Takes one piece of a file as it is read.
using Take = std::function<void(std::string_view piece)>;

/// Hands the first `max_bytes` of a regular file of any size to `take`, piece
/// by piece (never more than 64 KiB of it in memory), and says (`file_bytes`)
/// how big it is; refuses, never blocking, what read_small_file refuses but
/// its size: false and one line in `error`. Fewer than `file_bytes` given:
/// the file was cut.
bool read_file_pieces(const std::string& path, std::size_t max_bytes, std::uint64_t& file_bytes,
                      std::string& error, const Take& take);

/// Where scratch files go: $TMPDIR (else /tmp) as an absolute folder, a
/// relative one taken from the current folder (rs274 runs in another, the
/// INI's). Nullopt and one line naming TMPDIR in `error` when it cannot be
/// made absolute or is longer than `longest` characters.
std::optional<std::string> scratch_root(std::size_t longest, std::string& error);

/// Reads and validates a config.json; every message starts with the file's path.
ConfigResult load_config_file(const std::string& path);

/// Reads the saved tool state. A missing file is a first start (every pocket
/// full, spindle empty); anything unreadable or inconsistent with the config
/// is an error naming the file, never a silent reset.
ToolStateResult load_state_file(const std::string& path, const Config& config);
/// The same without a config to compare with (--check of a state file next to
/// a broken config): everything but the pockets the config must have.
ToolStateResult load_state_file(const std::string& path);

/// Writes the tool state crash-safe through FileWriter, waiting at most
/// `wait` for another writer of it. Throws std::runtime_error naming the file
/// on failure.
void save_state_file(const std::string& path, const ToolState& state,
                     std::chrono::milliseconds wait);

/// Writes a taught config.json, taken by `config` before it was read: first
/// `previous` (the text it was read as) to PATH.bak, replacing an older
/// backup, then `text` to PATH, each through FileWriter, both with PATH's
/// permissions. Throws std::runtime_error naming the file on failure.
void save_config_file(const FileWriter& config, const std::string& previous,
                      const std::string& text, std::chrono::milliseconds wait);

}  // namespace fatc::io
