// The energy ledger (docs/model.md, Energies), an observer of the accepted steps:
// kinetic + stored energy against the torque work, the damping and friction
// losses and the parametric work of the time-varying stiffness. Each is
// computed on its own (the losses and works as integrals of their powers in
// the state), so the residual measures the integration, not an identity.
#pragma once

#include <algorithm>
#include <cmath>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "run_parts.hpp"

namespace gearimpact {

class EnergyLedger {
 public:
  EnergyLedger(const GearSystem& system, const State& y, const Mode& m, SimulationSummary& s)
      : system_(system) {
    const double kinetic = system_.kinetic_energy(y);
    energy0_ = kinetic + system_.stored_energy(y, m).total_j();
    s.kinetic_energy_initial_j = kinetic;
    s.stored_energy_initial_j = energy0_ - kinetic;
  }

  // Stored energy appears or vanishes with a pair entering or leaving under
  // load: the jump is work of the time-varying stiffness.
  void mode_changed(double stored_before_j, double stored_after_j) {
    jump_work_ += stored_after_j - stored_before_j;
  }

  // After an accepted step: the largest stored energies, the scale and the residual.
  void observe(const State& y, const Mode& m, SimulationSummary& s) const {
    const ElasticEnergy u = system_.stored_energy(y, m);
    for (std::size_t i = 0; i < kTermCount; ++i) {
      s.energy_max_j[i] = std::max(s.energy_max_j[i], u.j[i]);
    }
    const double energy = system_.kinetic_energy(y) + u.total_j();
    // The losses: Hertzian damping, friction, mesh damper.
    book_ledger_residual(energy, energy0_, y[kTorqueWork],
                         {y[kDampingLoss], y[kFrictionLoss], y[kMeshDampingLoss]},
                         y[kParametricWork], jump_work_, s);
  }

  void finish(const State& y, const Mode& m, SimulationSummary& s) const {
    book_ledger_totals(system_.kinetic_energy(y), system_.stored_energy(y, m).total_j(),
                       y[kTorqueWork], y[kDampingLoss], y[kFrictionLoss], y[kMeshDampingLoss],
                       y[kParametricWork], jump_work_, s);
  }

 private:
  const GearSystem& system_;
  double energy0_ = 0.0;
  double jump_work_ = 0.0;
};

}  // namespace gearimpact
