// The atomic writer: a reader never sees half a file, a device is never
// replaced, and no temporary file survives a failure, a file-size limit or a
// terminating signal.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include "gearimpact/error.hpp"
#include "gearimpact/io/atomic_file.hpp"

namespace fs = std::filesystem;
using namespace gearimpact;

namespace {

fs::path scratch_dir(const char* name) {
  const fs::path dir = fs::temp_directory_path() / ("gearimpact-atomic-" + std::string(name) + "-" +
                                                    std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// True once `child` holds a file open in `dir`: the anonymous temporary file
// shows in /proc as "DIR/#INODE (deleted)", a named one by its name.
bool writing_into(pid_t child, const fs::path& dir) {
  std::error_code error;
  const fs::path fds = fs::path("/proc") / std::to_string(child) / "fd";
  for (const auto& fd : fs::directory_iterator(fds, error)) {
    const fs::path target = fs::read_symlink(fd.path(), error);
    if (!error && target.string().rfind(dir.string() + "/", 0) == 0) return true;
  }
  return false;
}

bool wait_for_write(pid_t child, const fs::path& dir) {
  for (int i = 0; i < 20000; ++i) {
    if (writing_into(child, dir)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("a write replaces a regular file whole and refuses a directory") {
  const fs::path dir = scratch_dir("plain");
  const fs::path file = dir / "out.csv";
  write_file_atomically(file.string(), "first\n");
  write_file_atomically(file.string(), "second\n");
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text == "second\n");
  fs::create_directory(dir / "folder");
  CHECK_THROWS_AS(write_file_atomically((dir / "folder").string(), "x"), Error);
  CHECK(fs::is_directory(dir / "folder"));
  CHECK(entries(dir) == 2);
  fs::remove_all(dir);
}

TEST_CASE("a file-size limit is an error, and the temporary file is removed") {
  const fs::path dir = scratch_dir("fsize");
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    remove_temporaries_on_signals();  // ignores SIGXFSZ: the write fails with EFBIG instead
    const rlimit limit{1u << 16, 1u << 16};
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(2);
    try {
      write_file_atomically((dir / "big.csv").string(), std::string(1u << 20, 'x'));
    } catch (const Error& e) {
      _exit(std::string(e.what()).find("big.csv") != std::string::npos ? 0 : 3);
    }
    _exit(4);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(entries(dir) == 0);
  fs::remove_all(dir);
}

TEST_CASE("SIGTERM, SIGINT and SIGKILL during a write leave no temporary file") {
  for (const int signal_number : {SIGTERM, SIGINT, SIGKILL}) {
    CAPTURE(signal_number);
    const fs::path dir = scratch_dir("signal");
    const pid_t child = fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      remove_temporaries_on_signals();
      // Large enough that the write and its fsync outlast the parent's poll.
      const std::string text(512u << 20, 'x');
      for (;;) write_file_atomically((dir / "series.csv").string(), text);
    }
    // The child is ended whatever the wait found, so that a failure here
    // leaves no writer behind.
    const bool writing = wait_for_write(child, dir);
    REQUIRE(::kill(child, signal_number) == 0);
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    REQUIRE(writing);
    // Ended by the signal itself, as a parent expects.
    REQUIRE(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal_number);
    // Nothing but a whole series.csv, if a write had completed.
    for (const auto& entry : fs::directory_iterator(dir)) {
      CHECK(entry.path().filename() == "series.csv");
      CHECK(fs::file_size(entry.path()) == (512u << 20));
    }
    fs::remove_all(dir);
  }
}

namespace {

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("a folder of outputs appears whole: absent until commit, refused when filled") {
  const fs::path dir = scratch_dir("folder");
  const fs::path set = dir / "set";
  {
    AtomicFolder folder(set.string(), false);
    write_file_atomically((fs::path(folder.temporary()) / "a.csv").string(), "new\n");
    CHECK_FALSE(fs::exists(set));
    folder.commit();
  }
  CHECK(read_text(set / "a.csv") == "new\n");
  CHECK(entries(dir) == 1u);  // no temporary folder left beside it

  // Filled: refused before anything is made, unless replaced whole.
  CHECK_THROWS_AS(AtomicFolder(set.string(), false), Error);
  CHECK(entries(dir) == 1u);
  {
    AtomicFolder folder(set.string(), true);
    write_file_atomically((fs::path(folder.temporary()) / "b.csv").string(), "newer\n");
    folder.commit();
  }
  CHECK_FALSE(fs::exists(set / "a.csv"));
  CHECK(read_text(set / "b.csv") == "newer\n");
  CHECK(entries(dir) == 1u);

  // Another run filled the path while this one wrote: this run's set is discarded, the other's
  // stays whole.
  const fs::path raced = dir / "raced";
  {
    AtomicFolder folder(raced.string(), false);
    write_file_atomically((fs::path(folder.temporary()) / "mine.csv").string(), "mine\n");
    fs::create_directories(raced);
    write_file_atomically((raced / "theirs.csv").string(), "theirs\n");
    CHECK_THROWS_AS(folder.commit(), Error);
  }
  CHECK_FALSE(fs::exists(raced / "mine.csv"));
  CHECK(read_text(raced / "theirs.csv") == "theirs\n");
  CHECK(entries(dir) == 2u);

  // Destroyed before commit (an error in the run): nothing left.
  { AtomicFolder folder((dir / "abandoned").string(), false); }
  CHECK(entries(dir) == 2u);

  // A missing folder above it, a file in its place, or an input inside it: refused.
  CHECK_THROWS_AS(require_output_folder((dir / "missing" / "set").string(), false), Error);
  CHECK_THROWS_AS(require_output_folder((set / "b.csv").string(), true), Error);
  CHECK_THROWS_AS(require_output_folder(dir.string(), true, {(set / "b.csv").string()}), Error);
  fs::remove_all(dir);
}

TEST_CASE("SIGTERM while a folder of outputs is written leaves no temporary folder") {
  const fs::path dir = scratch_dir("folder-signal");
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    remove_temporaries_on_signals();
    AtomicFolder folder((dir / "set").string(), false);
    for (int i = 0; i < 50; ++i) {
      std::string name = "f";
      name += std::to_string(i);
      write_file_atomically((fs::path(folder.temporary()) / name).string(), "x");
    }
    const std::string text(512u << 20, 'x');
    for (;;) write_file_atomically((fs::path(folder.temporary()) / "big").string(), text);
  }
  // Wait for the temporary folder's files to appear.
  bool seen = false;
  for (int i = 0; i < 20000 && !seen; ++i) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      seen = seen || (entry.path().filename().string().rfind(".set.", 0) == 0 &&
                      fs::exists(entry.path() / "f49"));
    }
    if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  REQUIRE(::kill(child, SIGTERM) == 0);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(seen);
  REQUIRE(WIFSIGNALED(status));
  CHECK(WTERMSIG(status) == SIGTERM);
  CHECK(entries(dir) == 0u);
  fs::remove_all(dir);
}

TEST_CASE("a temporary folder left by SIGKILL is removed by the next run into the same path") {
  const fs::path dir = scratch_dir("folder-kill");
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    AtomicFolder folder((dir / "set").string(), false);
    write_file_atomically((fs::path(folder.temporary()) / "done").string(), "x");
    const std::string text(512u << 20, 'x');
    for (;;) write_file_atomically((fs::path(folder.temporary()) / "big").string(), text);
  }
  fs::path left;
  for (int i = 0; i < 20000 && left.empty(); ++i) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (fs::exists(entry.path() / "done")) left = entry.path();
    }
    if (left.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const bool writing = !left.empty() && wait_for_write(child, left);
  REQUIRE(::kill(child, SIGKILL) == 0);
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(writing);
  // A process killed outright cannot clean up: its folder stays, named by
  // its host and process id, and only its committed file is in it.
  REQUIRE(fs::exists(left));
  CHECK(entries(left) == 1u);
  const std::string name = left.filename().string();
  std::string own_pid = ".";
  own_pid.append(std::to_string(child)).append(".");
  CHECK(name.find(own_pid) != std::string::npos);
  // A folder of the same pattern whose process lives (this one) stays.
  std::string alive_name = name.substr(0, name.find(own_pid));
  alive_name.append(".").append(std::to_string(::getpid())).append(".abcdef");
  const fs::path alive = dir / alive_name;
  fs::create_directory(alive);
  AtomicFolder next((dir / "set").string(), false);
  next.commit();
  CHECK_FALSE(fs::exists(left));
  CHECK(fs::exists(alive));
  CHECK(entries(dir) == 2u);
  fs::remove_all(dir);
}

TEST_CASE("a replaced file keeps its permissions; a new one is readable by everyone") {
  const fs::path dir = scratch_dir("mode");
  const fs::path kept = dir / "private.csv";
  write_file_atomically(kept.string(), "old");
  fs::permissions(kept, fs::perms::owner_read | fs::perms::owner_write);
  write_file_atomically(kept.string(), "new");
  CHECK(read_text(kept) == "new");
  CHECK(fs::status(kept).permissions() == (fs::perms::owner_read | fs::perms::owner_write));
  const fs::path fresh = dir / "fresh.csv";
  write_file_atomically(fresh.string(), "x");
  CHECK((fs::status(fresh).permissions() & fs::perms::others_read) == fs::perms::others_read);
  fs::remove_all(dir);
}
