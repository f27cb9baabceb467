#pragma once

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace fatc::test {

/// A fixture with a folder of its own under /tmp, removed with all in it.
class TempFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/fatc_test_XXXXXX";
    folder_ = ::mkdtemp(pattern);
  }
  void TearDown() override {
    ::chmod(folder_.c_str(), 0700);  // a test may have made it read-only
    std::filesystem::remove_all(folder_);
  }
  std::string folder_;
};

/// The whole text of a file, "" when it cannot be read.
inline std::string text_of(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace fatc::test
