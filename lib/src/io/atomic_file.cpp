#include "gearimpact/io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace gearimpact {

void write_file_atomically(const std::string& path, std::string_view text) {
  const std::filesystem::path target(path);
  const std::filesystem::path dir =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  // A hidden sibling: same file system, so the rename is atomic.
  std::string hidden(".");
  hidden.append(target.filename().string());
  hidden.append(".XXXXXX");
  const std::string pattern = (dir / hidden).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = mkstemp(name.data());
  if (fd < 0) {
    throw std::runtime_error("cannot create a temporary file beside " + path + ": " +
                             std::strerror(errno));
  }
  const auto fail = [&](const char* what) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    std::remove(name.data());
    throw std::runtime_error(std::string(what) + " " + path + ": " + reason);
  };
  // mkstemp creates the file private; an output is for everyone to read.
  if (::fchmod(fd, 0644) != 0) fail("cannot set the permissions of");
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) fail("cannot flush");
  if (::close(fd) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(name.data());
    throw std::runtime_error("cannot close " + path + ": " + reason);
  }
  if (std::rename(name.data(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(name.data());
    throw std::runtime_error("cannot rename onto " + path + ": " + reason);
  }
}

}  // namespace gearimpact
