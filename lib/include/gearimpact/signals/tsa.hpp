// The time-synchronous average of a shaft's signal and the signals derived
// from it (docs/signals.md gives the definitions and their sources).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "gearimpact/signals/resample.hpp"
#include "gearimpact/signals/spectrum.hpp"

namespace gearimpact::signals {

// The mean over the revolutions of a signal sampled in the shaft's angle:
// tsa_j = (1/R) sum_r values[r P + j], j = 0..P-1. A part periodic in one
// revolution passes unchanged; noise uncorrelated between revolutions falls as
// 1/sqrt(R). Throws InputError for no whole revolution.
std::vector<double> time_synchronous_average(const AngleSignal& signal);

// A record of one period (one revolution) of Q samples reduced to p samples
// of the same period, p <= Q: its orders below p/2 kept exactly, order p/2
// and above removed (an ideal anti-alias filter by the DFT, exact for a
// periodic record such as a TSA). Resampling on the angle at fewer samples a
// revolution than the record holds would otherwise fold the orders above
// p/2 onto lower ones. Throws InputError unless 4 <= p <= Q.
std::vector<double> decimate_periodic(const std::vector<double>& period, std::size_t p);

// Which orders of the TSA (harmonics of the shaft, cycles per revolution)
// make its parts, for a gear of `teeth` teeth:
// shaft orders 0..shaft_orders, the mesh harmonics h * teeth (h >= 1, up to
// the Nyquist order P/2) and their sidebands h * teeth +- 1..sidebands.
struct OrderSets {
  std::size_t teeth = 0;
  std::size_t shaft_orders = 1;
  std::size_t sidebands = 1;
};

// Throws InputError naming `teeth` (>= 3, with 2 (teeth + sidebands) < P,
// so that the first mesh order and its sidebands lie below the Nyquist
// order), `sidebands` (< teeth / 2, so that the sidebands of neighbouring
// harmonics stay apart), `shaft orders` (< teeth - sidebands, below the first
// lower sideband) and `samples per revolution` (16 to 2^24).
void check_order_sets(const OrderSets& sets, std::size_t samples_per_revolution);

struct TsaParts {
  std::vector<double> tsa;
  // Regular: shaft orders, mesh harmonics and their sidebands (Lebold et al.
  // 2000's regular meshing components, with 1..m sidebands).
  std::vector<double> regular;
  // Residual: the TSA without the shaft orders and the mesh harmonics.
  std::vector<double> residual;
  // Difference: the TSA without the regular signal (the residual without
  // the sidebands).
  std::vector<double> difference;
  // Band about the first mesh harmonic, teeth - sidebands .. teeth + sidebands,
  // and its envelope (the modulus of its analytic signal), for NB4.
  std::vector<double> mesh_band;
  std::vector<double> mesh_band_envelope;
  // Amplitude of each order 0..P/2 of the TSA (order 0: its mean).
  std::vector<double> order_amplitude;
};

// Splits a TSA of P samples (one revolution) by zeroing orders of its DFT.
TsaParts tsa_parts(const std::vector<double>& tsa, const OrderSets& sets);

// Order tracking of a record sampled at irregular instants with its shaft's
// angle: the record resampled on the angle at `grid` steps a revolution, the
// smallest samples_per_revolution times a power of two at or above the
// record's rows a revolution (so that the interpolation does not alias), up
// to 2^23; its order spectrum; its TSA reduced to samples_per_revolution
// (decimate_periodic); and with `sets` the TSA's parts.
struct OrderAnalysis {
  std::size_t grid = 0;
  std::size_t revolutions = 0;
  double start_angle = 0.0;
  Spectrum orders;
  std::vector<double> tsa;
  std::optional<TsaParts> parts;
};

// Throws InputError as resample_on_angle, check_samples_per_revolution and
// check_order_sets do.
OrderAnalysis analyse_orders(const std::vector<double>& angle, const std::vector<double>& signal,
                             std::size_t samples_per_revolution, Window window,
                             const std::optional<OrderSets>& sets, const char* angle_name = "angle",
                             const char* signal_name = "signal");

}  // namespace gearimpact::signals
