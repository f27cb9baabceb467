#pragma once

// Paths as messages name them (and what a path names when it is no regular
// file), and as LinuxCNC takes them from an INI: what the readers (files.hpp)
// and the writer (file_writer.hpp) share.

#include <sys/types.h>

#include <string>

namespace fatc::io {

/// A file path for a message: control characters escaped, cut short if huge.
std::string shown_path(const std::string& path);

/// The folder of `path`: "." for a bare name, "/" for one at the root.
std::string folder_of(const std::string& path);
/// A path an INI file gives, as LinuxCNC takes it: absolute as it is, else
/// from the folder of the INI file `ini_path`.
std::string beside(const std::string& ini_path, const std::string& path);

/// "PATH: expected a regular file, got a FIFO", or empty for a regular file.
std::string not_a_regular_file(const std::string& path, mode_t mode);

}  // namespace fatc::io
