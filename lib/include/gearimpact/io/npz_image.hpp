// A NumPy .npz archive built in memory and returned as bytes, with the interface of Hdf5Image so
// that one record's writer fills either (docs/datasets.md, "A record's NPZ layout"). The archive
// is what numpy.savez writes and numpy.load reads: a ZIP file (PKWARE's APPNOTE 6.3, entries
// stored, not compressed) of .npy members in NumPy's format 1.0 (NEP 1: the magic "\x93NUMPY",
// the version, a little-endian header length and a Python-literal header padded to 64 bytes,
// then the array's bytes). Each dataset is the member PATH.npy (the path without its leading
// "/"), each text PATH.txt (UTF-8), and every attribute of every group and dataset goes to one
// member attributes.json ({path: {name: value}}, NaN as null). The members' time stamps are
// 1980-01-01 00:00 (ZIP's earliest, numpy's too), so the bytes depend on the content only.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gearimpact {

// CRC-32 of ISO 3309 / ITU-T V.42 (the reflected polynomial 0xEDB88320), as ZIP stores it: zlib's.
std::uint32_t crc32(const std::string& bytes);

// The .npy file (format 1.0) of a 1-D array: descr "<f8" or "|i1".
std::string npy_file(const std::vector<double>& values);
std::string npy_file(const std::vector<std::int8_t>& values);

// A ZIP archive of stored members, in the given order. Throws InputError above ZIP's 32-bit
// limits (65535 members, 4 GiB in all).
std::string zip_archive(const std::vector<std::pair<std::string, std::string>>& members);

class NpzImage {
 public:
  void group(const std::string& path);
  // The member PATH.npy; "units", when not empty, an attribute of `path`.
  void dataset(const std::string& path, const std::vector<double>& values,
               const std::string& units = {});
  void dataset(const std::string& path, const std::vector<std::int8_t>& values,
               const std::string& units = {});
  // The member PATH.txt.
  void text(const std::string& path, const std::string& value);
  void attribute(const std::string& path, const std::string& name, double value);
  void attribute(const std::string& path, const std::string& name, std::int64_t value);
  void attribute(const std::string& path, const std::string& name, const std::string& value);

  // The archive: the members in the order given, then attributes.json.
  std::string bytes() const;

 private:
  std::vector<std::pair<std::string, std::string>> members_;
  // attributes.json's text, in order: paths in the order first named, names within them.
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> attributes_;
  void add(const std::string& path, const std::string& name, std::string json_value);
};

}  // namespace gearimpact
