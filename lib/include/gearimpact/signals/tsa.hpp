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
  // NB4's band h* teeth +- nb4_half_width orders. 0: the default, floor((teeth - 1) / 2), the
  // whole band between neighbouring harmonics. A half-width of 1 is refused: over z +- 1 the
  // envelope is |A_0| plus one once-a-revolution sinusoid to first order in the sideband
  // ratio, whose kurtosis is 1.5 whatever the fault (docs/signals.md, "NB4's band").
  std::size_t nb4_half_width = 0;
};

// NB4's half-width: sets.nb4_half_width, or floor((teeth - 1) / 2) for 0.
std::size_t nb4_half_width(const OrderSets& sets);

// The highest order a record's band holds, q_max = floor(band_hz / shaft_hz) with shaft_hz the
// fastest revolution's mean speed (orders above are images and folded lines, not the machine).
// The default band is 0.4 of the sample rate, so for a uniformly sampled record q_max =
// floor(0.4 x the fewest samples any whole revolution holds): kBandFraction.
inline constexpr double kBandFraction = 0.4;

// The grid the indicators are computed on: the smallest power of two >= 8 q_max + 1, on which
// the normalised moments up to the 8th of a TSA of orders <= q_max are exact (its n-th power has
// orders <= n q_max), whatever grid the TSA is written on.
std::size_t indicator_grid(std::size_t max_order);

// One period of Q samples as p samples of the same period (p below or above Q), keeping its
// orders k <= max_order that lie strictly below both Nyquist orders (2k < p, 2k < Q): the
// band-limited interpolation or decimation of a periodic record. Throws InputError unless
// p >= 4 and Q >= 4.
std::vector<double> band_limited_period(const std::vector<double>& period, std::size_t p,
                                        std::size_t max_order);

// Throws InputError naming `teeth` (>= 3, with 2 (teeth + sidebands) < P,
// so that the first mesh order and its sidebands lie below the Nyquist
// order), `sidebands` (< teeth / 2, so that the sidebands of neighbouring
// harmonics stay apart), `shaft orders` (< teeth - sidebands, below the first
// lower sideband) and `samples per revolution` (16 to 2^24).
// Also `nb4 half width` (2 to floor((teeth - 1) / 2), or 0 for the default).
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
  // NB4's band, h* teeth +- w (w = nb4_half_width(sets)), about the strongest mesh harmonic h*
  // whose band lies below max_order and the Nyquist order, and its envelope (the modulus of its
  // analytic signal). Zero (and NB4 absent) when no harmonic's band fits.
  std::vector<double> mesh_band;
  std::vector<double> mesh_band_envelope;
  std::size_t nb4_harmonic = 0;  // h*, 0 when no band fits
  std::size_t nb4_half_width = 0;
  // Amplitude of each order 0..P/2 of the TSA (order 0: its mean).
  std::vector<double> order_amplitude;
};

// Splits a TSA of P samples (one revolution) by zeroing orders of its DFT; orders above
// max_order (default: every order below P/2) are zeroed in every part.
TsaParts tsa_parts(const std::vector<double>& tsa, const OrderSets& sets,
                   std::size_t max_order = static_cast<std::size_t>(-1));

// Order tracking of a record sampled at irregular instants with its shaft's
// angle: the record resampled on the angle at `grid` steps a revolution, the
// record's own rows a revolution rounded (16 to 2^23), whatever
// samples_per_revolution; its order spectrum; its TSA on samples_per_revolution
// samples (band_limited_period); and with `sets` the TSA's parts.
//
// The TSA keeps the orders the record's band holds, k <= max_order (the
// argument, or kBandFraction of the fewest samples a whole revolution of the
// record holds); those above are zeroed, in `tsa` and in every part.
// samples_per_revolution 0 takes indicator_grid(max_order) for the TSA too.
// `indicator_parts` are the parts of the same TSA on indicator_grid(max_order)
// samples, on which the indicators are computed: they do not depend on
// samples_per_revolution.
struct OrderAnalysis {
  std::size_t grid = 0;
  std::size_t revolutions = 0;
  double start_angle = 0.0;
  std::size_t samples_per_revolution = 0;  // of `tsa`
  std::size_t max_order = 0;
  Spectrum orders;
  std::vector<double> tsa;
  std::optional<TsaParts> parts;
  std::size_t indicator_grid = 0;
  std::optional<TsaParts> indicator_parts;
};

// Throws InputError as resample_on_angle, check_samples_per_revolution and
// check_order_sets do, and naming "band" when max_order is below the first
// mesh harmonic's upper sideband (the band does not hold the gear's mesh).
OrderAnalysis analyse_orders(const std::vector<double>& angle, const std::vector<double>& signal,
                             std::size_t samples_per_revolution, Window window,
                             const std::optional<OrderSets>& sets, const char* angle_name = "angle",
                             const char* signal_name = "signal",
                             std::optional<std::size_t> max_order = std::nullopt);

// kBandFraction of the fewest samples any whole revolution of `angle` holds (from its first
// multiple of 2 pi, as resample_on_angle counts revolutions), floored; 0 without a whole one.
std::size_t band_max_order(const std::vector<double>& angle);

}  // namespace gearimpact::signals
