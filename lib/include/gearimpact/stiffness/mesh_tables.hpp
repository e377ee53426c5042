// The stiffness tables of a mesh whose teeth differ (docs/faults.md): the
// healthy table, shared by every pair of two healthy teeth, and one
// StiffnessTable per distinct (pinion tooth state, wheel tooth state) that
// meets on either line of action. A pair with a missing tooth has no table:
// it carries nothing.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

namespace gearimpact {

class MeshTables {
 public:
  // Checks the faults (check_tooth_faults) before building anything, then
  // builds the healthy table (or takes `healthy`, which must be the table of
  // pair and model) and one table per combination of states that meets. The
  // tables cover the contact segment, as StiffnessTable(pair, model).
  MeshTables(const GearPair& pair, const StiffnessModel& model, std::vector<ToothFault> faults,
             std::shared_ptr<const StiffnessTable> healthy = nullptr,
             StiffnessTableOptions options = {});

  // The table of pair k on `line` (Region::n1 or Region::n2, k as
  // MeshLayout and teeth_of_pair count it); nullptr when either tooth of the
  // pair is missing.
  const StiffnessTable* table(Region line, int k) const {
    const TeethInContact t = teeth_of_pair(pair_.teeth1, pair_.teeth2, line, k);
    return tables_[combination(t)].get();
  }
  // The table of pinion tooth i against wheel tooth j (nullptr: a missing tooth).
  const StiffnessTable* table_of_teeth(int pinion_tooth, int wheel_tooth) const {
    return tables_[combination({pinion_tooth, wheel_tooth})].get();
  }
  const StiffnessTable& healthy() const { return *healthy_; }
  // How many tables were built beside the healthy one.
  std::size_t fault_table_count() const { return fault_tables_; }
  const std::vector<ToothFault>& faults() const { return faults_; }
  bool has_faults() const { return !faults_.empty(); }
  // Which gears have a tooth that differs, and the true period of the mesh
  // in mesh periods (true_period_mesh_periods).
  DistinctTeeth distinct() const { return distinct_; }
  long long true_period_mesh_periods() const;

 private:
  std::size_t combination(TeethInContact t) const {
    return static_cast<std::size_t>(pinion_class_[static_cast<std::size_t>(t.pinion_tooth)]) *
               wheel_states_ +
           static_cast<std::size_t>(wheel_class_[static_cast<std::size_t>(t.wheel_tooth)]);
  }

  GearPair pair_;
  std::vector<ToothFault> faults_;
  std::shared_ptr<const StiffnessTable> healthy_;
  // Each tooth's class: the index of its state among its gear's distinct
  // states, 0 for healthy.
  std::vector<int> pinion_class_;
  std::vector<int> wheel_class_;
  std::size_t wheel_states_ = 1;
  // One entry per (pinion class, wheel class): the healthy table, a fault
  // table, or null (a missing tooth, or a combination that never meets).
  std::vector<std::shared_ptr<const StiffnessTable>> tables_;
  std::size_t fault_tables_ = 0;
  DistinctTeeth distinct_;
};

}  // namespace gearimpact
