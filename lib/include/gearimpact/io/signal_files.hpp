// The files of `gearimpact signals`: columns read from a CSV file the program
// wrote, the spectra, the TSA and its parts, the indicators.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/signals/decimate.hpp"
#include "gearimpact/signals/indicators.hpp"
#include "gearimpact/signals/recorder.hpp"
#include "gearimpact/signals/spectrum.hpp"
#include "gearimpact/signals/tsa.hpp"

namespace gearimpact {

// The bounds of a CSV file read_csv_columns reads, checked as it reads: its size (from the
// file system, before a byte is read), a line's length and the rows (simulate's max_rows).
constexpr std::uintmax_t kLargestCsvBytes = std::uintmax_t{16} << 30;
constexpr std::size_t kLongestCsvLine = 1 << 16;
constexpr std::size_t kMostCsvRows = 50000000;

// The columns `names` of the CSV file `path` (a header line of names, then
// rows of numbers), in that order; a UTF-8 byte order mark before the header
// is skipped. Throws InputError naming, for a missing column or one whose name
// the header holds twice, what chose it (`chosen_by`, e.g. the flag
// "--column"; "column" when empty) with the header's names, and file:line
// for a row of another number of fields than the header's or a field that is
// not a finite number; and the file unless it is a regular file within the
// bounds above (a FIFO or device is refused before it is read). A message
// quotes at most a short prefix of what the file holds.
std::vector<std::vector<double>> read_csv_columns(const std::string& path,
                                                  const std::vector<std::string>& names,
                                                  const std::vector<std::string>& chosen_by = {});

// "ABSCISSA,amplitude" rows of a spectrum (ABSCISSA: frequency_hz or order).
std::string spectrum_csv(const signals::Spectrum& spectrum, const std::string& abscissa);

// One row per angle step of one revolution: angle_rad (from the shaft's
// first multiple of 2 pi), tsa, and with `parts` regular, residual,
// difference, mesh_band, mesh_band_envelope.
std::string tsa_csv(const std::vector<double>& tsa, const signals::TsaParts* parts);

// What the analysis read and chose, for indicators.json.
struct SignalsRun {
  std::string input;
  std::string column;
  std::string time_column;
  // The record's first and last time, s: the rows analysed (from --from on).
  double start_s = 0.0;
  double end_s = 0.0;
  std::string angle_column;  // empty without an angle
  double sample_rate_hz = 0.0;
  double record_rate_hz = 0.0;  // the record's own, 1 / its median spacing
  // The anti-alias decimator before a grid coarser than the record (signals/decimate.hpp);
  // empty when the grid is not coarser.
  std::optional<signals::KaiserLowPass> anti_alias;
  std::size_t samples = 0;
  std::string window;
  std::size_t samples_per_revolution = 0;  // of the TSA
  std::size_t angle_grid = 0;  // of the resampling on the angle (and the order spectrum)
  std::size_t revolutions = 0;
  std::optional<signals::OrderSets> sets;
  double shaft_frequency_hz = 0.0;  // mean, from the angle; 0 without one
  // The TSA's band (OrderAnalysis): --band if given, the highest order kept, the indicators'
  // grid, NB4's harmonic h* and half-width.
  std::optional<double> band_hz;
  std::size_t max_order = 0;
  std::size_t indicator_grid = 0;
  std::size_t nb4_harmonic = 0;
  std::size_t nb4_half_width = 0;
  // The recorder's parts applied to the record (signals/recorder.hpp), each absent unless asked.
  std::optional<signals::SecondOrderSection> accelerometer;
  std::vector<signals::SecondOrderSection> path;  // drawn from `seed`
  std::optional<double> noise_snr_db;
  bool noise_exact = false;
  std::optional<signals::NoiseResult> noise;
  std::optional<double> adc_range;
  int adc_bits = 0;
  std::optional<signals::AdcResult> adc;
  unsigned long long seed = 0;
};

// The run and every indicator (null where it is absent: no gear given, or 0/0).
std::string indicators_json(const SignalsRun& run, const signals::Indicators& indicators);

}  // namespace gearimpact
