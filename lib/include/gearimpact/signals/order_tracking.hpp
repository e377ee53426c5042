// Computed order tracking from a tacho (docs/signals.md, "Order tracking from
// a tacho"): the shaft's angle estimated from the times of its pulses, which
// the order analysis (resample_on_angle, analyse_orders) then takes in place
// of a simulated angle. The pulses may carry jitter (tacho_jitter).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gearimpact::signals {

// The angle at each time t[j] from the pulse times t_k, pulse k at the angle
// 2 pi k / pulses_per_revolution (so 0 at the first pulse): on [t_k, t_k+1]
// the quadratic through the pulses k-1, k, k+1 (constant angular
// acceleration; on the first interval through 0, 1, 2). It is exact for a
// speed that changes linearly in time. Throws InputError naming `name` unless
// there are at least 3 pulse times, finite and strictly increasing, naming
// "pulses per revolution" unless it is 1 to 2^20, and naming "time" unless
// every t lies in [t_0, t_last].
std::vector<double> angle_from_pulses(const std::vector<double>& pulse_times,
                                      std::size_t pulses_per_revolution,
                                      const std::vector<double>& t, const char* name = "tacho");

// Pulse times moved by a seeded Gaussian jitter of standard deviation sigma:
// t_k + sigma z_k, z_k from std::mt19937_64 seeded with a SplitMix64 hash of
// `seed`, by Box-Muller on its top 53 bits (the library's distributions are
// implementation-defined; this is the same on every platform's libstdc++ and
// libc++ up to libm). sigma = 0 returns the times unchanged.
std::vector<double> tacho_jitter(const std::vector<double>& pulse_times, double sigma_s,
                                 std::uint64_t seed);

}  // namespace gearimpact::signals
