#include "gearimpact/io/atomic_file.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// The names of the temporary files being written, for the signal handler: a
// fixed table of fixed buffers, since a handler may neither allocate nor lock.
// A slot is claimed by compare-and-swap on `used` and its name is complete
// before `ready` is set.
constexpr std::size_t kSlots = 64;
// The signals whose handler removes the temporary files.
// SIGPIPE too: a reader of standard output that goes away (`| head`) ends
// the run, which must not leave its temporaries behind.
constexpr std::array<int, 4> kTerminatingSignals{SIGINT, SIGTERM, SIGHUP, SIGPIPE};

// Runs `create_and_track` with the terminating signals blocked, so that a
// temporary file or folder is registered for the handler before one of them
// can end the process.
template <typename Work>
void with_terminating_signals_blocked(Work create_and_track) {
  sigset_t terminating, previous;
  sigemptyset(&terminating);
  for (const int signal_number : kTerminatingSignals) sigaddset(&terminating, signal_number);
  pthread_sigmask(SIG_BLOCK, &terminating, &previous);
  create_and_track();
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}
constexpr std::size_t kNameLength = 4096;
struct Slot {
  std::atomic<bool> used{false};
  std::atomic<bool> ready{false};
  std::atomic<bool> folder{false};
  std::array<char, kNameLength> name{};
};
std::array<Slot, kSlots> slots;

// Registers `name` for removal on a signal; returns the slot, or kSlots when
// the table is full or the name too long (the file is then only removed on
// the error paths).
std::size_t track(const char* name, bool folder = false) {
  const std::size_t length = std::strlen(name);
  if (length >= kNameLength) return kSlots;
  for (std::size_t i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (slots[i].used.compare_exchange_strong(expected, true)) {
      std::memcpy(slots[i].name.data(), name, length + 1);
      slots[i].folder.store(folder);
      slots[i].ready.store(true);
      return i;
    }
  }
  return kSlots;
}

void untrack(std::size_t slot) noexcept {
  if (slot >= kSlots) return;
  slots[slot].ready.store(false);
  slots[slot].used.store(false);
}

// The files of a temporary folder (it holds no folders) and the folder, by
// system calls only: a handler may not use opendir, which allocates.
void remove_folder_in_handler(const char* name) noexcept {
  const int fd = ::open(name, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  alignas(8) static char entries[8192];
  while (true) {
    const long n = ::syscall(SYS_getdents64, fd, entries, sizeof entries);
    if (n <= 0) break;
    for (long at = 0; at < n;) {
      // struct linux_dirent64: d_ino (8), d_off (8), d_reclen (2), d_type (1), d_name.
      unsigned short length = 0;
      std::memcpy(&length, entries + at + 16, sizeof length);
      const char* entry = entries + at + 19;
      if (std::strcmp(entry, ".") != 0 && std::strcmp(entry, "..") != 0) {
        ::unlinkat(fd, entry, 0);
      }
      at += length;
    }
  }
  ::close(fd);
  ::rmdir(name);
}

// The children writing into temporary folders (TrackedChild), 0 where none.
constexpr std::size_t kChildSlots = 16;
std::array<std::atomic<long>, kChildSlots> children{};

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  // The children first: one still drawing would write into a folder being removed.
  for (std::atomic<long>& child : children) {
    const long pid = child.load();
    if (pid <= 0) continue;
    ::kill(static_cast<pid_t>(pid), SIGKILL);
    while (::waitpid(static_cast<pid_t>(pid), nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  // Files first: a temporary file may lie in a temporary folder.
  for (Slot& slot : slots) {
    if (slot.ready.load() && !slot.folder.load()) ::unlink(slot.name.data());
  }
  for (Slot& slot : slots) {
    if (slot.ready.load() && slot.folder.load()) remove_folder_in_handler(slot.name.data());
  }
  // The default action (termination by this signal) so that the parent sees
  // how the process ended.
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

std::string reason() {
  return std::strerror(errno);
}

// The folder a file or folder `target` is made in.
std::filesystem::path folder_of(const std::filesystem::path& target) {
  return target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
}

// Throws Error, its message starting with `what` ("cannot write PATH"),
// unless the folder `target` is made in exists and may be written.
void require_writable_folder_of(const std::filesystem::path& target, const std::string& what) {
  const std::filesystem::path dir = folder_of(target);
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    throw Error(what + ": its folder " + dir.string() + " does not exist");
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw Error(what + ": its folder " + dir.string() + " cannot be written (" + reason() + ")");
  }
}

// A temporary's name says who made it: ".NAME<tag>.HOST.PID.XXXXXX" beside
// NAME. A run killed by SIGKILL cannot remove its temporary folder (its files
// are anonymous until committed, see AtomicFile); the next run into the same
// target removes what a dead process of this host left (kill(pid, 0) says
// ESRCH). A live process's, or another host's on a shared file system, stays.
std::string this_host() {
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) != 0) return "host";
  std::string host(name.data());
  for (char& c : host) {
    if (c == '/' || c == '.') c = '_';
  }
  return host.empty() ? "host" : host;
}

std::string temporary_prefix(const std::filesystem::path& target, const char* tag) {
  return "." + target.filename().string() + tag + "." + this_host() + ".";
}

std::string temporary_pattern(const std::filesystem::path& target, const char* tag) {
  return (folder_of(target) /
          (temporary_prefix(target, tag) + std::to_string(::getpid()) + ".XXXXXX"))
      .string();
}

void remove_stale_temporaries(const std::filesystem::path& target) {
  std::error_code error;
  for (const char* tag : {"", ".old"}) {
    const std::string prefix = temporary_prefix(target, tag);
    for (const auto& entry : std::filesystem::directory_iterator(folder_of(target), error)) {
      const std::string name = entry.path().filename().string();
      if (name.compare(0, prefix.size(), prefix) != 0) continue;
      // The rest is "PID.XXXXXX".
      const std::string rest = name.substr(prefix.size());
      const std::size_t dot = rest.find('.');
      if (dot == std::string::npos || dot == 0 || rest.size() != dot + 7 ||
          rest.find_first_not_of("0123456789") != dot) {
        continue;
      }
      const long pid = std::strtol(rest.c_str(), nullptr, 10);
      if (pid <= 0 || ::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;
      std::error_code ignored;
      std::filesystem::remove_all(entry.path(), ignored);
    }
  }
}

}  // namespace

void require_regular_or_absent(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    if (errno == ENOENT) return;
    throw Error("cannot use " + path + " as an output: " + reason());
  }
  if (!S_ISREG(status.st_mode)) {
    const char* kind = S_ISDIR(status.st_mode)    ? "a directory"
                       : S_ISCHR(status.st_mode)  ? "a character device"
                       : S_ISBLK(status.st_mode)  ? "a block device"
                       : S_ISFIFO(status.st_mode) ? "a FIFO"
                       : S_ISSOCK(status.st_mode) ? "a socket"
                                                  : "not a regular file";
    throw Error("cannot write " + path + ": it is " + std::string(kind) +
                ", and an output replaces only a regular file or makes a new one");
  }
  // The rename would replace a file this user may not write (its folder
  // allows it): refused, as writing into it would be.
  if (::access(path.c_str(), W_OK) != 0) {
    throw Error("cannot write " + path + ": " + reason() +
                " (an output replaces only a file this user may write)");
  }
}

void require_output_file(const std::string& path, const std::vector<std::string>& inputs) {
  if (path.empty()) throw Error("an output path is empty");
  require_regular_or_absent(path);
  std::error_code error;
  for (const std::string& input : inputs) {
    if (std::filesystem::equivalent(path, input, error)) {
      throw Error("cannot write " + path + ": it is the input " + input + " of this run");
    }
  }
  require_writable_folder_of(path, "cannot write " + path);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  require_regular_or_absent(path_);
  const std::filesystem::path target(path_);
  const std::filesystem::path dir = folder_of(target);
  remove_stale_temporaries(target);
  // An anonymous file in the target's folder (same file system, so the final
  // rename is atomic): nothing of it survives the process, SIGKILL included,
  // until commit() gives it a name. Where the file system or a missing /proc
  // rules that out, a hidden named sibling, removed on the error paths and
  // the terminating signals.
  if (::access("/proc/self/fd", X_OK) == 0) {
    fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644);
  }
  if (fd_ < 0) {
    std::vector<char> name;
    const std::string pattern = temporary_pattern(target, "");
    name.assign(pattern.begin(), pattern.end());
    name.push_back('\0');
    // The file is registered for the signal handler before a terminating
    // signal may arrive: one between its creation and its registration would
    // leave it behind.
    int mkstemp_errno = 0;
    with_terminating_signals_blocked([&] {
      fd_ = mkstemp(name.data());
      mkstemp_errno = errno;
      if (fd_ >= 0) slot_ = track(name.data());
    });
    if (fd_ < 0) {
      errno = mkstemp_errno;
      throw Error("cannot create a temporary file beside " + path_ + ": " + reason());
    }
    temporary_.assign(name.data());
  }
  // mkstemp creates the file private, O_TMPFILE applies the umask: a new
  // output is for everyone to read, a replaced one keeps its permissions.
  struct stat existing {};
  const mode_t mode = ::stat(path_.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : 0644;
  if (::fchmod(fd_, mode) != 0) fail("cannot set the permissions of");
}

AtomicFile::~AtomicFile() {
  discard();
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
  untrack(slot_);
  slot_ = AtomicFile::kUntracked;
}

void AtomicFile::fail(const char* what) {
  const std::string why = reason();
  discard();
  throw Error(std::string(what) + " " + path_ + ": " + why);
}

void AtomicFile::append(std::string_view text) {
  if (fd_ < 0) throw Error("cannot write " + path_ + ": the file is already closed");
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd_, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    written += static_cast<std::size_t>(n);
  }
}

void AtomicFile::commit() {
  if (fd_ < 0) throw Error("cannot write " + path_ + ": the file is already closed");
  if (::fsync(fd_) != 0) fail("cannot flush");
  if (temporary_.empty()) link_anonymous_file();
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("cannot close");
  // Checked again: the target may have been replaced by a device or a folder
  // while the text was written.
  try {
    require_regular_or_absent(path_);
  } catch (const Error&) {
    discard();
    throw;
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) fail("cannot rename onto");
  temporary_.clear();
  untrack(slot_);
  slot_ = AtomicFile::kUntracked;
}

void AtomicFile::link_anonymous_file() {
  // linkat through /proc/self/fd names an O_TMPFILE file without privileges
  // (open(2)); the name is a fresh hidden sibling, registered for the signal
  // handler for the moment until the rename.
  const std::string proc_path = "/proc/self/fd/" + std::to_string(fd_);
  const std::string pattern = temporary_pattern(std::filesystem::path(path_), "");
  for (unsigned attempt = 0;; ++attempt) {
    std::string name = pattern.substr(0, pattern.size() - 6);
    unsigned value = static_cast<unsigned>(std::random_device{}()) + attempt;
    for (int i = 0; i < 6; ++i, value /= 36)
      name += "0123456789abcdefghijklmnopqrstuvwxyz"[value % 36];
    int link_errno = 0;
    with_terminating_signals_blocked([&] {
      if (::linkat(AT_FDCWD, proc_path.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
        slot_ = track(name.c_str());
        temporary_ = name;
      } else {
        link_errno = errno;
      }
    });
    if (!temporary_.empty()) return;
    if (link_errno != EEXIST || attempt == 100) {
      errno = link_errno;
      fail("cannot name the temporary file of");
    }
  }
}

namespace {

// A target named with a trailing slash ("out/") has an empty file name.
std::filesystem::path without_trailing_slash(const std::string& path) {
  std::filesystem::path target(path);
  if (!target.has_filename() && target.has_parent_path()) target = target.parent_path();
  return target;
}

bool is_within(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  std::error_code error;
  const std::filesystem::path a = std::filesystem::weakly_canonical(inner, error);
  if (error) return false;
  const std::filesystem::path b = std::filesystem::weakly_canonical(outer, error);
  if (error) return false;
  auto i = a.begin();
  for (auto o = b.begin(); o != b.end(); ++o, ++i) {
    if (o->empty()) continue;
    if (i == a.end() || *i != *o) return false;
  }
  return true;
}

// A fresh hidden folder beside `target`, from mkdtemp, registered for the
// signal handler as AtomicFile registers its file; throws Error.
std::string make_temporary_folder(const std::filesystem::path& target, const char* tag,
                                  std::size_t& slot) {
  remove_stale_temporaries(target);
  const std::string pattern = temporary_pattern(target, tag);
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const char* made = nullptr;
  int mkdtemp_errno = 0;
  with_terminating_signals_blocked([&] {
    made = ::mkdtemp(name.data());
    mkdtemp_errno = errno;
    if (made != nullptr) slot = track(name.data(), true);
  });
  if (made == nullptr) {
    errno = mkdtemp_errno;
    throw Error("cannot make a temporary folder beside " + target.string() + ": " + reason());
  }
  return std::string(name.data());
}

}  // namespace

void require_output_folder(const std::string& path, bool overwrite,
                           const std::vector<std::string>& inputs) {
  if (path.empty()) throw Error("an output folder is empty");
  const std::filesystem::path target = without_trailing_slash(path);
  std::error_code error;
  for (const std::string& input : inputs) {
    if (is_within(input, target)) {
      throw Error("cannot write the folder " + path + ": it is or holds the input " + input +
                  " of this run");
    }
  }
  // A link is renamed over, not followed: the folder it names would stay and the link go.
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(target, error))) {
    throw Error("cannot write the folder " + path +
                ": it is a symbolic link, and an output folder replaces only a folder (name "
                "the folder it links to)");
  }
  // The current folder or one that holds it cannot be replaced by a rename (and would take
  // the run's own folder with it).
  const std::filesystem::path here = std::filesystem::current_path(error);
  const std::filesystem::path whole = std::filesystem::weakly_canonical(target, error);
  if (!error && !whole.empty()) {
    const auto [end, rest] = std::mismatch(whole.begin(), whole.end(), here.begin(), here.end());
    if (end == whole.end()) {
      throw Error("cannot write the folder " + path +
                  ": it is or holds the current folder, which an output folder cannot replace");
    }
  }
  error.clear();
  const std::filesystem::file_status status = std::filesystem::status(target, error);
  if (std::filesystem::exists(status)) {
    if (!std::filesystem::is_directory(status)) {
      throw Error("cannot write the folder " + path +
                  ": it exists and is not a folder, and an output folder replaces only a folder");
    }
    if (!overwrite && !std::filesystem::is_empty(target, error)) {
      throw Error("cannot write the folder " + path +
                  ": it is not empty (files of an earlier run would mix with the new ones); "
                  "choose a new folder, or replace it whole with --overwrite");
    }
  }
  require_writable_folder_of(target, "cannot write the folder " + path);
}

AtomicFolder::AtomicFolder(std::string path, bool overwrite, const std::vector<std::string>& inputs)
    : path_(without_trailing_slash(path).string()), overwrite_(overwrite) {
  require_output_folder(path, overwrite, inputs);
  temporary_ = make_temporary_folder(path_, "", slot_);
  // mkdtemp makes the folder private; outputs are for everyone to read.
  if (::chmod(temporary_.c_str(), 0755) != 0) {
    const std::string why = reason();
    discard();
    throw Error("cannot set the permissions of a temporary folder beside " + path_ + ": " + why);
  }
}

AtomicFolder::~AtomicFolder() {
  discard();
}

void AtomicFolder::discard() noexcept {
  if (!temporary_.empty()) {
    std::error_code ignored;
    std::filesystem::remove_all(temporary_, ignored);
  }
  temporary_.clear();
  untrack(slot_);
  slot_ = AtomicFile::kUntracked;
}

void AtomicFolder::commit() {
  if (temporary_.empty()) throw Error("cannot write the folder " + path_ + ": already committed");
  // Onto an absent path or an empty folder, the rename is the whole commit.
  if (std::rename(temporary_.c_str(), path_.c_str()) == 0) {
    temporary_.clear();
    untrack(slot_);
    slot_ = AtomicFile::kUntracked;
    return;
  }
  const int rename_errno = errno;
  if ((rename_errno != ENOTEMPTY && rename_errno != EEXIST) || !overwrite_) {
    errno = rename_errno;
    const std::string why = rename_errno == ENOTEMPTY || rename_errno == EEXIST
                                ? "another run filled it while this one ran; this run's "
                                  "outputs are discarded (--overwrite replaces it whole)"
                                : reason();
    discard();
    throw Error("cannot write the folder " + path_ + ": " + why);
  }
  // Replaced whole: the old folder aside (onto an empty folder of our own),
  // the new one in, the old one removed.
  std::size_t aside_slot = AtomicFile::kUntracked;
  std::string aside;
  try {
    aside = make_temporary_folder(path_, ".old", aside_slot);
  } catch (const Error&) {
    discard();
    throw;
  }
  untrack(aside_slot);
  if (std::rename(path_.c_str(), aside.c_str()) != 0) {
    const std::string why = reason();
    ::rmdir(aside.c_str());
    discard();
    throw Error("cannot move the earlier folder " + path_ + " aside: " + why);
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const std::string why = reason();
    // The earlier folder back, unless another run took its place meanwhile.
    if (std::rename(aside.c_str(), path_.c_str()) != 0) {
      std::error_code ignored;
      std::filesystem::remove_all(aside, ignored);
    }
    discard();
    throw Error("cannot write the folder " + path_ + ": " + why);
  }
  temporary_.clear();
  untrack(slot_);
  slot_ = AtomicFile::kUntracked;
  std::error_code ignored;
  std::filesystem::remove_all(aside, ignored);
}

void write_file_atomically(const std::string& path, std::string_view text) {
  AtomicFile file(path);
  file.append(text);
  file.commit();
}

void TrackedChild::start(const std::function<long()>& spawn) {
  slot_ = kChildSlots;
  with_terminating_signals_blocked([&] {
    pid_ = spawn();
    if (pid_ <= 0) return;
    for (std::size_t i = 0; i < kChildSlots; ++i) {
      long expected = 0;
      if (children[i].compare_exchange_strong(expected, pid_)) {
        slot_ = i;
        break;
      }
    }
  });
}

int TrackedChild::wait() {
  if (pid_ <= 0) return 0;
  // Wait for the end without reaping, unregister, then reap: between the two the pid still
  // names this (ended) child, never another process.
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOWAIT) < 0 && errno == EINTR) {
  }
  if (slot_ < kChildSlots) children[slot_].store(0);
  slot_ = kChildSlots;
  int status = 0;
  while (::waitpid(static_cast<pid_t>(pid_), &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return status;
}

TrackedChild::~TrackedChild() {
  if (pid_ > 0) wait();
}

void remove_temporaries_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_reraise;
  sigemptyset(&action.sa_mask);
  for (const int signal_number : kTerminatingSignals) {
    ::sigaction(signal_number, &action, nullptr);
  }
  std::signal(SIGXFSZ, SIG_IGN);
}

}  // namespace gearimpact
