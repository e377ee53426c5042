// A MATLAB v5 MAT-file built through libmatio (Debian: libmatio-dev; optional at configure time)
// and returned as bytes, with the interface of Hdf5Image so that one record's writer fills either
// (docs/datasets.md, "A record's MAT layout"). MATLAB has no attributes and its names are
// identifiers, so the HDF5 layout maps as: a dataset of the root is a variable ("/time": time), a
// dataset of a group is a field of the group's struct ("/truth/w1_rad_s": truth.w1_rad_s), a text
// is a char row, and the attributes of each path are a struct under `attributes`, the path's
// name made an identifier ("/" is attributes.root, "/signals/sensor" attributes.signals_sensor;
// any other character than a letter, a digit or "_" becomes "_": "faults[0].depth_m" is
// faults_0__depth_m). Uncompressed, with a fixed header text, so the bytes depend on the content
// only. libmatio writes only to a named file: the image is written to a private temporary file
// (mkstemp) under one lock and read back; the caller writes the bytes with the one safe writer.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace gearimpact {

// Whether this build has libmatio (else MatImage::bytes throws InputError naming the format).
bool mat_files_available();

// The MATLAB identifier of an HDF5 path or attribute name (see above), at most 63 characters.
std::string matlab_name(const std::string& name);

class MatImage {
 public:
  void group(const std::string& path);
  void dataset(const std::string& path, const std::vector<double>& values,
               const std::string& units = {});
  void dataset(const std::string& path, const std::vector<std::int8_t>& values,
               const std::string& units = {});
  void text(const std::string& path, const std::string& value);
  void attribute(const std::string& path, const std::string& name, double value);
  void attribute(const std::string& path, const std::string& name, std::int64_t value);
  void attribute(const std::string& path, const std::string& name, const std::string& value);

  std::string bytes() const;

  // One value: a double column, an int8 column, a char row, an int64 or a double scalar.
  struct Value {
    enum Kind { f8, i1, text, i8, scalar } kind = f8;
    std::vector<double> f;
    std::vector<std::int8_t> b;
    std::string s;
    std::int64_t i = 0;
  };

 private:
  // Variables and group structs, in the order first named: (name, fields) where a root
  // variable has one field of the empty name.
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, Value>>>> variables_;
  std::vector<std::pair<std::string, std::vector<std::pair<std::string, Value>>>> attributes_;
  void put(const std::string& path, Value v);
  void add(const std::string& path, const std::string& name, Value v);
};

}  // namespace gearimpact
