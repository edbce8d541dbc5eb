// write_file_atomic through the file system as it is (issue #23, item 11): a symbolic link is
// written through (the link stays, its target gets the new contents), a FIFO is written into (not
// replaced), a failed write leaves every file as it was. Oracles: the file system itself (lstat,
// readlink, reading the files back, a non-blocking reader on the FIFO).
#include <gtest/gtest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "interfere/core/atomic_file.h"

namespace fs = std::filesystem;
using namespace interfere;

namespace {

struct TempDir {
  fs::path dir;
  TempDir() {
    dir = fs::temp_directory_path() / ("interfere_atomic_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

std::size_t count_entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST(AtomicFile, RegularFileReplacedAndPermissionsKept) {
  TempDir t;
  const fs::path f = t.dir / "out.json";
  put(f, "old contents, longer than the new ones");
  fs::permissions(f, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  ASSERT_TRUE(write_file_atomic(f, "new"));
  EXPECT_EQ(slurp(f), "new");
  EXPECT_EQ(fs::status(f).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(count_entries(t.dir), 1u);  // no temporary file left
}

TEST(AtomicFile, SymlinkWrittenThroughLinkKept) {
  TempDir t;
  fs::create_directories(t.dir / "data");
  fs::create_directories(t.dir / "links");
  const fs::path target = t.dir / "data" / "report.json";
  const fs::path link = t.dir / "links" / "report.json";
  put(target, "old");
  fs::create_symlink("../data/report.json", link);  // relative to the link's directory
  ASSERT_TRUE(write_file_atomic(link, "new contents"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(fs::read_symlink(link), fs::path("../data/report.json"));
  EXPECT_EQ(slurp(target), "new contents");
  EXPECT_EQ(count_entries(t.dir / "data"), 1u);
  EXPECT_EQ(count_entries(t.dir / "links"), 1u);
}

TEST(AtomicFile, SymlinkChainAndDanglingLink) {
  TempDir t;
  const fs::path target = t.dir / "final.txt";
  put(target, "old");
  fs::create_symlink(target, t.dir / "first");            // absolute
  fs::create_symlink("first", t.dir / "second");          // relative, to a link
  ASSERT_TRUE(write_file_atomic(t.dir / "second", "through two links"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(t.dir / "second")));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(t.dir / "first")));
  EXPECT_EQ(slurp(target), "through two links");

  fs::create_symlink("missing.txt", t.dir / "dangling");  // the target is created, as `>` does
  ASSERT_TRUE(write_file_atomic(t.dir / "dangling", "created"));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(t.dir / "dangling")));
  EXPECT_EQ(slurp(t.dir / "missing.txt"), "created");
}

TEST(AtomicFile, SymlinkLoopIsAnErrorAndWritesNothing) {
  TempDir t;
  fs::create_symlink("b", t.dir / "a");
  fs::create_symlink("a", t.dir / "b");
  const Status s = write_file_atomic(t.dir / "a", "x");
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message().find("symbolic links"), std::string::npos) << s.error().message();
  EXPECT_EQ(count_entries(t.dir), 2u);
}

TEST(AtomicFile, FailedBodyLeavesSymlinkTargetUntouched) {
  TempDir t;
  const fs::path target = t.dir / "keep.txt";
  put(target, "precious");
  fs::create_symlink("keep.txt", t.dir / "link");
  const Status s = write_file_atomic(t.dir / "link", [](std::FILE* f) {
    std::fputs("half a report", f);
    return EIO;
  });
  EXPECT_FALSE(s);
  EXPECT_EQ(slurp(target), "precious");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(t.dir / "link")));
  EXPECT_EQ(count_entries(t.dir), 2u);  // no temporary file left beside the target
}

TEST(AtomicFile, FifoIsWrittenIntoNotReplaced) {
  TempDir t;
  const fs::path fifo = t.dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
  // A reader that does not block: the writer's open then finds it, and the data waits in the pipe.
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  const std::string text = "{\"verdict\": \"clash\"}\n";
  ASSERT_TRUE(write_file_atomic(fifo, text));
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode)) << "the FIFO was replaced";
  char buf[256];
  const ssize_t n = ::read(reader, buf, sizeof buf);
  ::close(reader);
  ASSERT_GT(n, 0) << "nothing arrived through the FIFO";
  EXPECT_EQ(std::string(buf, static_cast<std::size_t>(n)), text);
}

TEST(AtomicFile, FailedBodyWritesNothingIntoFifo) {
  TempDir t;
  const fs::path fifo = t.dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  const Status s = write_file_atomic(fifo, [](std::FILE* f) {
    std::fputs("partial", f);
    return EIO;
  });
  EXPECT_FALSE(s);
  char buf[64];
  const ssize_t n = ::read(reader, buf, sizeof buf);
  ::close(reader);
  EXPECT_LE(n, 0) << "a failed write reached the reader: " << std::string(buf, n > 0 ? n : 0);
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(AtomicFile, WriteToDescriptorIsAllOrNothing) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  EXPECT_TRUE(write_to_descriptor(fds[1], "pipe", [](std::FILE* f) { return std::fputs("whole\n", f) < 0 ? EIO : 0; }));
  EXPECT_FALSE(write_to_descriptor(fds[1], "pipe", [](std::FILE* f) {
    std::fputs("never seen", f);
    return EIO;
  }));
  ::close(fds[1]);
  std::string got;
  char buf[64];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) got.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  EXPECT_EQ(got, "whole\n");
}

TEST(AtomicFile, ResolveOutputPath) {
  TempDir t;
  fs::create_directories(t.dir / "d");
  fs::create_symlink("d/x", t.dir / "l1");
  const auto r = resolve_output_path(t.dir / "l1");
  ASSERT_TRUE(r);
  EXPECT_EQ(fs::weakly_canonical(*r), fs::weakly_canonical(t.dir / "d" / "x"));
  const auto plain = resolve_output_path(t.dir / "plain.txt");
  ASSERT_TRUE(plain);
  EXPECT_EQ(*plain, t.dir / "plain.txt");
}
