#include "gearimpact/signals/indicators.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact::signals {
namespace {

void check_record(const std::vector<double>& x) {
  if (x.size() < 2) {
    throw InputError("record length", std::to_string(x.size()), "at least 2 samples");
  }
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) {
      throw InputError("record sample " + std::to_string(i + 1), x[i], "a finite value");
    }
  }
}

double mean(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

double standard_deviation(const std::vector<double>& x) {
  const double m = mean(x);
  double s = 0.0;
  for (double v : x) s += (v - m) * (v - m);
  return std::sqrt(s / static_cast<double>(x.size()));
}

std::optional<double> ratio(double num, double den) {
  if (!(den > 0.0) || !std::isfinite(num / den)) return std::nullopt;
  return num / den;
}

}  // namespace

double rms(const std::vector<double>& x) {
  check_record(x);
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s / static_cast<double>(x.size()));
}

double peak(const std::vector<double>& x) {
  check_record(x);
  double p = 0.0;
  for (double v : x) p = std::max(p, std::abs(v));
  return p;
}

double peak_to_peak(const std::vector<double>& x) {
  check_record(x);
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return *hi - *lo;
}

std::optional<double> normalised_moment(const std::vector<double>& x, int order, double scale) {
  check_record(x);
  const double m = mean(x);
  double m2 = 0.0;
  double mk = 0.0;
  double largest = 0.0;
  for (double v : x) {
    const double d = v - m;
    m2 += d * d;
    mk += std::pow(d, order);
    largest = std::max(largest, std::abs(v));
  }
  const double n = static_cast<double>(x.size());
  m2 /= n;
  mk /= n;
  largest = std::max(largest, scale);
  if (largest == 0.0 || std::sqrt(m2) <= kFlatRecord * largest) return std::nullopt;
  return mk / std::pow(m2, 0.5 * order);
}

Indicators record_indicators(const std::vector<double>& record) {
  Indicators i;
  i.rms = rms(record);
  i.peak = peak(record);
  i.crest_factor = ratio(i.peak, i.rms);
  i.kurtosis = normalised_moment(record, 4);
  return i;
}

Indicators gear_indicators(const std::vector<double>& record, const TsaParts& parts,
                           const OrderSets& sets) {
  Indicators i = record_indicators(record);
  const std::vector<double>& tsa = parts.tsa;
  const double size = peak(tsa);
  i.tsa_rms = rms(tsa);
  i.tsa_kurtosis = normalised_moment(tsa, 4);
  i.tsa_crest_factor = ratio(size, *i.tsa_rms);
  double mesh_sum = 0.0;
  for (std::size_t k = sets.teeth; k < parts.order_amplitude.size(); k += sets.teeth) {
    mesh_sum += parts.order_amplitude[k];
  }
  // A mesh harmonic below rounding against the TSA's own size counts as none.
  i.fm0 = mesh_sum > kFlatRecord * size ? ratio(peak_to_peak(tsa), mesh_sum) : std::nullopt;
  i.fm4 = normalised_moment(parts.difference, 4, size);
  i.m6a = normalised_moment(parts.difference, 6, size);
  i.m8a = normalised_moment(parts.difference, 8, size);
  i.na4 = normalised_moment(parts.residual, 4, size);
  i.nb4 = normalised_moment(parts.mesh_band_envelope, 4, size);
  const double difference_rms = rms(parts.difference);
  const double regular_rms = rms(parts.regular);
  i.energy_ratio =
      regular_rms > kFlatRecord * size ? ratio(difference_rms, regular_rms) : std::nullopt;
  const double spread = standard_deviation(tsa);
  const double sidebands =
      parts.order_amplitude[sets.teeth - 1] + parts.order_amplitude[sets.teeth + 1];
  i.sideband_level = spread > kFlatRecord * size ? ratio(sidebands, spread) : std::nullopt;
  return i;
}

}  // namespace gearimpact::signals
