#include "gearimpact/io/signal_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/results.hpp"

namespace gearimpact {
namespace {

using Json = nlohmann::ordered_json;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

Json optional_number(const std::optional<double>& v) {
  return v ? Json(*v) : Json(nullptr);
}

}  // namespace

namespace {

// At most a short prefix of a text from the file in a message: a header of megabytes or a line
// of NULs is not echoed.
std::string shown(const std::string& text) {
  constexpr std::size_t kShown = 60;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kShown; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    out += byte < 0x20 || byte == 0x7f ? '?' : text[i];
  }
  if (text.size() > kShown) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

// The file's lines, read through a descriptor that was checked to be a regular file before a
// byte was read (a FIFO without a writer would block an open for reading, a device would not
// end), each at most kLongestCsvLine bytes and free of NULs.
class CsvLines {
 public:
  explicit CsvLines(const std::string& path) : path_(path) {
    const auto refuse = [&](const std::string& why) {
      throw InputError(std::vector<Problem>{refused_problem(
          "input file", path, why,
          "a regular CSV file of at most " + std::to_string(kLargestCsvBytes >> 30) + " GiB")});
    };
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) refuse(std::strerror(errno));
    if (!S_ISREG(status.st_mode)) refuse("not a regular file (a FIFO, device or folder)");
    // O_NONBLOCK: should a FIFO replace the file after stat, the open still returns at once.
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) refuse(std::strerror(errno));
    if (::fstat(fd_, &status) != 0 || !S_ISREG(status.st_mode)) {
      ::close(fd_);
      refuse("not a regular file (a FIFO, device or folder)");
    }
    if (static_cast<std::uintmax_t>(status.st_size) > kLargestCsvBytes) {
      ::close(fd_);
      refuse("is " + std::to_string(status.st_size) + " bytes");
    }
  }
  ~CsvLines() { ::close(fd_); }
  CsvLines(const CsvLines&) = delete;
  CsvLines& operator=(const CsvLines&) = delete;

  // The next line without its "\n" (or "\r\n"); false at the end of the file.
  bool next(std::string& line) {
    line.clear();
    for (;;) {
      if (at_ == size_) {
        const ssize_t n = ::read(fd_, buffer_.data(), buffer_.size());
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
          throw InputError(std::vector<Problem>{
              refused_problem("input file", path_, std::strerror(errno), "a readable CSV file")});
        }
        at_ = 0;
        size_ = static_cast<std::size_t>(n);
        if (n == 0) break;
      }
      const char* begin = buffer_.data() + at_;
      const auto* newline = static_cast<const char*>(std::memchr(begin, '\n', size_ - at_));
      const std::size_t take = newline ? static_cast<std::size_t>(newline - begin) : size_ - at_;
      if (std::memchr(begin, '\0', take) != nullptr)
        refuse_line(line + std::string(begin, take), "holds a NUL byte: not text");
      line.append(begin, take);
      at_ += take;
      if (line.size() > kLongestCsvLine)
        refuse_line(line, "is longer than " + std::to_string(kLongestCsvLine) + " bytes");
      if (newline) {
        ++at_;
        ++number_;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
      }
    }
    if (line.empty()) return false;
    ++number_;
    if (line.back() == '\r') line.pop_back();
    return true;
  }
  std::size_t number() const { return number_; }

 private:
  [[noreturn]] void refuse_line(const std::string& line, const std::string& why) const {
    throw InputError(std::vector<Problem>{
        refused_problem(path_ + ":" + std::to_string(number_ + 1), shown(line), why,
                        "lines of at most " + std::to_string(kLongestCsvLine) +
                            " bytes of text (a header of names, rows of numbers)")});
  }

  std::string path_;
  int fd_ = -1;
  std::array<char, 1 << 16> buffer_{};
  std::size_t at_ = 0;
  std::size_t size_ = 0;
  std::size_t number_ = 0;
};

}  // namespace

std::vector<std::vector<double>> read_csv_columns(const std::string& path,
                                                  const std::vector<std::string>& names,
                                                  const std::vector<std::string>& chosen_by) {
  CsvLines in(path);
  std::string line;
  if (!in.next(line)) throw InputError("input file", path, "a CSV file with a header");
  // A UTF-8 byte order mark, which some editors and spreadsheets put first, is no part of the
  // first name.
  if (line.compare(0, 3, "\xEF\xBB\xBF") == 0) line.erase(0, 3);
  const std::vector<std::string> header = split(line);
  std::vector<std::size_t> index;
  for (std::size_t c = 0; c < names.size(); ++c) {
    const std::string& name = names[c];
    const std::string flag = c < chosen_by.size() ? chosen_by[c] : "column";
    const auto found = std::find(header.begin(), header.end(), name);
    if (found == header.end()) {
      std::string known;
      for (const std::string& h : header) known += (known.empty() ? "" : ", ") + h;
      throw InputError(std::vector<Problem>{refused_problem(
          flag, shown(name), "no such column in " + path, "one of " + shown(known))});
    }
    if (std::find(found + 1, header.end(), name) != header.end()) {
      throw InputError(std::vector<Problem>{
          refused_problem(flag, shown(name), "two columns of " + path + " have this name",
                          "a column whose name the header holds once")});
    }
    index.push_back(static_cast<std::size_t>(found - header.begin()));
  }
  std::vector<std::vector<double>> columns(names.size());
  std::size_t rows = 0;
  while (in.next(line)) {
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(in.number());
    if (++rows > kMostCsvRows) {
      throw InputError(
          "input file", path,
          "at most " + std::to_string(kMostCsvRows) + " rows (as simulate's max_rows)");
    }
    const std::vector<std::string> fields = split(line);
    if (fields.size() != header.size()) {
      throw InputError(std::vector<Problem>{
          refused_problem(where, shown(line), std::to_string(fields.size()) + " fields",
                          std::to_string(header.size()) + " fields a row, as the header has")});
    }
    for (std::size_t c = 0; c < names.size(); ++c) {
      const std::string& text = fields[index[c]];
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
        throw InputError(names[c] + " (" + where + ")", shown(text), "a finite number");
      }
      columns[c].push_back(value);
    }
  }
  return columns;
}

std::string spectrum_csv(const signals::Spectrum& spectrum, const std::string& abscissa) {
  std::string out = abscissa + ",amplitude\n";
  for (std::size_t k = 0; k < spectrum.frequency.size(); ++k) {
    out += format_data_number(spectrum.frequency[k]) + "," +
           format_data_number(spectrum.amplitude[k]) + "\n";
  }
  return out;
}

std::string tsa_csv(const std::vector<double>& tsa, const signals::TsaParts* parts) {
  std::string out = "angle_rad,tsa";
  if (parts != nullptr) out += ",regular,residual,difference,mesh_band,mesh_band_envelope";
  out += "\n";
  const double step = 2.0 * pi / static_cast<double>(tsa.size());
  for (std::size_t j = 0; j < tsa.size(); ++j) {
    out += format_data_number(static_cast<double>(j) * step) + "," + format_data_number(tsa[j]);
    if (parts != nullptr) {
      for (const std::vector<double>* v : {&parts->regular, &parts->residual, &parts->difference,
                                           &parts->mesh_band, &parts->mesh_band_envelope}) {
        out += "," + format_data_number((*v)[j]);
      }
    }
    out += "\n";
  }
  return out;
}

std::string indicators_json(const SignalsRun& run, const signals::Indicators& i) {
  Json j;
  j["input"] = run.input;
  j["column"] = run.column;
  j["time_column"] = run.time_column;
  j["record_start_s"] = run.start_s;
  j["record_end_s"] = run.end_s;
  j["resampling"] = "cubic Lagrange through the four nearest samples (fourth order)";
  j["sample_rate_hz"] = run.sample_rate_hz;
  j["record_rate_hz"] = run.record_rate_hz;
  if (run.anti_alias) {
    const signals::KaiserLowPass& f = *run.anti_alias;
    Json a;
    a["filter"] = "linear-phase FIR, Kaiser window (no delay), on the record's own uniform grid";
    a["passband_edge_hz"] = f.pass_hz;
    a["stopband_edge_hz"] = f.stop_hz;
    a["attenuation_db"] = f.attenuation_db;
    a["taps"] = f.order + 1;
    a["kaiser_beta"] = f.beta;
    a["input_rate_hz"] = f.rate_hz;
    j["anti_alias"] = a;
    j["alias_free_band_hz"] = f.pass_hz;
  } else {
    j["anti_alias"] = nullptr;
  }
  j["samples"] = run.samples;
  j["window"] = run.window;
  j["amplitude_scaling"] = "a sinusoid of amplitude A at a bin reads A (coherent gain corrected)";
  if (!run.angle_column.empty()) {
    j["angle_column"] = run.angle_column;
    j["angle_grid_per_revolution"] = run.angle_grid;
    j["samples_per_revolution"] = run.samples_per_revolution;
    j["tsa_anti_alias"] =
        "orders up to max_order (the record's band over the fastest revolution's speed) and "
        "below samples_per_revolution / 2 kept, the rest removed (DFT)";
    j["band_hz"] = run.band_hz ? Json(*run.band_hz) : Json("0.4 of the sample rate");
    j["max_order"] = run.max_order;
    j["indicator_grid_per_revolution"] = run.indicator_grid;
    j["revolutions"] = run.revolutions;
    j["shaft_frequency_hz"] = run.shaft_frequency_hz;
  }
  if (run.sets) {
    j["teeth"] = run.sets->teeth;
    j["shaft_orders"] = run.sets->shaft_orders;
    j["sidebands"] = run.sets->sidebands;
    j["nb4_harmonic"] = run.nb4_harmonic;
    j["nb4_half_width"] = run.nb4_half_width;
    j["mesh_frequency_hz"] = run.shaft_frequency_hz * static_cast<double>(run.sets->teeth);
  }
  Json recorder;
  const auto section = [](const signals::SecondOrderSection& x, double gain) {
    Json m;
    m["frequency_hz"] = x.frequency_hz;
    m["damping_ratio"] = x.damping_ratio;
    m["gain"] = gain;
    return m;
  };
  recorder["accelerometer"] = run.accelerometer ? section(*run.accelerometer, 1.0) : Json();
  Json path = Json::array();
  for (const signals::SecondOrderSection& m : run.path) {
    path.push_back(section(m, signals::gain_at(m, 0.0)));
  }
  recorder["path"] = path;
  recorder["seed"] = run.seed;
  if (run.noise) {
    recorder["noise_snr_db"] = *run.noise_snr_db;
    recorder["noise_mode"] = run.noise_exact ? "exact" : "expected";
    recorder["noise_sigma"] = run.noise->sigma;
    recorder["realised_snr_db"] = run.noise->realised_snr_db;
  } else {
    recorder["noise_snr_db"] = nullptr;
  }
  if (run.adc) {
    recorder["range"] = *run.adc_range;
    recorder["bits"] = run.adc_bits;
    recorder["lsb"] = run.adc->lsb;
    recorder["clipped"] = run.adc->clipped;
  } else {
    recorder["range"] = nullptr;
  }
  j["recorder"] = recorder;
  Json record;
  record["rms"] = i.rms;
  record["peak"] = i.peak;
  record["crest_factor"] = optional_number(i.crest_factor);
  record["kurtosis"] = optional_number(i.kurtosis);
  j["record"] = record;
  Json gear;
  gear["tsa_rms"] = optional_number(i.tsa_rms);
  gear["tsa_crest_factor"] = optional_number(i.tsa_crest_factor);
  gear["tsa_kurtosis"] = optional_number(i.tsa_kurtosis);
  gear["fm0"] = optional_number(i.fm0);
  gear["fm4"] = optional_number(i.fm4);
  gear["na4"] = optional_number(i.na4);
  gear["nb4"] = optional_number(i.nb4);
  gear["m6a"] = optional_number(i.m6a);
  gear["m8a"] = optional_number(i.m8a);
  gear["energy_ratio"] = optional_number(i.energy_ratio);
  gear["sideband_level"] = optional_number(i.sideband_level);
  j["gear"] = gear;
  j["definitions"] = "docs/signals.md";
  return j.dump(2) + "\n";
}

}  // namespace gearimpact
