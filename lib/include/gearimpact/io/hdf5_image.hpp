// An HDF5 file built in memory and returned as bytes, through Debian's libhdf5 C API behind this
// one small interface (the layout the data sets write is in docs/datasets.md). Built in memory
// (the core driver without a backing store), so that the caller writes the bytes with the one
// safe writer (write_file_atomically) and a killed process never leaves a half-written HDF5 file;
// the bytes depend on the content only: object time stamps are off and the format's version
// bounds are fixed, so that one content gives one file, byte for byte, on one build.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace gearimpact {

// Debian's libhdf5 is the serial build, not thread-safe: an image holds the process's one HDF5
// lock from construction to destruction, so that images built on several threads take turns.
class Hdf5Image {
 public:
  Hdf5Image();
  ~Hdf5Image();
  Hdf5Image(const Hdf5Image&) = delete;
  Hdf5Image& operator=(const Hdf5Image&) = delete;

  // A group at `path` ("/truth"); its parent must exist.
  void group(const std::string& path);
  // A 1-D dataset at `path` (contiguous, uncompressed), with a string attribute "units" when
  // `units` is not empty.
  void dataset(const std::string& path, const std::vector<double>& values,
               const std::string& units = {});
  void dataset(const std::string& path, const std::vector<std::int8_t>& values,
               const std::string& units = {});
  // A scalar dataset of UTF-8 text (a fixed-length string of the text's bytes).
  void text(const std::string& path, const std::string& value);
  // Scalar attributes of the group or dataset at `path`.
  void attribute(const std::string& path, const std::string& name, double value);
  void attribute(const std::string& path, const std::string& name, std::int64_t value);
  void attribute(const std::string& path, const std::string& name, const std::string& value);

  // The file's bytes, complete (the file is flushed first); the image may still grow after.
  std::string bytes();

 private:
  struct Handles;
  std::unique_lock<std::mutex> lock_;  // first: held until the handles are closed
  std::unique_ptr<Handles> h_;
};

}  // namespace gearimpact
