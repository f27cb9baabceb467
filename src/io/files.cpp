#include "files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/config/quote.hpp"

namespace fatc::io {
namespace {

std::string why(int error) { return std::string("(") + std::strerror(error) + ")"; }

/// One line when `st` is not a regular file, or (`limit_size`) one over kMaxFileBytes.
std::string refusal(const std::string& path, const struct stat& st, bool limit_size = true) {
  if (std::string refused = not_a_regular_file(path, st.st_mode); !refused.empty()) return refused;
  if (limit_size && static_cast<unsigned long long>(st.st_size) > kMaxFileBytes) {
    return shown_path(path) + ": expected a file of at most 1 MiB, got " +
           std::to_string(st.st_size) + " bytes";
  }
  return "";
}

/// Closes a descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

bool missing(const std::string& path) {
  struct stat st;
  return !path.empty() && ::stat(path.c_str(), &st) != 0 && errno == ENOENT;
}

}  // namespace

std::optional<std::string> scratch_root(std::size_t longest, std::string& error) {
  const char* given = std::getenv("TMPDIR");
  std::string folder = given != nullptr && *given != '\0' ? given : "/tmp";
  if (folder[0] != '/') {
    std::vector<char> here(PATH_MAX);
    if (::getcwd(here.data(), here.size()) == nullptr) {
      error = "TMPDIR " + quote(folder, 200) + " is a relative folder and the current folder " +
              "cannot be read " + why(errno) + ": set TMPDIR to an absolute folder";
      return std::nullopt;
    }
    folder = std::string(here.data()) + "/" + folder;
  }
  if (folder.size() > longest) {
    error = "TMPDIR " + quote(folder, 200) + " is " + std::to_string(folder.size()) +
            " characters long, over the " + std::to_string(longest) +
            " its scratch files' paths leave: set TMPDIR to a shorter folder";
    return std::nullopt;
  }
  return folder;
}

namespace {

/// Hands a regular file to `take` piece by piece, at most `max_bytes` + 1
/// bytes in all, refusing anything else before a read; `limit_size`: a file
/// over kMaxFileBytes is refused by its size.
bool read_regular(const std::string& path, std::size_t max_bytes, bool limit_size,
                  std::uint64_t& file_bytes, std::string& error, const Take& take) {
  if (path.empty()) {
    error = shown_path(path) + ": expected a file path, got nothing";
    return false;
  }
  // Refuse devices and FIFOs before opening them at all (opening some devices
  // does something), then again on what was opened, in case it changed.
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) {
    error = shown_path(path) + ": cannot open " + why(errno);
    return false;
  }
  if (std::string refused = refusal(path, st, limit_size); !refused.empty()) {
    error = refused;
    return false;
  }
  // O_NONBLOCK: a FIFO swapped in after the stat cannot make open() wait.
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC)};
  if (file.fd < 0) {
    error = shown_path(path) + ": cannot open " + why(errno);
    return false;
  }
  if (::fstat(file.fd, &st) != 0) {
    error = shown_path(path) + ": cannot read " + why(errno);
    return false;
  }
  if (std::string refused = refusal(path, st, limit_size); !refused.empty()) {
    error = refused;
    return false;
  }
  file_bytes = static_cast<std::uint64_t>(st.st_size);
  // One more than the limit tells a file that grew while we read.
  const std::uint64_t wanted = static_cast<std::uint64_t>(max_bytes) + 1;
  std::vector<char> buffer(static_cast<std::size_t>(std::min<std::uint64_t>(wanted, 64 * 1024)));
  for (std::uint64_t size = 0; size < wanted;) {
    const ssize_t n =
        ::read(file.fd, buffer.data(),
               static_cast<std::size_t>(std::min<std::uint64_t>(buffer.size(), wanted - size)));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = shown_path(path) + ": cannot read " + why(errno);
      return false;
    }
    if (n == 0) break;
    size += static_cast<std::uint64_t>(n);
    take(std::string_view(buffer.data(), static_cast<std::size_t>(n)));
  }
  return true;
}

}  // namespace

std::optional<FileStamp> stamp_of(const std::string& path) {
  struct stat about {};
  if (::stat(path.c_str(), &about) != 0) return std::nullopt;
  return FileStamp{about.st_mtim.tv_sec, about.st_mtim.tv_nsec, about.st_size};
}

std::optional<std::string> read_small_file(const std::string& path, std::string& error) {
  std::uint64_t file_bytes = 0;
  std::string text;
  if (!read_regular(path, kMaxFileBytes, true, file_bytes, error,
                    [&](std::string_view piece) { text.append(piece); })) {
    return std::nullopt;
  }
  if (text.size() > kMaxFileBytes) {  // it grew while we read
    error = shown_path(path) + ": expected a file of at most 1 MiB, got more";
    return std::nullopt;
  }
  return text;
}

bool read_file_pieces(const std::string& path, std::size_t max_bytes, std::uint64_t& file_bytes,
                      std::string& error, const Take& take) {
  std::uint64_t seen = 0;
  const bool read =
      read_regular(path, max_bytes, false, file_bytes, error, [&](std::string_view piece) {
        if (seen < max_bytes) take(piece.substr(0, static_cast<std::size_t>(max_bytes - seen)));
        seen += piece.size();
      });
  file_bytes = std::max(file_bytes, seen);
  return read;
}

ConfigResult load_config_file(const std::string& path) {
  ConfigResult result;
  std::string error;
  const auto text = read_small_file(path, error);
  if (!text) {
    result.errors.push_back(error);
    return result;
  }
  result = parse_config(*text);
  // A JSON path deep down repeats many keys: the line is cut, not the message lost.
  for (auto& message : result.errors) message = capped_lines(shown_path(path) + ": " + message);
  return result;
}

ToolStateResult load_state_file(const std::string& path) {
  std::string error;
  const auto text = read_small_file(path, error);
  if (!text) return {std::nullopt, error};
  auto result = tool_state_from_json(*text);
  if (!result.state) return {std::nullopt, capped_lines(shown_path(path) + ": " + result.error)};
  return result;
}

ToolStateResult load_state_file(const std::string& path, const Config& config) {
  if (missing(path)) return {ToolState::fresh(config), ""};
  auto result = load_state_file(path);
  if (!result.state) return result;
  if (const std::string why = fit_to_config(*result.state, config, result.version); !why.empty()) {
    return {std::nullopt, shown_path(path) + ": " + why};
  }
  return result;
}

void save_state_file(const std::string& path, const ToolState& state,
                     std::chrono::milliseconds wait) {
  write_file(path, to_json(state), wait);
}

void save_config_file(const FileWriter& config, const std::string& previous,
                      const std::string& text, std::chrono::milliseconds wait) {
  // The backup holds what the config held: no more open than the config.
  write_file(config.path() + ".bak", previous, wait, {true, config.mode()});
  config.replace(text);
}

}  // namespace fatc::io
