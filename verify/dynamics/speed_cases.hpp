// Two-gear cases whose pinion's speed is set, shared by the torsional and the planar train's
// tests: held by its speed controller (the drift check's whole revolutions, SpeedDriftMonitor),
// or driven with a speed harmonic (a kinematic driver's closed form).
#pragma once

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact::verify {

// c (its torque1 speed-controlled) from w_rad_per_s, the wheel rolling with the pinion, checked
// from the start (drive.settle 0) over `revolutions` of the pinion.
inline SimulationCase held_at_speed(SimulationCase c, double w_rad_per_s, double revolutions) {
  c.initial.w1_rad_per_s = w_rad_per_s;
  c.initial.w2_rad_per_s =
      w_rad_per_s * base_radius(c.gears, Gear::one) / base_radius(c.gears, Gear::two);
  c.torque1.mean_speed_rad_per_s = w_rad_per_s;
  c.drive.settle_s = 0.0;
  c.integrator.end_time_s = revolutions * 2.0 * pi / w_rad_per_s;
  return c;
}

// c with its pinion driven at its initial speed and a tenth-order harmonic of a fifth of it.
inline SimulationCase driven_with_harmonic(SimulationCase c) {
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::prescribed_speed;
  c.torque1.mean_speed_rad_per_s = c.initial.w1_rad_per_s;
  c.torque1.driver_orders = {10.0};
  c.torque1.driver_speed_amplitudes_rad_per_s = {0.2 * c.initial.w1_rad_per_s};
  c.torque1.harmonic_phases_rad = {0.0};
  return c;
}

}  // namespace gearimpact::verify
