#pragma once

#include <string>

namespace fatc::io {

/// "0.1.0 (29d48c9)": the project's version (CMakeLists.txt's project()) and,
/// built from a git checkout, the commit; the version alone from a tarball.
/// Defined by the file cmake/version.cmake writes at each build, linked into
/// the program alone: a new commit recompiles one file and relinks one binary.
std::string version();

}  // namespace fatc::io
