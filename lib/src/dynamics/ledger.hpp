// The energy ledger (docs/model.md, Energies), an observer of the accepted steps:
// kinetic + stored energy against the torque work, the damping and friction
// losses and the parametric work of the time-varying stiffness. Each is
// computed on its own (the losses and works as integrals of their powers in
// the state), so the residual measures the integration, not an identity.
// Written once for the two-gear GearSystem and a gear train's system.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "run_parts.hpp"

namespace gearimpact {

// The ledger of a system S that provides kinetic_energy(y), the meshes'
// stored_energy(y, m) by term (ElasticEnergy), shaft_energy_j(y) (the stored
// energy beside the meshes', of shaft springs; 0 without), and
// S::kLedgerStart: the index in its state of the ledger's integrals, in the
// order torque work, damping loss, friction loss, parametric work (its
// continuous part), the mesh damper's loss.
template <typename System>
class EnergyLedgerOf {
 public:
  using StateType = typename System::StateType;
  using ModeType = typename System::ModeType;

  EnergyLedgerOf(const System& system, const StateType& y, const ModeType& m, SimulationSummary& s)
      : system_(system) {
    const double kinetic = system_.kinetic_energy(y);
    energy0_ = kinetic + stored_j(y, m);
    s.kinetic_energy_initial_j = kinetic;
    s.stored_energy_initial_j = energy0_ - kinetic;
  }

  // Stored energy appears or vanishes with a pair entering or leaving under
  // load: the jump is work of the time-varying stiffness.
  void mode_changed(double stored_before_j, double stored_after_j) {
    jump_work_ += stored_after_j - stored_before_j;
  }

  // After an accepted step: the largest stored energies, the scale and the residual.
  void observe(const StateType& y, const ModeType& m, SimulationSummary& s) const {
    const ElasticEnergy u = system_.stored_energy(y, m);
    for (std::size_t i = 0; i < kTermCount; ++i) {
      s.energy_max_j[i] = std::max(s.energy_max_j[i], u.j[i]);
    }
    const double energy = system_.kinetic_energy(y) + (u.total_j() + system_.shaft_energy_j(y));
    // The losses: Hertzian damping, friction, mesh damper.
    book_ledger_residual(energy, energy0_, y[kWork], {y[kDamping], y[kFriction], y[kMeshDamping]},
                         y[kParametric], jump_work_, s);
  }

  void finish(const StateType& y, const ModeType& m, SimulationSummary& s) const {
    book_ledger_totals(system_.kinetic_energy(y), stored_j(y, m), y[kWork], y[kDamping],
                       y[kFriction], y[kMeshDamping], y[kParametric], jump_work_, s);
  }

 private:
  static constexpr std::size_t kWork = System::kLedgerStart;
  static constexpr std::size_t kDamping = kWork + 1;
  static constexpr std::size_t kFriction = kWork + 2;
  static constexpr std::size_t kParametric = kWork + 3;
  static constexpr std::size_t kMeshDamping = kWork + 4;

  double stored_j(const StateType& y, const ModeType& m) const {
    return system_.stored_energy(y, m).total_j() + system_.shaft_energy_j(y);
  }

  const System& system_;
  double energy0_ = 0.0;
  double jump_work_ = 0.0;
};

using EnergyLedger = EnergyLedgerOf<GearSystem>;

}  // namespace gearimpact
