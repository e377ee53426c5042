#include "gearimpact/steady/steady_state.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/steady/closed_forms.hpp"

namespace gearimpact {

namespace {

// What one excitation period of the output grid shows.
struct PeriodStats {
  double s_min = std::numeric_limits<double>::infinity();
  double s_max = -std::numeric_limits<double>::infinity();
  double s_sum = 0.0;
  double s_square_sum = 0.0;
  double w1_sum = 0.0;
  double w2_sum = 0.0;
  long long rows = 0;
  double force_max = 0.0;
  int impacts_n1 = 0;
  int impacts_n2 = 0;
  bool in_contact_n1 = true;  // at every row
  bool in_contact_n2 = true;
  bool ever_in_contact = false;
};

// The extremes of the cubic Hermite interpolant of s on [0, h] with values s0, s1 and slopes v0,
// v1: where its derivative, a quadratic in u = t / h, vanishes inside (0, 1).
void hermite_extremes(double h, double s0, double v0, double s1, double v1, PeriodStats& p) {
  const double a = 6.0 * s0 + 3.0 * h * v0 - 6.0 * s1 + 3.0 * h * v1;
  const double b = -6.0 * s0 - 4.0 * h * v0 + 6.0 * s1 - 2.0 * h * v1;
  const double c = h * v0;
  const auto value = [&](double u) {
    const double u2 = u * u;
    const double u3 = u2 * u;
    return (2.0 * u3 - 3.0 * u2 + 1.0) * s0 + (u3 - 2.0 * u2 + u) * h * v0 +
           (-2.0 * u3 + 3.0 * u2) * s1 + (u3 - u2) * h * v1;
  };
  const auto consider = [&](double u) {
    if (u > 0.0 && u < 1.0) {
      const double s = value(u);
      p.s_min = std::min(p.s_min, s);
      p.s_max = std::max(p.s_max, s);
    }
  };
  if (std::fabs(a) <= 1e-14 * (std::fabs(b) + std::fabs(c))) {
    if (b != 0.0) consider(-c / b);
    return;
  }
  const double discriminant = b * b - 4.0 * a * c;
  if (discriminant < 0.0) return;
  // The root formula without cancellation.
  const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
  consider(q / a);
  if (q != 0.0) consider(c / q);
}

// The output grid of one excitation period, observed row by row.
class PeriodRecorder {
 public:
  PeriodRecorder(double rb1, double rb2) : rb1_(rb1), rb2_(rb2) {}

  // A new period starts at t_s (its first row, the previous period's last, is not counted).
  void start(double t_s) {
    stats_ = PeriodStats{};
    start_s_ = t_s;
    have_previous_ = false;
  }

  void observe(const SeriesRow& row) {
    observe(row, rb1_ * row.w1_rad_per_s - rb2_ * row.w2_rad_per_s);
  }

  // A row whose s_m moves at `rate`: the planar model's s_d adds the centres' motion along the
  // drive line to the gears' turning.
  void observe(const SeriesRow& row, double rate) {
    if (have_previous_ && row.t_s > start_s_) {
      hermite_extremes(row.t_s - previous_.t_s, previous_.s_m, previous_rate_, row.s_m, rate,
                       stats_);
      stats_.s_min = std::min(stats_.s_min, row.s_m);
      stats_.s_max = std::max(stats_.s_max, row.s_m);
      stats_.s_sum += row.s_m;
      stats_.s_square_sum += row.s_m * row.s_m;
      stats_.w1_sum += row.w1_rad_per_s;
      stats_.w2_sum += row.w2_rad_per_s;
      ++stats_.rows;
      stats_.force_max = std::max(stats_.force_max, row.normal_force_n);
      const bool n1 = row.region == static_cast<int>(Region::n1);
      const bool n2 = row.region == static_cast<int>(Region::n2);
      stats_.in_contact_n1 = stats_.in_contact_n1 && n1;
      stats_.in_contact_n2 = stats_.in_contact_n2 && n2;
      stats_.ever_in_contact = stats_.ever_in_contact || n1 || n2;
    }
    previous_ = row;
    previous_rate_ = rate;
    have_previous_ = true;
  }

  PeriodStats finish(const SimulationSummary& summary) {
    stats_.impacts_n1 = summary.impacts_n1;
    stats_.impacts_n2 = summary.impacts_n2;
    return stats_;
  }

 private:
  double rb1_;
  double rb2_;
  PeriodStats stats_;
  double start_s_ = 0.0;
  SeriesRow previous_{};
  double previous_rate_ = 0.0;
  bool have_previous_ = false;
};

// When the Poincare samples say the run is steady.
class SteadyDecision {
 public:
  explicit SteadyDecision(const SteadySettings& settings)
      : settings_(settings),
        least_for_aperiodic_(settings.trend_window +
                             static_cast<std::size_t>(settings.max_period)) {
    periodicity_.tolerance = settings.tolerance;
    periodicity_.max_period = settings.max_period;
    periodicity_.window = settings.window;
    periodicity_.trend_window = settings.trend_window;
  }

  // After each new sample: true when the verdict is final.
  bool settled(const std::vector<Eigen::VectorXd>& samples, const Eigen::VectorXd& scale) {
    if (samples.size() < settings_.window + static_cast<std::size_t>(settings_.max_period)) {
      return false;
    }
    verdict_ = classify_poincare_samples(samples, scale, periodicity_);
    if (verdict_.verdict == PeriodicityVerdict::aperiodic) {
      candidate_period_ = 0;
      return samples.size() >= least_for_aperiodic_;
    }
    if (verdict_.verdict != PeriodicityVerdict::periodic) {
      candidate_period_ = 0;
      return false;
    }
    // A transient whose slowest mode turns by about pi a period (the natural frequency near
    // half the excitation's) alternates: samples two periods apart agree before those one
    // apart do. A period above 1 is accepted only after it has held for another window.
    if (verdict_.period == 1) return true;
    if (verdict_.period != candidate_period_) {
      candidate_period_ = verdict_.period;
      confirmed_at_ = samples.size() + settings_.window;
      return false;
    }
    return samples.size() >= confirmed_at_;
  }

  // The verdict at the end: aperiodic before enough samples is not converged.
  PeriodicityResult final_verdict(std::size_t samples) const {
    PeriodicityResult v = verdict_;
    if (v.verdict == PeriodicityVerdict::aperiodic && samples < least_for_aperiodic_) {
      v.verdict = PeriodicityVerdict::not_converged;
    }
    return v;
  }

 private:
  const SteadySettings& settings_;
  std::size_t least_for_aperiodic_;
  PeriodicitySettings periodicity_;
  PeriodicityResult verdict_;
  int candidate_period_ = 0;
  std::size_t confirmed_at_ = 0;
};

// The figures of the steady window (the last `periods` of history) and its regime.
void summarize_window(const std::deque<PeriodStats>& history, std::size_t periods,
                      const SimulationCase& c, double rb1, SteadyPoint& point) {
  // A driver's mean torque is not known before the run; its loose gear is
  // held on the drive flank (N1) by the drag.
  const double mean_torque1_n_m = c.torque1.kind == Torque::Kind::prescribed_speed
                                      ? 0.0
                                      : mean_torque_n_m(c.torque1, "torque1");
  PeriodStats w;
  for (std::size_t i = history.size() - periods; i < history.size(); ++i) {
    const PeriodStats& p = history[i];
    w.s_min = std::min(w.s_min, p.s_min);
    w.s_max = std::max(w.s_max, p.s_max);
    w.s_sum += p.s_sum;
    w.s_square_sum += p.s_square_sum;
    w.w1_sum += p.w1_sum;
    w.w2_sum += p.w2_sum;
    w.rows += p.rows;
    w.force_max = std::max(w.force_max, p.force_max);
    w.impacts_n1 += p.impacts_n1;
    w.impacts_n2 += p.impacts_n2;
    w.in_contact_n1 = w.in_contact_n1 && p.in_contact_n1;
    w.in_contact_n2 = w.in_contact_n2 && p.in_contact_n2;
    w.ever_in_contact = w.ever_in_contact || p.ever_in_contact;
  }
  const double rows = static_cast<double>(w.rows);
  const double mean = w.s_sum / rows;
  point.dte_mean_m = mean;
  point.dte_amplitude_m = 0.5 * (w.s_max - w.s_min);
  point.dte_rms_m = std::sqrt(std::max(0.0, w.s_square_sum / rows - mean * mean));
  point.s_min_m = w.s_min;
  point.s_max_m = w.s_max;
  const double backlash = c.gears.backlash_m;
  // The loaded flank, as the regime below reads it.
  const bool drive_loaded = mean_torque1_n_m >= 0.0;
  if (drive_loaded) {
    point.dte_contact_mean_m = mean - backlash;
    point.dte_contact_min_m = w.s_min - backlash;
    point.dte_contact_max_m = w.s_max - backlash;
  } else {
    point.dte_contact_mean_m = -mean - backlash;
    point.dte_contact_min_m = -w.s_max - backlash;
    point.dte_contact_max_m = -w.s_min - backlash;
  }
  point.w1_mean_rad_s = w.w1_sum / rows;
  point.w2_mean_rad_s = w.w2_sum / rows;
  point.pinion_rpm = *point.w1_mean_rad_s * 60.0 / (2.0 * pi);
  point.mesh_frequency_hz = c.gears.teeth1 * std::fabs(*point.w1_mean_rad_s) / (2.0 * pi);
  if (mean_torque1_n_m != 0.0) {
    point.dynamic_factor = w.force_max / std::fabs(mean_torque1_n_m / rb1);
  }
  point.impacts_drive_per_period = w.impacts_n1 / static_cast<double>(periods);
  point.impacts_coast_per_period = w.impacts_n2 / static_cast<double>(periods);
  const int loaded_impacts = drive_loaded ? w.impacts_n1 : w.impacts_n2;
  const int other_impacts = drive_loaded ? w.impacts_n2 : w.impacts_n1;
  const bool held = drive_loaded ? w.in_contact_n1 : w.in_contact_n2;
  if (other_impacts > 0) {
    point.regime = Regime::double_sided;
  } else if (loaded_impacts > 0) {
    point.regime = Regime::single_sided;
  } else if (held) {
    point.regime = Regime::no_impact;
  } else {
    point.regime = Regime::no_contact;
  }
}

// The name of the mesh period as a Poincare period's kind.
constexpr const char* kMeshPeriodKind = "mesh";

// After how many mesh periods the teeth repeat (docs/faults.md, "True period"), and its name.
struct ToothPattern {
  long long mesh_periods;
  const char* kind;
};

ToothPattern tooth_pattern(const SimulationCase& c) {
  // Faulted teeth, and tooth errors that differ from tooth to tooth, alike.
  DistinctTeeth distinct = distinct_teeth(c.modifications);
  for (const ToothFault& f : c.faults)
    (f.gear == Gear::one ? distinct.pinion : distinct.wheel) = true;
  const long long n = true_period_mesh_periods(c.gears, distinct);
  if (distinct.pinion && distinct.wheel) return {n, "hunting"};
  if (distinct.pinion) return {n, "pinion-revolution"};
  if (distinct.wheel) return {n, "wheel-revolution"};
  return {n, kMeshPeriodKind};
}

// The keys of forcing_frequencies' entries, in its order.
std::vector<std::string> forcing_keys(const SimulationCase& c) {
  std::vector<std::string> keys;
  for (const auto& [t, name] : {std::pair<const Torque*, std::string>{&c.torque1, "torque1"},
                                std::pair<const Torque*, std::string>{&c.torque2, "torque2"}}) {
    if (t->kind == Torque::Kind::sinusoidal && t->amplitude_n_m != 0.0 &&
        t->angular_frequency_rad_per_s != 0.0) {
      keys.push_back(name + ".angular_frequency");
    }
    if (t->kind == Torque::Kind::harmonic) {
      for (std::size_t i = 0; i < t->harmonic_amplitudes_n_m.size(); ++i) {
        if (t->harmonic_amplitudes_n_m[i] != 0.0 &&
            t->harmonic_angular_frequencies_rad_per_s[i] != 0.0) {
          keys.push_back(name + ".angular_frequencies[" + std::to_string(i) + "]");
        }
      }
    }
  }
  return keys;
}

// Whether the planar model runs the case with its motor and load behind shafts.
bool planar_shafts(const SimulationCase& c) {
  return c.bearings.kind == BearingKind::elastic && c.shafts.kind == ShaftKind::elastic;
}

// The mean pinion speed of the rolling pair (Rb1 w1 = Rb2 w2 on average over a periodic s).
// The momentum P = J1 w1/Rb1 + J2 w2/Rb2 obeys P' = T1/Rb1 + T2/Rb2, the mesh forces
// cancelling. Without fluctuation it is constant. A fluctuation A sin(w t + phi) adds
// A (cos(phi) - cos(w t + phi)) / w, whose mean over its period is A cos(phi) / w: with
// `with_forcing` the mean of P, which sets the speed at which the teeth pass, includes it.
double rolling_mean_pinion_speed(const SimulationCase& c, bool with_forcing) {
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  double j1 = moment_of_inertia(g, Gear::one);
  double j2 = moment_of_inertia(g, Gear::two);
  if (planar_shafts(c)) {
    // The motor and the load turn with their gears on average (they start with them,
    // planar_initial_state) and carry the torques: their inertias join the gears'.
    j1 += c.shafts.motor_inertia_kg_m2;
    j2 += c.shafts.load_inertia_kg_m2;
  }
  double momentum = j1 * c.initial.w1_rad_per_s / rb1 + j2 * c.initial.w2_rad_per_s / rb2;
  if (with_forcing) {
    for (const auto& [t, rb] : {std::pair<const Torque*, double>{&c.torque1, rb1},
                                std::pair<const Torque*, double>{&c.torque2, rb2}}) {
      if (t->kind == Torque::Kind::sinusoidal && t->angular_frequency_rad_per_s != 0.0) {
        momentum += t->amplitude_n_m * std::cos(t->phase_rad) / t->angular_frequency_rad_per_s / rb;
      }
      if (t->kind == Torque::Kind::harmonic) {
        for (std::size_t i = 0; i < t->harmonic_amplitudes_n_m.size(); ++i) {
          const double wi = t->harmonic_angular_frequencies_rad_per_s[i];
          if (wi != 0.0) {
            momentum +=
                t->harmonic_amplitudes_n_m[i] * std::cos(t->harmonic_phases_rad[i]) / wi / rb;
          }
        }
      }
    }
  }
  return momentum / (j1 / rb1 + j2 * rb1 / (rb2 * rb2));
}

// q tooth patterns of P s that are p forcing periods of T s (q P = p T to 1e-9 relative, the
// 10 significant digits a frequency is typed with), q the least up to
// kMostToothPatternsPerPoincarePeriod; p = 0 when none is.
struct Commensurate {
  long long tooth_patterns = 0;
  long long forcing_periods = 0;
};

Commensurate common_period(double pattern_s, double forcing_s) {
  const double ratio = pattern_s / forcing_s;
  for (long long q = 1; q <= kMostToothPatternsPerPoincarePeriod; ++q) {
    const double periods = ratio * static_cast<double>(q);
    const double whole = std::round(periods);
    if (whole >= 1.0 && std::fabs(periods - whole) <= 1e-9 * periods) {
      return {q, static_cast<long long>(whole)};
    }
  }
  return {};
}
}  // namespace

std::vector<double> forcing_frequencies(const SimulationCase& c) {
  std::vector<double> w;
  for (const Torque* t : {&c.torque1, &c.torque2}) {
    if (t->kind == Torque::Kind::sinusoidal && t->amplitude_n_m != 0.0 &&
        t->angular_frequency_rad_per_s != 0.0) {
      w.push_back(std::fabs(t->angular_frequency_rad_per_s));
    }
    if (t->kind == Torque::Kind::harmonic) {
      for (std::size_t i = 0; i < t->harmonic_amplitudes_n_m.size(); ++i) {
        if (t->harmonic_amplitudes_n_m[i] != 0.0 &&
            t->harmonic_angular_frequencies_rad_per_s[i] != 0.0) {
          w.push_back(std::fabs(t->harmonic_angular_frequencies_rad_per_s[i]));
        }
      }
    }
  }
  return w;
}

std::string period_label(const SteadyPoint& point) {
  switch (point.verdict) {
    case PeriodicityVerdict::periodic:
      return std::to_string(point.period);
    case PeriodicityVerdict::aperiodic:
      return "aperiodic";
    case PeriodicityVerdict::not_converged:
      break;
  }
  return "";
}

std::string to_string(Regime regime) {
  switch (regime) {
    case Regime::no_impact:
      return "NI";
    case Regime::single_sided:
      return "SS";
    case Regime::double_sided:
      return "DS";
    case Regime::no_contact:
      return "NC";
  }
  return "?";
}

void require_steady_case(const SimulationCase& c) {
  // A kinematic driver holds the mean speed whatever the load, the drag and
  // friction draw from it: nothing need balance.
  if (c.torque1.kind == Torque::Kind::prescribed_speed) return;
  // Every refusal at once, each with the value that cures it.
  Problems problems;
  double t1 = 0.0;
  double t2 = 0.0;
  const bool known = problems.collect([&] {
    t1 = mean_torque_n_m(c.torque1, "torque1");
    t2 = mean_torque_n_m(c.torque2, "torque2");
  });
  if (known) {
    try {
      require_balanced_mean_torques(t1, t2, base_radius(c.gears, Gear::one),
                                    base_radius(c.gears, Gear::two));
    } catch (const InputError& e) {
      // The key of each mean torque; gear 2's (the load) is the one to set.
      const auto key = [](const Torque& t, const char* name) {
        return std::string(name) + (t.kind == Torque::Kind::constant ? ".value" : ".mean");
      };
      const std::string key1 = key(c.torque1, "torque1");
      const std::string key2 = key(c.torque2, "torque2");
      // T1/Rb1 + T2/Rb2 = 0.
      const double balancing =
          -t1 * base_radius(c.gears, Gear::two) / base_radius(c.gears, Gear::one);
      const std::string value = format_number(balancing) + " N*m";
      problems.add(
          range_problem(key2, format_number(t2) + " N*m",
                        "mean torques with T1/Rb1 + T2/Rb2 = 0 for a steady state, here " +
                            e.value() + " with " + key1 + " = " + format_number(t1) +
                            " N*m (an unbalanced mean torque accelerates the pair without bound)",
                        key2 + " = \"" + value + "\" balances it (in the case file, or --set '" +
                            key2 + "=" + value + "')"));
    }
  }
  if (c.model.friction_coefficient != 0.0) {
    problems.add(range_problem(
        "model.friction_coefficient", format_number(c.model.friction_coefficient),
        "0 for a steady state: friction loss f N |Vs| is drawn from the mean rotation, which "
        "balanced mean torques do not feed, so the pair slows down without end",
        "model.friction_coefficient = 0 (in the case file, or --set "
        "model.friction_coefficient=0)"));
  }
  // Any law other than the constant one has friction whatever friction_coefficient says.
  if (c.model.friction_law != FrictionLaw::constant) {
    problems.add(range_problem(
        "model.friction_law", std::string(name_of(kFrictionLaws, c.model.friction_law)),
        "\"constant\" (with friction_coefficient = 0) for a steady state: friction loss is "
        "drawn from the mean rotation, which balanced mean torques do not feed",
        "model.friction_law = \"constant\" and model.friction_coefficient = 0 (--set "
        "model.friction_law=constant --set model.friction_coefficient=0)"));
  }
  problems.throw_if_any();
}

SimulationCase steady_dynamics_case(const SimulationCase& c) {
  refuse_helical_run(c);
  return dynamics_case(c);
}

SteadyTiming steady_timing(const SimulationCase& c, const StiffnessTable& table,
                           const SteadySettings& settings) {
  if (c.gears.helix_angle_rad != 0.0)
    return steady_timing(steady_dynamics_case(c), table, settings);
  require_steady_case(c);
  if (!(settings.steps_per_contact_period >= kStepsPerContactPeriod) ||
      !std::isfinite(settings.steps_per_contact_period)) {
    throw InputError("steps_per_contact_period", settings.steps_per_contact_period,
                     "a finite value >= " + format_number(kStepsPerContactPeriod));
  }
  SteadyTiming timing;
  // z |w| of the faster gear at the start (and of the mean speed below): the
  // step resolves its mesh period as simulate() requires (validate_implied).
  double fastest_mesh = std::max(c.gears.teeth1 * std::fabs(c.initial.w1_rad_per_s),
                                 c.gears.teeth2 * std::fabs(c.initial.w2_rad_per_s));
  const std::vector<double> w = forcing_frequencies(c);
  const bool time_varying = c.model.mesh_stiffness == MeshStiffnessMode::time_varying;
  // Faults need a time-varying stiffness (validation refuses them on a constant one).
  const ToothPattern pattern = time_varying ? tooth_pattern(c) : ToothPattern{1, kMeshPeriodKind};
  const bool faulted = pattern.mesh_periods > 1;
  if (c.torque1.kind == Torque::Kind::prescribed_speed) {
    // The driver's period: its orders are harmonics of W, and a time-varying
    // mesh stiffness repeats with the mesh, z1 W; the motion repeats at W
    // times their greatest common divisor, so the orders must be whole.
    const Torque& d = c.torque1;
    long long divisor = time_varying ? c.gears.teeth1 : 0;
    long long orders_divisor = 0;
    double fastest = d.mean_speed_rad_per_s;
    for (std::size_t i = 0; i < d.driver_orders.size(); ++i) {
      const double order = d.driver_orders[i];
      if (order != std::round(order)) {
        throw InputError("torque1.orders[" + std::to_string(i) + "]", format_number(order),
                         "a whole number for a steady state, so that the driver has one period");
      }
      divisor = std::gcd(divisor, static_cast<long long>(order));
      orders_divisor = std::gcd(orders_divisor, static_cast<long long>(order));
      fastest += std::fabs(d.driver_speed_amplitudes_rad_per_s[i]);
    }
    if (divisor == 0) divisor = 1;
    if (faulted) {
      // In pinion revolutions the teeth repeat after a / b = N / z1 (lowest terms) and the
      // driver after 1 / g, g the orders' divisor: their least common multiple is
      // lcm(a, 1) / gcd(b, g) = a / gcd(b, g) (with g = 0, no orders, gcd(b, 0) = b).
      const long long z1 = c.gears.teeth1;
      const long long common = std::gcd(pattern.mesh_periods, z1);
      const long long a = pattern.mesh_periods / common;
      const long long b = z1 / common;
      const long long denominator = std::gcd(b, orders_divisor);
      timing.excitation_period_s = 2.0 * pi * static_cast<double>(a) /
                                   (d.mean_speed_rad_per_s * static_cast<double>(denominator));
      timing.mesh_periods = z1 * a / denominator;
    } else {
      timing.excitation_period_s =
          2.0 * pi / (d.mean_speed_rad_per_s * static_cast<double>(divisor));
      if (time_varying) timing.mesh_periods = c.gears.teeth1 / divisor;
    }
    timing.kind = time_varying ? std::string(pattern.kind) : std::string();
    if (!d.driver_orders.empty() || !time_varying) {
      timing.kind += std::string(timing.kind.empty() ? "" : "+") + "driver";
    }
    fastest_mesh = std::max(fastest_mesh, c.gears.teeth1 * fastest);
  } else if (!w.empty()) {
    const double fundamental = *std::min_element(w.begin(), w.end());
    for (double wi : w) {
      const double ratio = wi / fundamental;
      // Frequencies typed with 10 significant digits.
      if (std::fabs(ratio - std::round(ratio)) > 1e-9 * ratio) {
        throw InputError("torque angular_frequency", format_number(wi) + " rad/s",
                         "a whole multiple of the lowest, " + format_number(fundamental) +
                             " rad/s, so that the forcing has one period");
      }
    }
    timing.excitation_period_s = 2.0 * pi / fundamental;
    timing.kind = "forcing";
    if (faulted) {
      const double w1_mean = std::fabs(rolling_mean_pinion_speed(c, true));
      if (!std::isfinite(w1_mean) || w1_mean == 0.0) {
        throw InputError("initial.w1", c.initial.w1_rad_per_s,
                         "a mean pinion speed != 0: the faulted teeth repeat every " +
                             std::to_string(pattern.mesh_periods) + " mesh periods 2 pi / (z1 w1)");
      }
      const double pattern_s =
          2.0 * pi * static_cast<double>(pattern.mesh_periods) / (c.gears.teeth1 * w1_mean);
      const Commensurate common = common_period(pattern_s, timing.excitation_period_s);
      if (common.forcing_periods == 0) {
        const std::string forcing_key = forcing_keys(
            c)[static_cast<std::size_t>(std::min_element(w.begin(), w.end()) - w.begin())];
        throw InputError(
            forcing_key + ", initial.w1",
            format_number(fundamental) + " rad/s against " + pattern.kind + " " +
                format_number(pattern_s) + " s (mean pinion speed " + format_number(w1_mean) +
                " rad/s)",
            "a forcing commensurate with the faulted teeth: its period T = 2 pi / w and the "
            "teeth's period P (" +
                std::to_string(pattern.mesh_periods) +
                " mesh periods at the mean speed) with q P = p T for whole p and q <= " +
                std::to_string(kMostToothPatternsPerPoincarePeriod) +
                " to 1e-9, so that the motion has one period; here P / T = " +
                format_number(pattern_s / timing.excitation_period_s));
      }
      timing.excitation_period_s *= static_cast<double>(common.forcing_periods);
      timing.mesh_periods = pattern.mesh_periods * common.tooth_patterns;
      timing.kind = std::string(pattern.kind) + "+forcing";
      fastest_mesh = std::max(fastest_mesh, c.gears.teeth1 * w1_mean);
    }
  } else {
    const GearPair& g = c.gears;
    const double w1_mean = rolling_mean_pinion_speed(c, false);
    if (!std::isfinite(w1_mean) || w1_mean == 0.0) {
      throw InputError("initial.w1", c.initial.w1_rad_per_s,
                       "a mean pinion speed != 0: without torque fluctuations the mesh period "
                       "2 pi / (z1 w1) is the sampling period");
    }
    if (faulted) {
      timing.excitation_period_s =
          2.0 * pi * static_cast<double>(pattern.mesh_periods) / (g.teeth1 * std::fabs(w1_mean));
    } else {
      timing.excitation_period_s = 2.0 * pi / (g.teeth1 * std::fabs(w1_mean));
    }
    timing.mesh_periods = pattern.mesh_periods;
    timing.kind = pattern.kind;
    fastest_mesh = std::max(fastest_mesh, g.teeth1 * std::fabs(w1_mean));
  }
  // The contact period of the stiffest contact: the table's largest Ke sum (step_bound.hpp is
  // 1/20 of it), or the constant mesh stiffness when that is stiffer.
  double contact_period = largest_resolving_step_s(c, table) * kStepsPerContactPeriod;
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    contact_period = std::min(
        contact_period,
        2.0 * pi * std::sqrt(effective_mass_kg(c.gears) / c.model.constant_mesh_stiffness_n_per_m));
  }
  if (c.bearings.kind == BearingKind::elastic) {
    // The planar system's shortest period (its bearings, shafts and both lines of the mesh),
    // which simulate() bounds the step by (check_planar_step).
    contact_period = std::min(
        contact_period, planar_largest_step_s(c, table, planar_mounting(c), IntegratorKind::rk4) *
                            steps_per_contact_period(IntegratorKind::rk4));
  }
  double largest = contact_period / settings.steps_per_contact_period;
  if (fastest_mesh > 0.0) {
    // A hair under the bound, so that the step rounded to a whole number per
    // period below stays within it.
    largest = std::min(largest, 2.0 * pi / (kStepsPerMeshPeriod * fastest_mesh) * (1.0 - 1e-9));
  }
  timing.steps_per_period =
      static_cast<long long>(std::ceil(timing.excitation_period_s / largest * (1.0 - 1e-12)));
  timing.step_s = timing.excitation_period_s / static_cast<double>(timing.steps_per_period);
  return timing;
}

Eigen::Vector2d state_scale(const SimulationCase& c, const StiffnessTable& table) {
  if (c.gears.helix_angle_rad != 0.0) return state_scale(steady_dynamics_case(c), table);
  const GearPair& g = c.gears;
  const double length = std::max(g.backlash_m, kLeastStateScalePerModule * g.module_m);
  return Eigen::Vector2d(length, length * natural_frequency_rad_per_s(c, table));
}

Eigen::VectorXd poincare_scale(const SimulationCase& c, const StiffnessTable& table) {
  const Eigen::Vector2d relative = state_scale(c, table);
  if (c.bearings.kind != BearingKind::elastic) return relative;
  const Eigen::Index n = planar_shafts(c) ? 6 : 4;
  Eigen::VectorXd scale(2 + 2 * n);
  scale.head(2) = relative;
  scale.segment(2, n).setConstant(relative[0]);
  scale.tail(n).setConstant(relative[1]);
  return scale;
}

Eigen::VectorXd poincare_state(const SimulationCase& c, const RunState& state) {
  if (c.gears.helix_angle_rad != 0.0) return poincare_state(steady_dynamics_case(c), state);
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const InitialState& y = state.state;
  const double s = rb1 * y.theta1_rad - rb2 * y.theta2_rad;
  const double s_rate = rb1 * y.w1_rad_per_s - rb2 * y.w2_rad_per_s;
  if (c.bearings.kind != BearingKind::elastic || !state.planar) {
    Eigen::VectorXd v(2);
    v << s, s_rate;
    return v;
  }
  const PlanarState& p = *state.planar;
  const bool shafts = planar_shafts(c);
  const Eigen::Index n = shafts ? 6 : 4;
  Eigen::VectorXd v(2 + 2 * n);
  v.head(2) << s, s_rate;
  v.segment(2, 4) << p.x1_m, p.y1_m, p.x2_m, p.y2_m;
  v.segment(2 + n, 4) << p.vx1_m_s, p.vy1_m_s, p.vx2_m_s, p.vy2_m_s;
  if (shafts) {
    v.segment(6, 2) << rb1 * (p.theta_motor_rad - p.theta1_rad),
        rb2 * (p.theta_load_rad - p.theta2_rad);
    v.tail(2) << rb1 * (p.w_motor_rad_per_s - p.w1_rad_per_s),
        rb2 * (p.w_load_rad_per_s - p.w2_rad_per_s);
  }
  return v;
}

SteadyPoint find_steady_state(const SimulationCase& c, const StiffnessTable& table,
                              const SteadySettings& settings,
                              const std::optional<RunState>& start) {
  if (c.gears.helix_angle_rad != 0.0) {
    return find_steady_state(steady_dynamics_case(c), table, settings, start);
  }
  if (settings.max_periods < 1) {
    throw InputError("max_periods", settings.max_periods, "at least 1");
  }
  SteadyPoint point;
  point.timing = steady_timing(c, table, settings);
  const GearPair& g = c.gears;
  const double rb1 = base_radius(g, Gear::one);
  const double rb2 = base_radius(g, Gear::two);
  const Eigen::VectorXd scale = poincare_scale(c, table);

  SimulationCase period_case = c;
  period_case.integrator.kind = IntegratorKind::rk4;
  period_case.integrator.step_s = point.timing.step_s;
  period_case.integrator.end_time_s = point.timing.excitation_period_s;
  period_case.integrator.output_every = 1;
  PeriodRecorder recorder(rb1, rb2);
  RunControl control;
  control.keep_series = false;
  std::optional<PlanarState> planar_start;
  if (c.bearings.kind == BearingKind::elastic) {
    // The planar rows follow their series rows (each from the same state): s_d's rate adds the
    // centres' relative speed along the drive line's normal (sin a, cos a), a the operating
    // pressure angle (docs/vibration.md, "The planar dynamics").
    const double a = operating_pressure_angle(g);
    const double sin_a = std::sin(a);
    const double cos_a = std::cos(a);
    auto pending = std::make_shared<SeriesRow>();
    control.on_row = [pending](const SeriesRow& row) { *pending = row; };
    control.on_planar_row = [pending, &recorder, rb1, rb2, sin_a, cos_a](const PlanarRow& row) {
      const PlanarState& p = row.state;
      recorder.observe(*pending, rb1 * p.w1_rad_per_s - rb2 * p.w2_rad_per_s +
                                     (p.vx1_m_s - p.vx2_m_s) * sin_a +
                                     (p.vy1_m_s - p.vy2_m_s) * cos_a);
    };
    if (!start || !start->planar) planar_start = planar_initial_state(c);
  } else {
    control.on_row = [&recorder](const SeriesRow& row) { recorder.observe(row); };
  }

  RunState state;
  if (start) {
    state = *start;
  } else {
    state.state = c.initial;
  }
  // A planar point started from a torsional state (or from none) starts its centres at rest
  // on their bearings' unloaded positions, as a planar run does.
  if (planar_start) {
    if (start) {
      planar_start->theta1_rad = planar_start->theta_motor_rad = state.state.theta1_rad;
      planar_start->theta2_rad = planar_start->theta_load_rad = state.state.theta2_rad;
      planar_start->w1_rad_per_s = planar_start->w_motor_rad_per_s = state.state.w1_rad_per_s;
      planar_start->w2_rad_per_s = planar_start->w_load_rad_per_s = state.state.w2_rad_per_s;
    }
    state.planar = planar_start;
  }
  if (c.bearings.kind != BearingKind::elastic) state.planar.reset();
  state.time_s = 0.0;
  std::vector<Eigen::VectorXd> samples;
  std::deque<PeriodStats> history;
  SteadyDecision decision(settings);
  for (int k = 0; k < settings.max_periods; ++k) {
    recorder.start(state.time_s);
    if (start || k > 0) control.resume = state;
    const SimulationResult r = simulate(period_case, table, control);
    state = r.final_state;
    history.push_back(recorder.finish(r.summary));
    if (history.size() > settings.window) history.pop_front();
    samples.push_back(poincare_state(c, state));
    point.periods_run = k + 1;
    if (decision.settled(samples, scale)) break;
  }
  // A whole number of excitation periods has passed: the next point starts at the forcing's
  // phase of t = 0.
  state.time_s = 0.0;
  point.final_state = state;
  const PeriodicityResult verdict = decision.final_verdict(samples.size());
  point.verdict = verdict.verdict;
  point.explanation = verdict.explanation;
  point.converged = point.verdict != PeriodicityVerdict::not_converged;
  point.period = point.verdict == PeriodicityVerdict::periodic ? verdict.period : 0;
  const std::size_t steady_periods = std::min(
      point.period > 0 ? static_cast<std::size_t>(point.period) : settings.window, samples.size());
  for (std::size_t i = samples.size() - steady_periods; i < samples.size(); ++i) {
    point.poincare.push_back({samples[i](0), samples[i](1)});
  }
  if (point.converged) {
    summarize_window(history, steady_periods, c, rb1, point);
  }
  return point;
}

}  // namespace gearimpact
