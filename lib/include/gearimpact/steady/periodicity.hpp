// Is a run steady, and with which period? Judged from its Poincare samples: one state vector
// per excitation period, taken at the same excitation phase, oldest first.
//
// Tolerance semantics. Two samples a and b are the same point when
//   max_i |a_i - b_i| / scale_i <= tolerance,
// each component measured in its own scale (the backlash B for a displacement, B w_n for a
// speed, ...), so the tolerance is a fraction of those scales. The record is periodic with period
// p when every sample of the last `window` equals, in that sense, the sample p periods before
// it. The period reported is the smallest such p in 1..max_period: the minimal period, since
// every multiple of a period passes too. Consequences to keep in mind:
// - orbit points closer than the tolerance are one point: a period-2 orbit whose two samples
//   differ by less than tolerance * scale is reported as period 1;
// - the test bounds the drift of the samples, not their distance to the limit orbit: a sequence
//   that contracts by a factor rho per period and moves by at most tolerance in the window can
//   still be up to tolerance * rho / (1 - rho) away from its limit.
// Periods 1, 2, 4, 8 are the period-doubling cascade; 3, 5, 6 and 7 are tested too because
// subharmonic orbits of those periods occur in impact oscillators, and calling them aperiodic
// would be wrong.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <string>
#include <vector>

namespace gearimpact {

struct PeriodicitySettings {
  double tolerance = 1e-6;
  // Samples that must repeat; at least 2 max_period so that the longest period tested repeats
  // at least twice inside it.
  std::size_t window = 32;
  // Samples over which a still-decreasing residual is looked for (clipped to the record).
  std::size_t trend_window = 128;
  int max_period = 8;
};

enum class PeriodicityVerdict {
  // Steady with the period reported.
  periodic,
  // No period up to max_period repeats, and no residual still shrinks or grows: chaotic or
  // quasi-periodic, or periodic with a longer period.
  aperiodic,
  // Still settling (some candidate period's residual decreases steadily over the trend window),
  // still leaving an unstable orbit (a residual that grows steadily), or the record is shorter
  // than window + max_period: run more periods. At the caller's
  // limit on periods this is the final answer: not converged within that limit.
  not_converged
};

struct PeriodicityResult {
  PeriodicityVerdict verdict = PeriodicityVerdict::not_converged;
  // The minimal period when periodic, else 0.
  int period = 0;
  // The period when periodic; when still settling, the smallest candidate whose residual
  // decreases; when aperiodic, the smallest candidate whose residual is within a factor 2 of the
  // smallest (multiples of a period repeat about as well as the period itself); 0 when the
  // record is too short.
  int closest_period = 0;
  // Its residual: the largest scaled distance over the window between a sample and the one
  // closest_period before it (+infinity when the record is too short).
  double residual = 0.0;
  // For not_converged with a residual that still changes: the fitted factor by which it changes
  // per period (< 1 shrinking, > 1 growing away from an unstable orbit), else 0.
  double contraction_per_period = 0.0;
  // The last `window` samples (all of them when the record is shorter): for periodic records
  // the steady orbit repeated, for aperiodic ones the points of a bifurcation diagram.
  std::vector<Eigen::VectorXd> window_samples;
  // The verdict in words, with the figures it rests on.
  std::string explanation;
};

// Decides as described above. A residual counts as still decreasing when the least-squares line
// through log(residual) over the trend window falls by at least 10 % over that window and its
// slope is below -5 standard errors, as still growing when it rises by at least 10 % (1/0.9) with
// a slope above 5 standard errors; a stationary residual (chaos, a torus) has neither trend.
// Throws InputError for settings out of range (tolerance finite and > 0, max_period >= 1,
// window >= 2 max_period, trend_window >= window), a scale that is not finite and > 0, or a
// sample of another dimension or with a non-finite component.
PeriodicityResult classify_poincare_samples(const std::vector<Eigen::VectorXd>& samples,
                                            const Eigen::VectorXd& scale,
                                            const PeriodicitySettings& settings = {});

}  // namespace gearimpact
