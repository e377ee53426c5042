// Runs a shell command for the end-to-end tests of the gearimpact program and
// collects its exit code, standard output and standard error.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace gearimpact::verify {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline CommandResult run_command(const std::string& command) {
  const std::filesystem::path err_path =
      std::filesystem::temp_directory_path() /
      ("gearimpact-test-stderr-" + std::to_string(::getpid()) + ".txt");
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>" + err_path.string()).c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.out.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  std::stringstream text;
  text << err.rdbuf();
  result.err = text.str();
  std::filesystem::remove(err_path);
  return result;
}

inline std::string cli(const std::string& arguments) {
  return std::string(GEARIMPACT_CLI) + " " + arguments;
}

// A shell command that starts `command` in the background and sends it `signal_name` (INT, TERM,
// KILL) once it is under way: after it catches SIGINT (bit 2 of SigCgt in /proc/PID/status, the
// last hexadecimal digit one of 2 3 6 7 a b e f), then `delay_s` more, and waits for it. A
// background job of a shell without job control starts with SIGINT ignored, so a SIGINT sent
// before the program sets its handlers (a slow start on a loaded machine, under the sanitizers)
// would be lost and the run would go on to its end. Gives up waiting after 60 s, or when it has
// ended.
inline std::string signal_when_under_way(const std::string& command, const std::string& signal_name,
                                         double delay_s) {
  return command +
         " & p=$!; i=0; while [ $i -lt 1200 ] && [ -e /proc/$p ]; do case \"$(sed -n "
         "'s/^SigCgt:.*\\(.\\)$/\\1/p' "
         "/proc/$p/status 2>/dev/null)\" in [2367abef]) break;; esac; sleep 0.05; i=$((i+1)); "
         "done; sleep " +
         std::to_string(delay_s) + "; kill -" + signal_name + " $p; wait";
}

}  // namespace gearimpact::verify
