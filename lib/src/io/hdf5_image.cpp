#include "gearimpact/io/hdf5_image.hpp"

#include <hdf5.h>

#include <string>
#include <vector>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw Error("HDF5: cannot " + what + " (libhdf5 " + std::to_string(H5_VERS_MAJOR) + "." +
              std::to_string(H5_VERS_MINOR) + ")");
}

hid_t checked(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void checked(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

// Closes an identifier of any kind at the end of a scope.
struct Closer {
  hid_t id;
  explicit Closer(hid_t i) : id(i) {}
  ~Closer() {
    if (id >= 0) H5Idec_ref(id);
  }
  Closer(const Closer&) = delete;
  Closer& operator=(const Closer&) = delete;
};

// A fixed-length UTF-8 string type of `size` bytes (at least one: HDF5 refuses 0).
hid_t string_type(std::size_t size) {
  const hid_t type = checked(H5Tcopy(H5T_C_S1), "copy the string type");
  checked(H5Tset_size(type, size == 0 ? 1 : size), "size a string type");
  checked(H5Tset_cset(type, H5T_CSET_UTF8), "set a string type's character set");
  checked(H5Tset_strpad(type, H5T_STR_NULLPAD), "set a string type's padding");
  return type;
}

}  // namespace

struct Hdf5Image::Handles {
  hid_t file = -1;
  hid_t group_properties = -1;
  hid_t dataset_properties = -1;
};

namespace {
std::mutex& hdf5_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

Hdf5Image::Hdf5Image() : lock_(hdf5_mutex()), h_(std::make_unique<Handles>()) {
  // Errors reach the caller as exceptions, not as HDF5's stack printed on stderr.
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t access = checked(H5Pcreate(H5P_FILE_ACCESS), "create file access properties");
  Closer access_closer(access);
  // In memory, grown 1 MiB at a time, never written to disk by the library.
  checked(H5Pset_fapl_core(access, std::size_t{1} << 20, 0), "select the core driver");
  // Fixed version bounds: the format never depends on the library's default choice.
  checked(H5Pset_libver_bounds(access, H5F_LIBVER_EARLIEST, H5F_LIBVER_V18),
          "fix the format's version bounds");
  const hid_t creation = checked(H5Pcreate(H5P_FILE_CREATE), "create file creation properties");
  Closer creation_closer(creation);
  checked(H5Pset_obj_track_times(creation, 0), "turn the root group's time stamps off");
  h_->file = checked(H5Fcreate("gearimpact-image.h5", H5F_ACC_TRUNC, creation, access),
                     "create an in-memory file");
  h_->group_properties = checked(H5Pcreate(H5P_GROUP_CREATE), "create group properties");
  checked(H5Pset_obj_track_times(h_->group_properties, 0), "turn group time stamps off");
  h_->dataset_properties = checked(H5Pcreate(H5P_DATASET_CREATE), "create dataset properties");
  checked(H5Pset_obj_track_times(h_->dataset_properties, 0), "turn dataset time stamps off");
}

Hdf5Image::~Hdf5Image() {
  for (const hid_t id : {h_->dataset_properties, h_->group_properties}) {
    if (id >= 0) H5Pclose(id);
  }
  if (h_->file >= 0) H5Fclose(h_->file);
}

void Hdf5Image::group(const std::string& path) {
  const hid_t g =
      checked(H5Gcreate2(h_->file, path.c_str(), H5P_DEFAULT, h_->group_properties, H5P_DEFAULT),
              "create group " + path);
  H5Gclose(g);
}

namespace {

template <typename T>
void write_dataset(hid_t file, hid_t properties, const std::string& path, hid_t type,
                   const std::vector<T>& values) {
  const hsize_t size = values.size();
  const hid_t space = checked(H5Screate_simple(1, &size, nullptr), "make the space of " + path);
  Closer space_closer(space);
  const hid_t set =
      checked(H5Dcreate2(file, path.c_str(), type, space, H5P_DEFAULT, properties, H5P_DEFAULT),
              "create dataset " + path);
  Closer set_closer(set);
  if (!values.empty()) {
    checked(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "write " + path);
  }
}

}  // namespace

void Hdf5Image::dataset(const std::string& path, const std::vector<double>& values,
                        const std::string& units) {
  write_dataset(h_->file, h_->dataset_properties, path, H5T_IEEE_F64LE, values);
  if (!units.empty()) attribute(path, "units", units);
}

void Hdf5Image::dataset(const std::string& path, const std::vector<std::int8_t>& values,
                        const std::string& units) {
  write_dataset(h_->file, h_->dataset_properties, path, H5T_STD_I8LE, values);
  if (!units.empty()) attribute(path, "units", units);
}

void Hdf5Image::text(const std::string& path, const std::string& value) {
  const hid_t type = string_type(value.size());
  Closer type_closer(type);
  const hid_t space = checked(H5Screate(H5S_SCALAR), "make a scalar space");
  Closer space_closer(space);
  const hid_t set = checked(H5Dcreate2(h_->file, path.c_str(), type, space, H5P_DEFAULT,
                                       h_->dataset_properties, H5P_DEFAULT),
                            "create dataset " + path);
  Closer set_closer(set);
  // A buffer of the type's size: an empty text is one NUL byte.
  std::string buffer = value.empty() ? std::string(1, '\0') : value;
  checked(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), "write " + path);
}

namespace {

void write_attribute(hid_t file, const std::string& path, const std::string& name, hid_t type,
                     const void* value) {
  const hid_t object = checked(H5Oopen(file, path.c_str(), H5P_DEFAULT), "open " + path);
  Closer object_closer(object);
  const hid_t space = checked(H5Screate(H5S_SCALAR), "make a scalar space");
  Closer space_closer(space);
  const hid_t attribute =
      checked(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
              "create attribute " + name + " of " + path);
  Closer attribute_closer(attribute);
  checked(H5Awrite(attribute, type, value), "write attribute " + name + " of " + path);
}

}  // namespace

void Hdf5Image::attribute(const std::string& path, const std::string& name, double value) {
  write_attribute(h_->file, path, name, H5T_IEEE_F64LE, &value);
}

void Hdf5Image::attribute(const std::string& path, const std::string& name, std::int64_t value) {
  write_attribute(h_->file, path, name, H5T_STD_I64LE, &value);
}

void Hdf5Image::attribute(const std::string& path, const std::string& name,
                          const std::string& value) {
  const hid_t type = string_type(value.size());
  Closer type_closer(type);
  std::string buffer = value.empty() ? std::string(1, '\0') : value;
  write_attribute(h_->file, path, name, type, buffer.data());
}

std::string Hdf5Image::bytes() {
  checked(H5Fflush(h_->file, H5F_SCOPE_GLOBAL), "flush the in-memory file");
  const ssize_t size = H5Fget_file_image(h_->file, nullptr, 0);
  if (size < 0) fail("measure the in-memory file");
  std::string image(static_cast<std::size_t>(size), '\0');
  if (H5Fget_file_image(h_->file, image.data(), image.size()) != size) {
    fail("copy the in-memory file");
  }
  return image;
}

}  // namespace gearimpact
