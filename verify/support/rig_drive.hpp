// The drive and damping reading examples/rig_17_38.toml had before its speed controller: constant
// torques balancing friction's 17.592 W at 40 Hz and D set at each impact. The step policy, the
// sensor's convergence with the sample rate and the indicators' bands were measured under it.
#pragma once

#include "gearimpact/case/simulation_case.hpp"

namespace gearimpact::verify {

inline void use_rig_constant_drive(SimulationCase& c) {
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::constant;
  c.torque1.constant_n_m = 10.0;
  c.torque2 = Torque{};
  c.torque2.kind = Torque::Kind::constant;
  c.torque2.constant_n_m = -22.196478760533587;
  c.model.damping_update = DampingUpdate::each_impact;
}

}  // namespace gearimpact::verify
