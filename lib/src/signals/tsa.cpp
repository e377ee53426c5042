#include "gearimpact/signals/tsa.hpp"

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

void check_order_sets(const OrderSets& s, std::size_t p) {
  check_samples_per_revolution(p);
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

TsaParts tsa_parts(const std::vector<double>& tsa, const OrderSets& sets) {
  const std::size_t p = tsa.size();
  check_order_sets(sets, p);
  for (std::size_t i = 0; i < p; ++i) {
    if (!std::isfinite(tsa[i])) {
      throw InputError("TSA sample " + std::to_string(i + 1), tsa[i], "a finite value");
    }
  }
  const std::vector<std::complex<double>> x = real_dft(tsa);
  const std::size_t bins = x.size();
  std::vector<bool> regular(bins), residual(bins), difference(bins), band(bins);
  TsaParts parts;
  parts.tsa = tsa;
  parts.order_amplitude.resize(bins);
  for (std::size_t k = 0; k < bins; ++k) {
    const Part part = part_of(k, sets);
    regular[k] = part != Part::other;
    residual[k] = part == Part::sideband || part == Part::other;
    difference[k] = part == Part::other;
    band[k] = k + sets.sidebands >= sets.teeth && k <= sets.teeth + sets.sidebands;
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
                             const char* signal_name) {
  check_samples_per_revolution(samples_per_revolution);
  if (sets) check_order_sets(*sets, samples_per_revolution);
  OrderAnalysis a;
  a.grid = samples_per_revolution;
  if (angle.size() >= 2 && angle.back() > angle.front()) {
    const double rows_per_revolution =
        static_cast<double>(angle.size() - 1) * 2.0 * pi / (angle.back() - angle.front());
    while (static_cast<double>(a.grid) < rows_per_revolution && a.grid < (std::size_t{1} << 23)) {
      a.grid *= 2;
    }
  }
  const AngleSignal on_angle = resample_on_angle(angle, signal, a.grid, angle_name, signal_name);
  a.revolutions = on_angle.revolutions;
  a.start_angle = on_angle.start_angle;
  a.orders = amplitude_spectrum(on_angle.values, static_cast<double>(a.grid), window);
  a.tsa = decimate_periodic(time_synchronous_average(on_angle), samples_per_revolution);
  if (sets) a.parts = tsa_parts(a.tsa, *sets);
  return a;
}

}  // namespace gearimpact::signals
