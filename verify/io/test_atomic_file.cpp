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

TEST_CASE("SIGTERM and SIGINT during a write leave no temporary file") {
  for (const int signal_number : {SIGTERM, SIGINT}) {
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
    // Wait for the temporary file (a hidden sibling of series.csv) to appear.
    bool seen = false;
    for (int i = 0; i < 20000 && !seen; ++i) {
      for (const auto& entry : fs::directory_iterator(dir)) {
        seen = seen || entry.path().filename().string().rfind(".series.csv.", 0) == 0;
      }
      if (!seen) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    REQUIRE(seen);
    REQUIRE(::kill(child, signal_number) == 0);
    int status = 0;
    REQUIRE(waitpid(child, &status, 0) == child);
    // Ended by the signal itself, as a parent expects.
    REQUIRE(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal_number);
    for (const auto& entry : fs::directory_iterator(dir)) {
      CHECK(entry.path().filename().string().rfind(".series.csv.", 0) != 0);
    }
    fs::remove_all(dir);
  }
}
