// STATE.log: what the component says on stderr, kept beside the state file.
#include "io/message_log.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <ostream>
#include <sstream>

#include "temp_folder.hpp"

namespace fatc::io {
namespace {

using Log = test::TempFolder;

TEST_F(Log, shouldKeepEachLineWithItsTimeAndPassItOn) {
  std::stringstream terminal;
  const std::string path = folder_ + "/state.json.log";
  {
    MessageLog log(path, terminal.rdbuf());
    std::ostream err(&log);
    err << "fixed_atc_probe: info: 0.1.0 started with c.json" << std::endl;
    err << "fixed_atc_probe: info: tool 3 measured 29.998 mm, in pocket 3" << std::endl;
  }
  EXPECT_EQ(terminal.str(),
            "fixed_atc_probe: info: 0.1.0 started with c.json\n"
            "fixed_atc_probe: info: tool 3 measured 29.998 mm, in pocket 3\n");
  const std::string kept = test::text_of(path);
  EXPECT_NE(kept.find(" fixed_atc_probe: info: 0.1.0 started with c.json\n"), std::string::npos)
      << kept;
  EXPECT_NE(kept.find(" fixed_atc_probe: info: tool 3 measured"), std::string::npos) << kept;
  EXPECT_EQ(kept.substr(0, 2), "20") << "each line starts with the date";
}

TEST_F(Log, shouldNotWriteThroughALinkAndSaySoOnce) {
  std::stringstream terminal;
  const std::string target = folder_ + "/config.json";
  { std::ofstream(target) << "{}"; }
  const std::string path = folder_ + "/state.json.log";
  ASSERT_EQ(::symlink(target.c_str(), path.c_str()), 0);
  {
    MessageLog log(path, terminal.rdbuf());
    std::ostream err(&log);
    err << "one\n" << "two\n";
  }
  EXPECT_EQ(test::text_of(target), "{}");
  EXPECT_EQ(terminal.str(),
            "one\nfixed_atc_probe: " + path + ": no log kept (a symbolic link)\ntwo\n");
}

TEST_F(Log, shouldMoveAFullLogAsideAndStartANewOne) {
  std::stringstream terminal;
  const std::string path = folder_ + "/state.json.log";
  { std::ofstream(path) << std::string(MessageLog::kLimit + 1, 'x') << "\n"; }
  {
    MessageLog log(path, terminal.rdbuf());
    std::ostream err(&log);
    err << "after\n";
  }
  EXPECT_EQ(test::text_of(path + ".1").size(), static_cast<std::size_t>(MessageLog::kLimit + 2));
  EXPECT_NE(test::text_of(path).find(" after\n"), std::string::npos);
}

}  // namespace
}  // namespace fatc::io
