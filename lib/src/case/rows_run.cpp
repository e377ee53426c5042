// The rows of a run: [initial], [integrator], [drive] and [tacho].
#include <climits>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/constants.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

void schema_detail::add_initial_rows(std::vector<Field>& rows) {
  Rows r(rows, "initial");
  // s = Rb1 theta1 - Rb2 theta2 is a difference of angles times radii: at
  // 1e6 rad a double holds Rb theta to about 1e-11 m, a millionth of a
  // micrometre deflection; far beyond it the contact is lost in rounding
  // (at 1e17 rad one ulp is 16 rad) and event location cannot converge.
  const Range kInitialAngles{closed(-1e6), closed(1e6),
                             "|theta| <= 1e6 rad keeps s resolved to 1e-11 m"};
  r.quantity(
      "theta1", Dimension::angle, "deg", kInitialAngles, false,
      "theta1(0); theta1 = theta2 = 0 centres the teeth in the backlash",
      [](auto& c) -> auto& { return c.initial.theta1_rad; });
  r.quantity(
      "theta2", Dimension::angle, "deg", kInitialAngles, false, "theta2(0)",
      [](auto& c) -> auto& { return c.initial.theta2_rad; });
  r.quantity(
      "w1", Dimension::angular_velocity, "rad/s", {}, false, "w1(0)",
      [](auto& c) -> auto& { return c.initial.w1_rad_per_s; });
  r.quantity(
      "w2", Dimension::angular_velocity, "rad/s", {}, false, "w2(0)",
      [](auto& c) -> auto& { return c.initial.w2_rad_per_s; });
}

void schema_detail::add_run_rows(std::vector<Field>& rows) {
  {
    Rows r(rows, "integrator");
    r.choice(
        "kind", choices_of(kIntegratorKinds), false, "the integrator",
        [](auto& c) -> auto& { return c.integrator.kind; });
    r.quantity(
        "step", Dimension::time, "us", {open(0.0), {}, {}}, false,
        "the fixed RK4 step (the adaptive integrator's first step); the dynamics also "
        "requires at least " +
            shortest_decimal(kStepsPerContactPeriod) +
            " steps per period of the stiffest contact (" +
            shortest_decimal(kDopri5StepsPerContactPeriod) + " with kind = \"dopri5\")",
        [](auto& c) -> auto& { return c.integrator.step_s; });
    r.quantity(
        "end_time", Dimension::time, "ms", {open(0.0), {}, {}}, true,
        "run length; at most " + bound_text(static_cast<double>(kMostSteps)) +
            " steps of integrator.step: a longer run is a mistake (days of computing)",
        [](auto& c) -> auto& { return c.integrator.end_time_s; });
    r.number(
        "relative_tolerance", {closed(1e-14), closed(1e-3), {}}, false,
        "of the adaptive integrator, the cross-check of RK4: 1e-14 is a few ulps of the "
        "state; looser than 1e-3 it no longer sets the step, the largest step that "
        "resolves the contact does (cases 1-3 over 10 ms: the same steps, impacts and "
        "losses at 1e-3 and 1e-2)",
        [](auto& c) -> auto& { return c.integrator.adaptive_relative_tolerance; });
    r.integer(
        "output_every", {closed(1.0), closed(static_cast<double>(INT_MAX)), {}}, false,
        "keep every n-th row of the time series",
        [](auto& c) -> auto& { return c.integrator.output_every; });
  }
  Rows(rows, "drive")
      .number(
          "speed_tolerance", {open(0.0), {}, {}}, false,
          "the largest relative drift of the pinion's mean speed over a whole revolution "
          "from its reference (speed_drift_max_rel) before a planar run warns; 1e-3: over a "
          "1 s record of the rig example the mesh line moves by one bin at 1.5e-3",
          [](auto& c) -> auto& { return c.drive.speed_tolerance; })
      .written_at_default = false;
  {
    Rows r(rows, "tacho");
    r.integer(
         "pulses_per_revolution", {closed(0.0), closed(1048576.0), "0: no tacho"}, false,
         "the tacho's edges a revolution of its shaft, each located as an event on the "
         "true angle (planar runs; simulate --tacho-out writes their times)",
         [](auto& c) -> auto& { return c.tacho.pulses_per_revolution; })
        .written_at_default = false;
    r.choice(
         "shaft", choices_of(kTachoShafts), false, "the shaft the tacho reads",
         [](auto& c) -> auto& { return c.tacho.shaft; })
        .written_at_default = false;
    r.quantity(
         "offset", Dimension::angle, "deg", {}, false,
         "the angle of edge 0: edges where the shaft's angle crosses offset + 2 pi k / "
         "pulses_per_revolution upward",
         [](auto& c) -> auto& { return c.tacho.offset_rad; })
        .written_at_default = false;
    r.quantity(
         "jitter", Dimension::time, "s", {closed(0.0), {}, {}}, false,
         "the standard deviation of a Gaussian jitter of the emitted edge times (the true "
         "times stay jitter-free)",
         [](auto& c) -> auto& { return c.tacho.jitter_s; })
        .written_at_default = false;
    r.integer(
         "seed", {closed(0.0), closed(4294967295.0), "a 32-bit unsigned integer"}, false,
         "the seed of the jitter: the same seed, the same times, bit for bit",
         [](auto& c) -> auto& { return c.tacho.seed; })
        .written_at_default = false;
  }
  Rows(rows, "drive")
      .quantity(
          "settle", Dimension::time, "s", {closed(0.0), {}, {}}, false,
          "the start of the drift check: revolutions that begin earlier are the start's "
          "transient, not drift (a 10 Hz speed loop's error falls by e^-6.3 in 0.1 s)",
          [](auto& c) -> auto& { return c.drive.settle_s; })
      .written_at_default = false;
}

}  // namespace gearimpact
