// Condition indicators of gear vibration (docs/signals.md: each formula and
// its source). Moments are central; "kurtosis" is the normalised fourth
// moment (3 for a Gaussian, not the excess).
#pragma once

#include <optional>
#include <vector>

#include "gearimpact/signals/tsa.hpp"

namespace gearimpact::signals {

// Of any record (at least 2 finite samples, else InputError):
double rms(const std::vector<double>& x);           // sqrt(mean x^2), the mean kept
double peak(const std::vector<double>& x);          // max |x|
double peak_to_peak(const std::vector<double>& x);  // max x - min x
// m_k / m_2^(k/2), m_k = mean (x - mean x)^k: 4 -> kurtosis, 6 -> M6A, 8 -> M8A.
// Empty for a flat record (see kFlatRecord); `scale` is the size of the
// signal the record was derived from (the TSA for its difference signal), 0
// for the record itself.
std::optional<double> normalised_moment(const std::vector<double>& x, int order,
                                        double scale = 0.0);

// A record counts as flat when its standard deviation is at most this
// fraction of its largest magnitude or of `scale` (or it is all zero): its
// normalised moments are then 0/0 of rounding errors and are reported absent,
// not as a number made of noise.
inline constexpr double kFlatRecord = 1e-12;

struct Indicators {
  // Of the record as given (the uniformly resampled signal).
  double rms = 0.0;
  double peak = 0.0;
  std::optional<double> crest_factor;  // peak / rms
  std::optional<double> kurtosis;
  // Of the TSA and its parts; absent without a gear (teeth) or where a ratio is 0/0.
  std::optional<double> tsa_rms;
  std::optional<double> tsa_kurtosis;
  std::optional<double> tsa_crest_factor;
  std::optional<double> fm0;             // peak-to-peak(TSA) / sum of mesh harmonic amplitudes
  std::optional<double> fm4;             // kurtosis of the difference signal
  std::optional<double> na4;             // kurtosis of the residual (single record)
  std::optional<double> nb4;             // kurtosis of the mesh band's envelope (single record)
  std::optional<double> m6a;             // normalised 6th moment of the difference signal
  std::optional<double> m8a;             // normalised 8th moment of the difference signal
  std::optional<double> energy_ratio;    // rms(difference) / rms(regular)
  std::optional<double> sideband_level;  // (A_{z-1} + A_{z+1}) / std(TSA)
};

// The record's own indicators only.
Indicators record_indicators(const std::vector<double>& record);
// The record's and those of the TSA's parts.
Indicators gear_indicators(const std::vector<double>& record, const TsaParts& parts,
                           const OrderSets& sets);

}  // namespace gearimpact::signals
