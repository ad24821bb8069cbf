// write_file_atomic: the final file is either the old or the complete new content, failures
// name the path, and no temporary file is ever left behind.
#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"

namespace fs = std::filesystem;
using rtsph::io::ensure_directory;
using rtsph::io::IoError;
using rtsph::io::write_file_atomic;

namespace {

class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_atomic_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::add);
    fs::remove_all(dir_);
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
  /// Expects IoError whose message names `path`; returns the message.
  static std::string expect_io_error(const fs::path& path, const std::function<void()>& f) {
    try {
      f();
    } catch (const IoError& e) {
      std::string msg = e.what();
      EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
      return msg;
    }
    ADD_FAILURE() << "no IoError for " << path;
    return {};
  }
  fs::path dir_;
};

TEST_F(AtomicFileTest, WritesContentAndLeavesOnlyTheFinalFile) {
  write_file_atomic(dir_ / "a.txt", [](std::ostream& os) { os << "hello\n"; });
  EXPECT_EQ(slurp(dir_ / "a.txt"), "hello\n");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFileTest, ReplacesExistingFile) {
  write_file_atomic(dir_ / "a.txt", std::string_view("first version, longer"));
  write_file_atomic(dir_ / "a.txt", std::string_view("second"));
  EXPECT_EQ(slurp(dir_ / "a.txt"), "second");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFileTest, LargeBodyIsWrittenCompletely) {
  std::string big(3'000'000, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 7919 % 251);
  write_file_atomic(dir_ / "big.bin", [&](std::ostream& os) {
    // Mixed small and large writes exercise both buffer paths.
    os.write(big.data(), 10);
    os.write(big.data() + 10, 1'000'000);
    for (std::size_t i = 1'000'010; i < big.size(); ++i) os.put(big[i]);
  });
  EXPECT_EQ(slurp(dir_ / "big.bin"), big);
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsNamingThePath) {
  const auto target = dir_ / "no_such_dir" / "a.txt";
  auto msg = expect_io_error(target, [&] { write_file_atomic(target, std::string_view("x")); });
  EXPECT_NE(msg.find("No such file or directory"), std::string::npos) << msg;
  EXPECT_TRUE(entries().empty());
}

TEST_F(AtomicFileTest, FileWhereDirectoryExpectedThrows) {
  write_file_atomic(dir_ / "plain", std::string_view("x"));
  const auto target = dir_ / "plain" / "a.txt";
  auto msg = expect_io_error(target, [&] { write_file_atomic(target, std::string_view("x")); });
  EXPECT_NE(msg.find("Not a directory"), std::string::npos) << msg;
  EXPECT_EQ(entries(), std::vector<std::string>{"plain"});
}

TEST_F(AtomicFileTest, ReadOnlyDirectoryThrows) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions; covered by the Not a directory case";
  const auto ro = dir_ / "ro";
  fs::create_directories(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  auto msg = expect_io_error(ro / "a.txt", [&] { write_file_atomic(ro / "a.txt", std::string_view("x")); });
  EXPECT_NE(msg.find("Permission denied"), std::string::npos) << msg;
  fs::permissions(ro, fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(ro));
}

TEST_F(AtomicFileTest, ThrowingBodyKeepsPreviousContent) {
  write_file_atomic(dir_ / "a.txt", std::string_view("old"));
  EXPECT_THROW(write_file_atomic(dir_ / "a.txt",
                                 [](std::ostream& os) {
                                   os << std::string(200'000, 'n');
                                   throw std::runtime_error("body failed");
                                 }),
               std::runtime_error);
  EXPECT_EQ(slurp(dir_ / "a.txt"), "old");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

// A full disk cannot be made without privileges, but a file size limit fails write() the same
// way part-way through (EFBIG instead of ENOSPC).
TEST_F(AtomicFileTest, FailedWriteKeepsPreviousContent) {
  write_file_atomic(dir_ / "a.txt", std::string_view("old"));
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  rlimit small = saved;
  small.rlim_cur = 100'000;
  auto* old_handler = ::signal(SIGXFSZ, SIG_IGN);
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string msg;
  try {
    write_file_atomic(dir_ / "a.txt", [](std::ostream& os) { os << std::string(1'000'000, 'n'); });
  } catch (const IoError& e) {
    msg = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, old_handler);
  EXPECT_NE(msg.find((dir_ / "a.txt").string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("File too large"), std::string::npos) << msg;
  EXPECT_EQ(slurp(dir_ / "a.txt"), "old");
  EXPECT_EQ(entries(), std::vector<std::string>{"a.txt"});
}

TEST_F(AtomicFileTest, EnsureDirectoryCreatesParents) {
  ensure_directory(dir_ / "x" / "y" / "z");
  EXPECT_TRUE(fs::is_directory(dir_ / "x" / "y" / "z"));
  ensure_directory(dir_ / "x");  // existing: fine
}

TEST_F(AtomicFileTest, EnsureDirectoryOnAFileThrows) {
  write_file_atomic(dir_ / "plain", std::string_view("x"));
  expect_io_error(dir_ / "plain", [&] { ensure_directory(dir_ / "plain"); });
  expect_io_error(dir_ / "plain" / "sub", [&] { ensure_directory(dir_ / "plain" / "sub"); });
}

// What `rtsph run --stats-json` and `rtsph bench --json` check before they run: a file that
// write_file_atomic could write, or an IoError naming it; nothing is created either way.
TEST_F(AtomicFileTest, CheckFileTargetBeforeALongRun) {
  EXPECT_NO_THROW(rtsph::io::check_file_target(dir_ / "new.json"));
  write_file_atomic(dir_ / "old.json", std::string_view("x"));
  EXPECT_NO_THROW(rtsph::io::check_file_target(dir_ / "old.json"));  // replaced at the end
  expect_io_error(dir_ / "missing" / "a.json", [&] { rtsph::io::check_file_target(dir_ / "missing" / "a.json"); });
  expect_io_error(dir_ / "old.json" / "a.json", [&] { rtsph::io::check_file_target(dir_ / "old.json" / "a.json"); });
  expect_io_error(dir_, [&] { rtsph::io::check_file_target(dir_); });  // a directory
  EXPECT_EQ(entries(), std::vector<std::string>{"old.json"});
  EXPECT_EQ(slurp(dir_ / "old.json"), "x");
}

}  // namespace
