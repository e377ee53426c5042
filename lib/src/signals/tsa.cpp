#include "gearimpact/signals/tsa.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/signals/fft.hpp"

namespace gearimpact::signals {
namespace {

enum class Part { shaft, mesh, sideband, other };

// What order k (0..P/2) is for these sets; a mesh order wins over a shaft
// order or a sideband of a neighbour.
Part part_of(std::size_t k, const OrderSets& s) {
  if (k >= 1 && k % s.teeth == 0) return Part::mesh;
  if (k <= s.shaft_orders) return Part::shaft;
  const std::size_t below = k % s.teeth;      // distance above the harmonic under k
  const std::size_t above = s.teeth - below;  // distance below the harmonic over k
  if ((k >= s.teeth && below <= s.sidebands) || above <= s.sidebands) return Part::sideband;
  return Part::other;
}

std::vector<double> keep(const std::vector<std::complex<double>>& x, std::size_t n,
                         const std::vector<bool>& kept) {
  std::vector<std::complex<double>> y(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) y[k] = kept[k] ? x[k] : 0.0;
  return inverse_real_dft(y, n);
}

}  // namespace

std::vector<double> time_synchronous_average(const AngleSignal& signal) {
  const std::size_t p = signal.samples_per_revolution;
  if (p == 0 || signal.revolutions == 0 || signal.values.size() != p * signal.revolutions) {
    throw InputError("angle signal",
                     std::to_string(signal.values.size()) + " samples, " +
                         std::to_string(signal.revolutions) + " revolutions of " +
                         std::to_string(p),
                     "at least one whole revolution of samples");
  }
  std::vector<double> tsa(p, 0.0);
  for (std::size_t r = 0; r < signal.revolutions; ++r) {
    for (std::size_t j = 0; j < p; ++j) tsa[j] += signal.values[r * p + j];
  }
  for (double& v : tsa) v /= static_cast<double>(signal.revolutions);
  return tsa;
}

std::vector<double> decimate_periodic(const std::vector<double>& period, std::size_t p) {
  const std::size_t q = period.size();
  if (p < 4 || p > q) {
    throw InputError("samples per revolution", std::to_string(p),
                     "4 to the record's " + std::to_string(q) + " samples a revolution");
  }
  const std::vector<std::complex<double>> x = real_dft(period);
  std::vector<std::complex<double>> y(p / 2 + 1, 0.0);
  // The p-point DFT of the same continuous signal is the Q-point one times p/Q.
  const double scale = static_cast<double>(p) / static_cast<double>(q);
  for (std::size_t k = 0; 2 * k < p; ++k) y[k] = x[k] * scale;
  return inverse_real_dft(y, p);
}

std::size_t nb4_half_width(const OrderSets& sets) {
  return sets.nb4_half_width != 0 ? sets.nb4_half_width
                                  : (sets.teeth >= 1 ? (sets.teeth - 1) / 2 : 0);
}

std::size_t indicator_grid(std::size_t max_order) {
  std::size_t p = 16;
  while (p < 8 * max_order + 1 && p < (std::size_t{1} << 24)) p *= 2;
  return p;
}

std::vector<double> band_limited_period(const std::vector<double>& period, std::size_t p,
                                        std::size_t max_order) {
  const std::size_t q = period.size();
  if (p < 4 || q < 4) {
    throw InputError("samples per revolution", std::to_string(p) + " from " + std::to_string(q),
                     "at least 4 of each");
  }
  const std::vector<std::complex<double>> x = real_dft(period);
  std::vector<std::complex<double>> y(p / 2 + 1, 0.0);
  // The p-point DFT of the same continuous signal is the Q-point one times p/Q.
  const double scale = static_cast<double>(p) / static_cast<double>(q);
  for (std::size_t k = 0; 2 * k < p && 2 * k < q && k <= max_order; ++k) y[k] = x[k] * scale;
  return inverse_real_dft(y, p);
}

std::size_t band_max_order(const std::vector<double>& angle) {
  if (angle.size() < 2 || !(angle.back() > angle.front())) return 0;
  const double turn = 2.0 * pi;
  const double start = std::ceil(angle.front() / turn) * turn;
  // Samples in each whole revolution [start + 2 pi r, start + 2 pi (r + 1)).
  std::size_t fewest = 0;
  bool any = false;
  std::size_t count = 0;
  double next = start + turn;
  std::size_t i = 0;
  while (i < angle.size() && angle[i] < start) ++i;
  for (; i < angle.size(); ++i) {
    if (angle[i] >= next) {
      fewest = any ? std::min(fewest, count) : count;
      any = true;
      count = 0;
      next += turn;
      while (angle[i] >= next) next += turn;  // a revolution without samples would count 0
    }
    ++count;
  }
  return any ? static_cast<std::size_t>(std::floor(kBandFraction * static_cast<double>(fewest)))
             : 0;
}

void check_order_sets(const OrderSets& s, std::size_t p) {
  check_samples_per_revolution(p);
  if (s.nb4_half_width != 0 && (s.nb4_half_width < 2 || 2 * s.nb4_half_width >= s.teeth)) {
    throw InputError("nb4 half width", std::to_string(s.nb4_half_width),
                     "2 to " + std::to_string(s.teeth >= 1 ? (s.teeth - 1) / 2 : 0) + " for " +
                         std::to_string(s.teeth) +
                         " teeth, or 0 for that default (over z +- 1 the envelope's kurtosis is "
                         "1.5 whatever the fault)");
  }
  // Too many sidebands for the teeth first: the teeth' range below subtracts them, and
  // --sidebands 100000 once read as the teeth' fault, "3 to 0".
  if (s.teeth >= 3 && 2 * s.sidebands >= s.teeth) {
    throw InputError("sidebands", std::to_string(s.sidebands),
                     "0 to " + std::to_string((s.teeth - 1) / 2) + " for " +
                         std::to_string(s.teeth) +
                         " teeth (sidebands of neighbouring mesh harmonics apart)");
  }
  if (s.teeth < 3 || 2 * (s.teeth + s.sidebands) >= p) {
    throw InputError("teeth", std::to_string(s.teeth),
                     "3 to " + std::to_string((p - 1) / 2 - std::min(s.sidebands, (p - 1) / 2)) +
                         " for " + std::to_string(p) + " samples per revolution and " +
                         std::to_string(s.sidebands) +
                         " sidebands (the first mesh order and its sidebands below P/2)");
  }
  if (2 * s.sidebands >= s.teeth) {
    throw InputError("sidebands", std::to_string(s.sidebands),
                     "0 to " + std::to_string((s.teeth - 1) / 2) + " for " +
                         std::to_string(s.teeth) +
                         " teeth (sidebands of neighbouring mesh harmonics apart)");
  }
  if (s.shaft_orders + s.sidebands >= s.teeth) {
    throw InputError("shaft orders", std::to_string(s.shaft_orders),
                     "0 to " + std::to_string(s.teeth - s.sidebands - 1) + " for " +
                         std::to_string(s.teeth) + " teeth and " + std::to_string(s.sidebands) +
                         " sidebands (below the first lower sideband)");
  }
}

TsaParts tsa_parts(const std::vector<double>& tsa, const OrderSets& sets, std::size_t max_order) {
  const std::size_t p = tsa.size();
  check_order_sets(sets, p);
  for (std::size_t i = 0; i < p; ++i) {
    if (!std::isfinite(tsa[i])) {
      throw InputError("TSA sample " + std::to_string(i + 1), tsa[i], "a finite value");
    }
  }
  std::vector<std::complex<double>> x = real_dft(tsa);
  const std::size_t bins = x.size();
  // The orders the band holds: those above it zeroed everywhere.
  bool limited = false;
  for (std::size_t k = max_order + 1; k < bins && max_order < bins; ++k) {
    limited = limited || x[k] != 0.0;
    x[k] = 0.0;
  }
  std::vector<bool> regular(bins), residual(bins), difference(bins), band(bins);
  TsaParts parts;
  parts.tsa = limited ? inverse_real_dft(x, p) : tsa;
  parts.order_amplitude.resize(bins);
  // NB4's band about the strongest mesh harmonic h* whose band h z +- w lies strictly inside
  // (0, min(max_order, P/2)].
  const std::size_t w = nb4_half_width(sets);
  const std::size_t top = std::min(max_order, (p - 1) / 2);
  double strongest = -1.0;
  for (std::size_t h = 1; h * sets.teeth + w <= top; ++h) {
    if (std::abs(x[h * sets.teeth]) > strongest) {
      strongest = std::abs(x[h * sets.teeth]);
      parts.nb4_harmonic = h;
    }
  }
  parts.nb4_half_width = w;
  const std::size_t centre = parts.nb4_harmonic * sets.teeth;
  for (std::size_t k = 0; k < bins; ++k) {
    const Part part = part_of(k, sets);
    regular[k] = part != Part::other;
    residual[k] = part == Part::sideband || part == Part::other;
    difference[k] = part == Part::other;
    band[k] = parts.nb4_harmonic > 0 && k + w >= centre && k <= centre + w;
    const bool own_mirror = k == 0 || 2 * k == p;
    parts.order_amplitude[k] = (own_mirror ? 1.0 : 2.0) * std::abs(x[k]) / static_cast<double>(p);
  }
  parts.regular = keep(x, p, regular);
  parts.residual = keep(x, p, residual);
  parts.difference = keep(x, p, difference);
  parts.mesh_band = keep(x, p, band);
  // The analytic signal of the band: its positive orders doubled, the
  // negative ones zero (the band lies strictly inside 0 < k < P/2).
  std::vector<std::complex<double>> analytic(p, 0.0);
  for (std::size_t k = 0; k < bins; ++k) {
    if (band[k]) analytic[k] = 2.0 * x[k];
  }
  const std::vector<std::complex<double>> z = inverse_dft(analytic);
  parts.mesh_band_envelope.resize(p);
  for (std::size_t i = 0; i < p; ++i) parts.mesh_band_envelope[i] = std::abs(z[i]);
  return parts;
}

OrderAnalysis analyse_orders(const std::vector<double>& angle, const std::vector<double>& signal,
                             std::size_t samples_per_revolution, Window window,
                             const std::optional<OrderSets>& sets, const char* angle_name,
                             const char* signal_name, std::optional<std::size_t> max_order) {
  OrderAnalysis a;
  a.max_order = max_order ? *max_order : band_max_order(angle);
  a.indicator_grid = indicator_grid(a.max_order);
  if (samples_per_revolution == 0) samples_per_revolution = a.indicator_grid;
  a.samples_per_revolution = samples_per_revolution;
  check_samples_per_revolution(samples_per_revolution);
  if (sets) {
    check_order_sets(*sets, samples_per_revolution);
    if (a.max_order < sets->teeth + sets->sidebands) {
      throw InputError("band", "orders up to " + std::to_string(a.max_order),
                       "a band up to at least order " +
                           std::to_string(sets->teeth + sets->sidebands) +
                           ", the first mesh harmonic's upper sideband (a faster record, or a "
                           "wider band)");
    }
  }
  // The angle grid: the record's own rows a revolution, rounded (at least 16, at most 2^23),
  // whatever P, so that the TSA (and so every indicator) does not depend on P; on a record
  // locked to the shaft the grid's points are then the record's samples, where the cubic
  // returns each sample itself (elsewhere the cubic droops near the record's Nyquist order).
  a.grid = 16;
  if (angle.size() >= 2 && angle.back() > angle.front()) {
    const double rows_per_revolution =
        static_cast<double>(angle.size() - 1) * 2.0 * pi / (angle.back() - angle.front());
    a.grid = static_cast<std::size_t>(
        std::clamp(std::round(rows_per_revolution), 16.0, static_cast<double>(1 << 23)));
  }
  const AngleSignal on_angle = resample_on_angle(angle, signal, a.grid, angle_name, signal_name);
  a.revolutions = on_angle.revolutions;
  a.start_angle = on_angle.start_angle;
  a.orders = amplitude_spectrum(on_angle.values, static_cast<double>(a.grid), window);
  const std::vector<double> whole = time_synchronous_average(on_angle);
  a.tsa = band_limited_period(whole, samples_per_revolution, a.max_order);
  if (sets) {
    a.parts = tsa_parts(a.tsa, *sets, a.max_order);
    a.indicator_parts =
        tsa_parts(band_limited_period(whole, a.indicator_grid, a.max_order), *sets, a.max_order);
  }
  return a;
}

}  // namespace gearimpact::signals
