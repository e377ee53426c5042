// Writing an output file so that a reader never sees half of it, and so that
// no output replaces what is not a regular file.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace gearimpact {

// Writes `text` to a temporary file in the directory of `path`, then renames it
// onto `path`. Refuses, before writing, a `path` that exists and is not a
// regular file (a device such as /dev/null, a FIFO, a directory, a socket):
// the rename would replace the node itself. Throws Error naming the path on
// any failure. The temporary file is anonymous (O_TMPFILE) until the moment
// of the rename, so nothing of it survives a failure or the process's end,
// SIGKILL included; where the file system cannot make anonymous files it is a
// hidden sibling, removed on failure and, once remove_temporaries_on_signals()
// has been called, on SIGINT, SIGTERM or SIGHUP, and by the next write of the
// same path after a SIGKILL.
void write_file_atomically(const std::string& path, std::string_view text);

// An output written in pieces, for one too long to hold in memory (a time
// series of minutes): the pieces go to a hidden temporary file beside `path`,
// which commit() renames onto it. The same guarantees as write_file_atomically;
// a file destroyed before commit() (an exception, an early return) is removed.
class AtomicFile {
 public:
  // Refuses a `path` that exists and is not a regular file; throws Error.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Throws Error naming the path when the write fails or falls short.
  void append(std::string_view text);
  // Flushes to disk and renames onto the path; throws Error naming it.
  void commit();

  // The slot of a file not (or no longer) registered for removal on a signal.
  static constexpr std::size_t kUntracked = static_cast<std::size_t>(-1);

 private:
  void discard() noexcept;
  [[noreturn]] void fail(const char* what);
  void link_anonymous_file();

  std::string path_;
  // The temporary file's name once it has one (empty while it is anonymous).
  std::string temporary_;
  int fd_ = -1;
  std::size_t slot_ = kUntracked;
};

// Throws Error naming `path` unless it is absent or a regular file (a link to
// one counts as one), so that a command can refuse an output before any work.
void require_regular_or_absent(const std::string& path);

// Throws Error naming `path` unless a file can be written there without harm:
// absent or a regular file (require_regular_or_absent), not the same file as
// any of `inputs` (the case file a run reads, a shard a merge reads), and in
// a folder that exists and may be written. For commands to call before any
// work, so that a run is not lost to a bad output path.
void require_output_file(const std::string& path, const std::vector<std::string>& inputs = {});

// Throws Error naming `path` unless a folder of outputs can be written there
// as a set (AtomicFolder) without harm: absent, an empty folder, or (with
// `overwrite`) a folder to be replaced whole; not one of `inputs`, nor a
// folder holding one (a replaced folder would take the input with it); in a
// folder that exists and may be written. For commands to call before any work.
void require_output_folder(const std::string& path, bool overwrite,
                           const std::vector<std::string>& inputs = {});

// A folder of outputs written as a set, so that a reader never sees some
// files of one run beside files of another: the files go to a fresh hidden
// folder beside `path` (same file system), which commit() renames onto it.
// An existing `path` is replaced whole when `overwrite` is set (renamed
// aside, the new folder renamed in, the old one removed); otherwise only an
// empty folder is replaced, and a run that finds `path` filled by another run
// meanwhile fails naming it, its own outputs discarded. The temporary folder
// never survives a failure, nor SIGINT, SIGTERM or SIGHUP once
// remove_temporaries_on_signals() has been called; one left by a process
// killed outright (SIGKILL, a crash) is removed by the next AtomicFolder of
// the same path on the same host. It holds files only.
class AtomicFolder {
 public:
  // Checks `path` (require_output_folder) and makes the temporary folder;
  // throws Error naming the path.
  AtomicFolder(std::string path, bool overwrite, const std::vector<std::string>& inputs = {});
  ~AtomicFolder();
  AtomicFolder(const AtomicFolder&) = delete;
  AtomicFolder& operator=(const AtomicFolder&) = delete;

  // Where the files of the set are written until commit().
  const std::string& temporary() const { return temporary_; }
  // Renames the temporary folder onto the path; throws Error naming it.
  void commit();

 private:
  void discard() noexcept;

  std::string path_;
  bool overwrite_ = false;
  std::string temporary_;
  std::size_t slot_ = AtomicFile::kUntracked;
};

// Installs handlers of SIGINT, SIGTERM, SIGHUP and SIGPIPE that remove the temporary
// files and folders of writes still under way and then end the process by the same signal,
// and ignores SIGXFSZ so that a file-size limit (ulimit -f) makes a write fail
// with an error instead of killing the process silently. For programs; a host
// with handlers of its own (an interpreter) need not call it.
void remove_temporaries_on_signals();

// A child process that writes into a temporary folder (gnuplot drawing a figure): the
// handlers of remove_temporaries_on_signals() kill it (SIGKILL) and wait for it before they
// remove the temporaries, so that it cannot write a file into a folder being removed (a PNG
// was once left in a hidden folder). `spawn` starts the child and returns its pid (or -1); it
// runs with the terminating signals blocked, so the child is registered before one can end the
// process; the child must set its own signal mask (posix_spawnattr_setsigmask) as it inherits
// the blocked one. wait() reaps the child and ends the registration.
class TrackedChild {
 public:
  template <typename Spawn>
  explicit TrackedChild(Spawn spawn) {
    start([&spawn] { return static_cast<long>(spawn()); });
  }
  ~TrackedChild();
  TrackedChild(const TrackedChild&) = delete;
  TrackedChild& operator=(const TrackedChild&) = delete;

  long pid() const { return pid_; }
  // The child's wait status (waitpid), once it has ended; it is unregistered before it is
  // reaped, so that the handler never signals a pid the system may have given another process.
  int wait();

 private:
  void start(const std::function<long()>& spawn);
  long pid_ = -1;
  std::size_t slot_ = 0;
};

}  // namespace gearimpact
