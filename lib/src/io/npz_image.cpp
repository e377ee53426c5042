#include "gearimpact/io/npz_image.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// Little-endian integers, as ZIP and the .npy header length store them, whatever the host's order.
void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xffu);
  out += static_cast<char>((v >> 8) & 0xffu);
}

void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffffu);
  put16(out, v >> 16);
}

// NEP 1's format 1.0: magic, version 1.0, the header's length (uint16 LE), the header (a Python
// dict literal) padded with spaces and ended by a newline so that the data starts at a multiple
// of 64 bytes (numpy's alignment).
std::string npy_header(const std::string& descr, std::size_t n) {
  std::string dict =
      "{'descr': '" + descr + "', 'fortran_order': False, 'shape': (" + std::to_string(n) + ",), }";
  const std::size_t fixed = 10;  // magic (6), version (2), length (2)
  std::size_t total = fixed + dict.size() + 1;
  const std::size_t padded = (total + 63) / 64 * 64;
  dict.append(padded - total, ' ');
  dict += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  put16(out, static_cast<std::uint32_t>(dict.size()));
  return out + dict;
}

// The DOS date of 1980-01-01 (day 1, month 1, year 0 from 1980) at 00:00.
constexpr std::uint32_t kDosDate = (1u << 5) | 1u;

}  // namespace

std::uint32_t crc32(const std::string& bytes) {
  // zlib's CRC-32 (Debian: zlib1g-dev), over the bytes in pieces its uInt length can hold.
  uLong c = ::crc32(0L, Z_NULL, 0);
  const auto* data = reinterpret_cast<const Bytef*>(bytes.data());
  std::size_t left = bytes.size();
  while (left > 0) {
    const auto piece = static_cast<uInt>(std::min<std::size_t>(left, 1u << 30));
    c = ::crc32(c, data, piece);
    data += piece;
    left -= piece;
  }
  return static_cast<std::uint32_t>(c);
}

std::string npy_file(const std::vector<double>& values) {
  std::string out = npy_header("<f8", values.size());
  out.reserve(out.size() + 8 * values.size());
  for (const double v : values) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    put32(out, static_cast<std::uint32_t>(bits & 0xffffffffu));
    put32(out, static_cast<std::uint32_t>(bits >> 32));
  }
  return out;
}

std::string npy_file(const std::vector<std::int8_t>& values) {
  std::string out = npy_header("|i1", values.size());
  for (const std::int8_t v : values) out += static_cast<char>(v);
  return out;
}

std::string zip_archive(const std::vector<std::pair<std::string, std::string>>& members) {
  constexpr double kMost = std::numeric_limits<std::uint32_t>::max();
  double total = 0.0;
  for (const auto& [name, data] : members) {
    total += 76.0 + 2.0 * static_cast<double>(name.size()) + static_cast<double>(data.size());
  }
  if (members.size() >= 0xffffu || total >= kMost) {
    throw InputError("npz archive",
                     std::to_string(members.size()) + " members, " +
                         std::to_string(static_cast<long long>(total)) + " bytes",
                     "at most 65534 members and 4 GiB (ZIP without its 64-bit extension)");
  }
  std::string out;
  std::string directory;
  for (const auto& [name, data] : members) {
    const std::uint32_t offset = static_cast<std::uint32_t>(out.size());
    const std::uint32_t crc = crc32(data);
    const auto size = static_cast<std::uint32_t>(data.size());
    const auto name_size = static_cast<std::uint32_t>(name.size());
    // The local header (APPNOTE 4.3.7): version 2.0, no flags, stored, the time, the sizes.
    put32(out, 0x04034b50u);
    put16(out, 20);
    put16(out, 0);
    put16(out, 0);
    put16(out, 0);
    put16(out, kDosDate);
    put32(out, crc);
    put32(out, size);
    put32(out, size);
    put16(out, name_size);
    put16(out, 0);
    out += name;
    out += data;
    // Its central directory entry (4.3.12).
    put32(directory, 0x02014b50u);
    put16(directory, 20);
    put16(directory, 20);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, 0);
    put16(directory, kDosDate);
    put32(directory, crc);
    put32(directory, size);
    put32(directory, size);
    put16(directory, name_size);
    put16(directory, 0);  // extra field
    put16(directory, 0);  // comment
    put16(directory, 0);  // disk
    put16(directory, 0);  // internal attributes
    put32(directory, 0);  // external attributes
    put32(directory, offset);
    directory += name;
  }
  const auto directory_offset = static_cast<std::uint32_t>(out.size());
  out += directory;
  // The end of the central directory (4.3.16).
  put32(out, 0x06054b50u);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(members.size()));
  put16(out, static_cast<std::uint32_t>(members.size()));
  put32(out, static_cast<std::uint32_t>(directory.size()));
  put32(out, directory_offset);
  put16(out, 0);
  return out;
}

namespace {

std::string member_name(const std::string& path, const char* suffix) {
  return (path.rfind('/', 0) == 0 ? path.substr(1) : path) + suffix;
}

}  // namespace

void NpzImage::add(const std::string& path, const std::string& name, std::string json_value) {
  for (auto& [p, list] : attributes_) {
    if (p == path) {
      list.emplace_back(name, std::move(json_value));
      return;
    }
  }
  attributes_.push_back({path, {{name, std::move(json_value)}}});
}

void NpzImage::group(const std::string& path) {
  for (const auto& entry : attributes_) {
    if (entry.first == path) return;
  }
  attributes_.push_back({path, {}});
}

void NpzImage::dataset(const std::string& path, const std::vector<double>& values,
                       const std::string& units) {
  members_.emplace_back(member_name(path, ".npy"), npy_file(values));
  group(path);
  if (!units.empty()) attribute(path, "units", units);
}

void NpzImage::dataset(const std::string& path, const std::vector<std::int8_t>& values,
                       const std::string& units) {
  members_.emplace_back(member_name(path, ".npy"), npy_file(values));
  group(path);
  if (!units.empty()) attribute(path, "units", units);
}

void NpzImage::text(const std::string& path, const std::string& value) {
  members_.emplace_back(member_name(path, ".txt"), value);
  group(path);
}

void NpzImage::attribute(const std::string& path, const std::string& name, double value) {
  add(path, name, nlohmann::json(value).dump());
}

void NpzImage::attribute(const std::string& path, const std::string& name, std::int64_t value) {
  add(path, name, nlohmann::json(value).dump());
}

void NpzImage::attribute(const std::string& path, const std::string& name,
                         const std::string& value) {
  add(path, name, nlohmann::json(value).dump());
}

std::string NpzImage::bytes() const {
  std::string json = "{";
  for (std::size_t i = 0; i < attributes_.size(); ++i) {
    json += (i ? ",\n " : "\n ") + nlohmann::json(attributes_[i].first).dump() + ": {";
    const auto& list = attributes_[i].second;
    for (std::size_t k = 0; k < list.size(); ++k) {
      json += (k ? ",\n  " : "\n  ") + nlohmann::json(list[k].first).dump() + ": " + list[k].second;
    }
    json += list.empty() ? "}" : "\n }";
  }
  json += "\n}\n";
  std::vector<std::pair<std::string, std::string>> all = members_;
  all.emplace_back("attributes.json", json);
  return zip_archive(all);
}

}  // namespace gearimpact
