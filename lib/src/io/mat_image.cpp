#include "gearimpact/io/mat_image.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>

#include "gearimpact/error.hpp"

#ifdef GEARIMPACT_HAVE_MATIO
#include <matio.h>
#include <unistd.h>
#endif

namespace gearimpact {

bool mat_files_available() {
#ifdef GEARIMPACT_HAVE_MATIO
  return true;
#else
  return false;
#endif
}

std::string matlab_name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    out += keep ? c : '_';
  }
  // An identifier starts with a letter: "/" is the root, "/truth" truth.
  while (!out.empty() && out.front() == '_') out.erase(out.begin());
  if (out.empty()) return "root";
  if (!(out.front() >= 'a' && out.front() <= 'z') && !(out.front() >= 'A' && out.front() <= 'Z')) {
    out = "x" + out;
  }
  return out.substr(0, 63);
}

void MatImage::put(const std::string& path, Value v) {
  const std::size_t slash = path.find('/', 1);
  if (path.empty() || path[0] != '/' ||
      (slash != std::string::npos && path.find('/', slash + 1) != std::string::npos)) {
    throw InputError("MAT-file path", path, "/NAME or /GROUP/NAME (one level of groups)");
  }
  const std::string variable =
      matlab_name(slash == std::string::npos ? path : path.substr(0, slash));
  const std::string field = slash == std::string::npos ? "" : matlab_name(path.substr(slash + 1));
  for (auto& [name, fields] : variables_) {
    if (name == variable) {
      fields.emplace_back(field, std::move(v));
      return;
    }
  }
  variables_.push_back({variable, {{field, std::move(v)}}});
}

void MatImage::add(const std::string& path, const std::string& name, Value v) {
  const std::string key = matlab_name(path);
  for (auto& [p, list] : attributes_) {
    if (p == key) {
      list.emplace_back(matlab_name(name), std::move(v));
      return;
    }
  }
  attributes_.push_back({key, {{matlab_name(name), std::move(v)}}});
}

void MatImage::group(const std::string& path) {
  (void)path;  // a group is a struct once it has a field
}

void MatImage::dataset(const std::string& path, const std::vector<double>& values,
                       const std::string& units) {
  Value v;
  v.kind = Value::f8;
  v.f = values;
  put(path, std::move(v));
  if (!units.empty()) attribute(path, "units", units);
}

void MatImage::dataset(const std::string& path, const std::vector<std::int8_t>& values,
                       const std::string& units) {
  Value v;
  v.kind = Value::i1;
  v.b = values;
  put(path, std::move(v));
  if (!units.empty()) attribute(path, "units", units);
}

void MatImage::text(const std::string& path, const std::string& value) {
  Value v;
  v.kind = Value::text;
  v.s = value;
  put(path, std::move(v));
}

void MatImage::attribute(const std::string& path, const std::string& name, double value) {
  Value v;
  v.kind = Value::scalar;
  v.f = {value};
  add(path, name, std::move(v));
}

void MatImage::attribute(const std::string& path, const std::string& name, std::int64_t value) {
  Value v;
  v.kind = Value::i8;
  v.i = value;
  add(path, name, std::move(v));
}

void MatImage::attribute(const std::string& path, const std::string& name,
                         const std::string& value) {
  Value v;
  v.kind = Value::text;
  v.s = value;
  add(path, name, std::move(v));
}

#ifdef GEARIMPACT_HAVE_MATIO
namespace {

// A matio variable of one value (its data copied, freed with it).
matvar_t* variable_of(const char* name, const MatImage::Value& v) {
  size_t dims[2] = {1, 1};
  switch (v.kind) {
    case MatImage::Value::f8:
      dims[0] = v.f.size();
      return Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                           const_cast<double*>(v.f.data()), 0);
    case MatImage::Value::i1:
      dims[0] = v.b.size();
      return Mat_VarCreate(name, MAT_C_INT8, MAT_T_INT8, 2, dims,
                           const_cast<std::int8_t*>(v.b.data()), 0);
    case MatImage::Value::text:
      // A char row of the text's bytes (UTF-8; MATLAB reads ASCII as is).
      dims[1] = v.s.size();
      return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UINT8, 2, dims, const_cast<char*>(v.s.data()),
                           0);
    case MatImage::Value::i8:
      return Mat_VarCreate(name, MAT_C_INT64, MAT_T_INT64, 2, dims, const_cast<std::int64_t*>(&v.i),
                           0);
    case MatImage::Value::scalar:
      return Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                           const_cast<double*>(v.f.data()), 0);
  }
  return nullptr;
}

// A 1x1 struct of the fields.
matvar_t* struct_of(const std::string& name,
                    const std::vector<std::pair<std::string, MatImage::Value>>& fields) {
  std::vector<const char*> names;
  for (const auto& f : fields) names.push_back(f.first.c_str());
  size_t dims[2] = {1, 1};
  matvar_t* s =
      Mat_VarCreateStruct(name.c_str(), 2, dims, names.data(), static_cast<unsigned>(names.size()));
  if (s == nullptr) throw Error("libmatio: the struct " + name + " was not made");
  for (const auto& [field, value] : fields) {
    matvar_t* v = variable_of(field.c_str(), value);
    if (v == nullptr) {
      Mat_VarFree(s);
      throw Error("libmatio: the field " + name + "." + field + " was not made");
    }
    // The struct owns the field from here (the previous field, none, is returned).
    Mat_VarSetStructFieldByName(s, field.c_str(), 0, v);
  }
  return s;
}

std::mutex& matio_lock() {
  static std::mutex m;
  return m;
}

}  // namespace
#endif

std::string MatImage::bytes() const {
#ifdef GEARIMPACT_HAVE_MATIO
  // One image at a time: records made on several threads take turns (libmatio's thread safety
  // is not documented).
  const std::lock_guard<std::mutex> lock(matio_lock());
  std::vector<matvar_t*> all;
  const auto free_all = [&all] {
    for (matvar_t* v : all) Mat_VarFree(v);
  };
  try {
    for (const auto& [name, fields] : variables_) {
      all.push_back(fields.size() == 1 && fields[0].first.empty()
                        ? variable_of(name.c_str(), fields[0].second)
                        : struct_of(name, fields));
    }
    // attributes: a struct of a struct per path.
    std::vector<const char*> paths;
    for (const auto& a : attributes_) paths.push_back(a.first.c_str());
    size_t dims[2] = {1, 1};
    matvar_t* attributes = Mat_VarCreateStruct("attributes", 2, dims, paths.data(),
                                               static_cast<unsigned>(paths.size()));
    all.push_back(attributes);
    for (const auto& [path, list] : attributes_) {
      matvar_t* s = struct_of(path, list);
      Mat_VarSetStructFieldByName(attributes, path.c_str(), 0, s);
    }
  } catch (...) {
    free_all();
    throw;
  }
  std::string name = (std::filesystem::temp_directory_path() / "gearimpact-mat-XXXXXX").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    free_all();
    throw Error("a temporary file for libmatio could not be made in " +
                std::filesystem::temp_directory_path().string());
  }
  ::close(fd);
  // The 116-byte header text MATLAB shows; fixed, so that no date enters the bytes.
  mat_t* mat = Mat_CreateVer(name.c_str(), "MATLAB 5.0 MAT-file, written by gearimpact (libmatio)",
                             MAT_FT_MAT5);
  bool ok = mat != nullptr;
  for (matvar_t* v : all) {
    ok = ok && Mat_VarWrite(mat, v, MAT_COMPRESSION_NONE) == 0;
  }
  if (mat != nullptr) ok = Mat_Close(mat) == 0 && ok;
  free_all();
  std::ifstream in(name, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  ok = ok && in.good();
  std::error_code ignored;
  std::filesystem::remove(name, ignored);
  if (!ok) throw Error("libmatio could not write the MAT-file " + name);
  return bytes.str();
#else
  throw InputError("dataset.format", "\"mat\"",
                   "\"hdf5\" or \"npz\": this build has no libmatio (Debian: libmatio-dev; "
                   "reconfigure after installing it)");
#endif
}

}  // namespace gearimpact
