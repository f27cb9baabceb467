#include "paths.hpp"

#include <sys/stat.h>

#include "core/config/quote.hpp"

namespace fatc::io {
namespace {

/// What a non-regular file is, for "expected a regular file, got ...".
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "something that is not a file";
}

}  // namespace

std::string shown_path(const std::string& path) {
  return path.empty() ? std::string("\"\" (an empty path)") : escape(path, 200);
}

std::string folder_of(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string beside(const std::string& ini_path, const std::string& path) {
  return !path.empty() && path[0] == '/' ? path : folder_of(ini_path) + "/" + path;
}

std::string not_a_regular_file(const std::string& path, mode_t mode) {
  if (S_ISREG(mode)) return "";
  return shown_path(path) + ": expected a regular file, got " + kind_of(mode);
}

}  // namespace fatc::io
