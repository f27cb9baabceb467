#include "files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fatc::io {
namespace {

std::optional<std::string> read_text(const std::string& path, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = path + ": cannot open (" + std::strerror(errno) + ")";
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

void write_all(int fd, const std::string& text, const std::string& path) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(path + ": cannot write (" + std::strerror(errno) + ")");
    }
    written += static_cast<std::size_t>(n);
  }
}

}  // namespace

ConfigResult load_config_file(const std::string& path) {
  ConfigResult result;
  std::string error;
  const auto text = read_text(path, error);
  if (!text) {
    result.errors.push_back(error);
    return result;
  }
  result = parse_config(*text);
  for (auto& message : result.errors) message = path + ": " + message;
  return result;
}

ToolStateResult load_state_file(const std::string& path, const Config& config) {
  if (::access(path.c_str(), F_OK) != 0 && errno == ENOENT) return {ToolState::fresh(config), ""};
  std::string error;
  const auto text = read_text(path, error);
  if (!text) return {std::nullopt, error};
  auto result = tool_state_from_json(*text);
  if (!result.state) return {std::nullopt, path + ": " + result.error};
  const ToolState& state = *result.state;
  auto unknown = [&](int tool) { return tool != 0 && !config.has_pocket(tool); };
  for (const int tool : state.in_pocket) {
    if (unknown(tool)) {
      return {std::nullopt, path + ": in_pocket: tool " + std::to_string(tool) +
                                " is recorded in a pocket that config.json does not have"};
    }
  }
  return result;
}

void save_state_file(const std::string& path, const ToolState& state) {
  const std::string temporary = path + ".tmp";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error(temporary + ": cannot create (" + std::strerror(errno) + ")");
  try {
    write_all(fd, to_json(state), temporary);
    if (::fsync(fd) != 0) throw std::runtime_error(temporary + ": fsync failed (" + std::strerror(errno) + ")");
  } catch (...) {
    ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  ::close(fd);
  if (::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(temporary.c_str());
    throw std::runtime_error(path + ": cannot replace (" + why + ")");
  }
  // The rename itself must reach the disk before we call the state saved.
  const int folder = ::open(folder_of(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (folder >= 0) {
    ::fsync(folder);
    ::close(folder);
  }
}

}  // namespace fatc::io
