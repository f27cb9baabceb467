// The one writer of every file the changer writes, tried as a hostile user
// would: links, FIFOs and devices at the target or at a name the writer might
// use, hard links, read-only files and folders, and two writers at once. Each
// refusal is one line, within a second, and leaves every file as it was.
#include "io/file_writer.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <set>
#include <thread>

#include "io/files.hpp"
#include "temp_folder.hpp"

namespace fatc {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

class Writer : public test::TempFolder {
 protected:
  void SetUp() override {
    TempFolder::SetUp();
    path_ = folder_ + "/rack.svg";
    precious_ = folder_ + "/config.json";
    std::ofstream(precious_) << "keep me";
  }
  static std::string read(const std::string& path) { return test::text_of(path); }
  /// The one line write_file() refused with, within a second; "" when it wrote.
  static std::string refusal(const std::string& path, milliseconds wait = milliseconds(0)) {
    const auto start = std::chrono::steady_clock::now();
    auto writing = std::async(std::launch::async, [&] {
      try {
        io::write_file(path, "new", wait);
      } catch (const std::exception& e) {
        return std::string(e.what());
      }
      return std::string();
    });
    if (writing.wait_for(std::chrono::seconds(10)) != std::future_status::ready) {
      std::cerr << "writing " << path << " blocked for 10 s\n";
      std::abort();
    }
    const std::string said = writing.get();
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    EXPECT_EQ(said.find('\n'), std::string::npos) << said;
    return said;
  }
  /// refusal() in a child process that is not root, where permissions hold:
  /// as root (CI runs as root) the child gives itself up to user nobody.
  static std::string refusal_without_root(const std::string& path) {
    int pipe_ends[2];
    if (::pipe(pipe_ends) != 0) return "pipe failed";
    const pid_t child = ::fork();
    if (child == 0) {
      ::close(pipe_ends[0]);
      std::string said = "could not become user nobody";
      if (::geteuid() != 0 || (::setgid(65534) == 0 && ::setuid(65534) == 0)) {
        try {
          io::write_file(path, "new", milliseconds(0));
          said.clear();
        } catch (const std::exception& e) {
          said = e.what();
        }
      }
      const auto written = ::write(pipe_ends[1], said.data(), said.size());
      ::_exit(written == static_cast<ssize_t>(said.size()) ? 0 : 1);
    }
    ::close(pipe_ends[1]);
    std::string said;
    char buffer[512];
    for (ssize_t n; (n = ::read(pipe_ends[0], buffer, sizeof buffer)) > 0;) said.append(buffer, n);
    ::close(pipe_ends[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    return said;
  }
  /// The files in the folder, but for `precious_`.
  std::set<std::string> others() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder_)) {
      if (entry.path() != precious_) names.insert(entry.path().filename().string());
    }
    return names;
  }

  std::string path_;
  std::string precious_;
};

TEST_F(Writer, shouldNotFollowALinkPlantedAtTheNameTheOldWriterUsed) {
  fs::create_symlink(precious_, path_ + ".tmp");
  EXPECT_EQ(refusal(path_), "");
  EXPECT_EQ(read(precious_), "keep me");
  EXPECT_EQ(read(path_), "new");
}

TEST_F(Writer, shouldNotWaitForAFifoPlantedAtTheNameTheOldWriterUsed) {
  ASSERT_EQ(::mkfifo((path_ + ".tmp").c_str(), 0600), 0);
  EXPECT_EQ(refusal(path_), "");
  EXPECT_EQ(read(path_), "new");
}

TEST_F(Writer, shouldLeaveNoTemporaryFileAndKeepThePermissions) {
  std::ofstream(path_) << "old";
  ::chmod(path_.c_str(), 0640);
  EXPECT_EQ(refusal(path_), "");
  EXPECT_EQ(others(), std::set<std::string>{"rack.svg"});
  struct stat st;
  ASSERT_EQ(::stat(path_.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
}

TEST_F(Writer, shouldRefuseASymlinkedTarget) {
  fs::create_symlink(precious_, path_);
  EXPECT_EQ(refusal(path_), path_ + ": a symbolic link (to " + precious_ +
                                "): not written, the link would become a file of its own; give "
                                "the file it points to");
  EXPECT_EQ(read(precious_), "keep me");
  EXPECT_TRUE(fs::is_symlink(path_));
}

TEST_F(Writer, shouldRefuseADanglingSymlinkedTarget) {
  fs::create_symlink(folder_ + "/nowhere", path_);
  EXPECT_EQ(refusal(path_), path_ + ": a symbolic link (to " + folder_ +
                                "/nowhere): not written, the link would become a file of its "
                                "own; give the file it points to");
  EXPECT_FALSE(fs::exists(folder_ + "/nowhere"));
}

TEST_F(Writer, shouldRefuseAHardLinkedTarget) {
  ASSERT_EQ(::link(precious_.c_str(), path_.c_str()), 0);
  EXPECT_EQ(refusal(path_), path_ +
                                ": has 2 names (hard links): not written, the other names "
                                "would keep the old text");
  EXPECT_EQ(read(precious_), "keep me");
}

TEST_F(Writer, shouldRefuseATargetMarkedReadOnlyEvenForRoot) {
  std::ofstream(path_) << "old";
  ::chmod(path_.c_str(), 0444);
  EXPECT_EQ(refusal(path_), path_ + ": read-only (mode 0444): not written");
  EXPECT_EQ(read(path_), "old");
}

TEST_F(Writer, shouldRefuseAFifoTargetWithoutOpeningIt) {
  ASSERT_EQ(::mkfifo(path_.c_str(), 0600), 0);
  EXPECT_EQ(refusal(path_), path_ + ": expected a regular file, got a FIFO: not written");
}

TEST_F(Writer, shouldRefuseADeviceOrAFolder) {
  EXPECT_EQ(refusal("/dev/null"),
            "/dev/null: expected a regular file, got a character device: "
            "not written");
  EXPECT_EQ(refusal(folder_), folder_ + ": expected a regular file, got a directory: not written");
  EXPECT_EQ(refusal(""), "\"\" (an empty path): expected a file path, got nothing");
}

TEST_F(Writer, shouldSayWhyAFolderTakesNoFile) {
  EXPECT_EQ(refusal(folder_ + "/none/rack.svg"),
            folder_ + "/none/rack.svg: cannot create a temporary file in " + folder_ +
                "/none (No such file or directory): not written");
  ::chmod(folder_.c_str(), 0555);
  EXPECT_EQ(refusal_without_root(path_), path_ + ": cannot create a temporary file in " +
                                             folder_ + " (Permission denied): not written");
}

TEST_F(Writer, shouldRemoveWhatAKilledWriterOfTheSameFileLeft) {
  std::ofstream(path_) << "old";
  std::ofstream(folder_ + "/.rack.svg.0123456789ab.tmp") << "torn";
  fs::create_symlink(precious_, folder_ + "/.rack.svg.ABCDEFGHIJKL.tmp");
  std::ofstream(folder_ + "/.rack.svg.short.tmp") << "not of its shape";
  EXPECT_EQ(refusal(path_), "");
  EXPECT_EQ((others()), (std::set<std::string>{"rack.svg", ".rack.svg.short.tmp"}));
  EXPECT_EQ(read(precious_), "keep me");
}

TEST_F(Writer, shouldSayAnotherProgramIsWritingWhenItWaitedInVain) {
  std::ofstream(path_) << "old";
  const io::FileWriter first(path_, milliseconds(0));
  EXPECT_EQ(refusal(path_, milliseconds(50)),
            path_ + ": another program is writing it (waited 0.05 s): not written");
  EXPECT_EQ(read(path_), "old");
}

TEST_F(Writer, shouldWaitItsTurnAndTakeTheFileTheWriterBeforeLeft) {
  std::ofstream(path_) << "old";
  std::promise<void> taken;
  std::thread first([&] {
    const io::FileWriter writer(path_, milliseconds(0));
    taken.set_value();
    std::this_thread::sleep_for(milliseconds(100));
    writer.replace("first");
  });
  taken.get_future().wait();
  // Waits on the file the first writer replaces, then takes the new one.
  const io::FileWriter second(path_, milliseconds(5000));
  EXPECT_EQ(read(path_), "first");
  second.replace(read(path_) + ", second");
  first.join();
  EXPECT_EQ(read(path_), "first, second");
}

TEST_F(Writer, shouldKnowAFileByItsLinksAndAPathByItsSpelling) {
  const std::string& folder = folder_;
  const std::string file = precious_;
  fs::create_symlink(file, folder + "/link.svg");
  ASSERT_EQ(::link(file.c_str(), (folder + "/hard.svg").c_str()), 0);
  EXPECT_TRUE(io::same_file(file, folder + "/link.svg"));
  EXPECT_TRUE(io::same_file(file, folder + "/hard.svg"));
  EXPECT_TRUE(io::same_file(folder + "/new.svg", folder + "/./new.svg"));
  EXPECT_FALSE(io::same_file(file, folder + "/new.svg"));
}

}  // namespace
}  // namespace fatc
