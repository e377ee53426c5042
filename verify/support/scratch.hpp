// A fresh folder per test case, for the suites that run the program against
// the file system.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace gearimpact::verify {

// A fresh folder under the temporary directory, named by `tag` and the
// process, removed at the end of the test case.
struct Scratch {
  std::filesystem::path dir;
  explicit Scratch(const std::string& tag) {
    dir = std::filesystem::temp_directory_path() /
          ("gearimpact-" + tag + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  ~Scratch() { std::filesystem::remove_all(dir); }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};

}  // namespace gearimpact::verify
