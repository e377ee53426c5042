// The stiffness tables of a mesh whose teeth differ (docs/faults.md): the
// healthy table, shared by every pair of two healthy teeth, and one
// StiffnessTable per distinct (pinion tooth state, wheel tooth state) that
// meets on either line of action; with a spall in the pair, one per line (the
// pit lies on one flank). A table of a spalled or chipped tooth is cut at the
// positions where the contact meets the fault's edges (fault_breaks); across
// the whole face its part beyond the edge has no contact (Ke 0,
// StiffnessTable::part_in_contact). A table of a cracked tooth is cut where the
// tooth's terms kink (PairCrackChange::kinks_x1_m: the contact meets a section
// where the crack's cut starts or kinks), so that no piece is fitted across a
// kink. A pair with a missing tooth has no table:
// it carries nothing.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/stiffness/helical.hpp"
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
    return tables_[line == Region::n2 ? 1 : 0][combination(t)].get();
  }
  // The table of pinion tooth i against wheel tooth j on `line` (nullptr: a
  // missing tooth, or teeth that never meet on that line).
  const StiffnessTable* table_of_teeth(int pinion_tooth, int wheel_tooth,
                                       Region line = Region::n1) const {
    return tables_[line == Region::n2 ? 1 : 0][combination({pinion_tooth, wheel_tooth})].get();
  }
  const StiffnessTable& healthy() const { return *healthy_; }
  // A helical pair's section (face_advance_m > 0): the bands of the face of
  // pair k on `line` that are not healthy, each with its section's table as
  // helical_faulted_pair_table integrated them (empty for a pair that reads
  // the healthy table, for a missing tooth and for a spur pair), and the
  // section's healthy table, which the rest of the face reads (nullptr for a
  // spur pair). Valid while these tables live.
  const std::vector<FaceBand>& face_bands(Region line, int k) const {
    static const std::vector<FaceBand> none;
    if (face_bands_[0].empty()) return none;
    const TeethInContact t = teeth_of_pair(pair_.teeth1, pair_.teeth2, line, k);
    return face_bands_[line == Region::n2 ? 1 : 0][combination(t)];
  }
  const StiffnessTable* healthy_section() const { return section_healthy_.get(); }
  // Route A's slice [y0, y1) of these tables of a helical pair (docs/helical.md,
  // Faults): one table per pair over the transverse section's path of
  // contact, for a faulted pair the slice's stiffness from its face bands
  // (helical_slice_stiffness, Hertz by `hertz`), for a pair none of whose
  // bands reaches into the slice `healthy_slice` itself (shared, so that such
  // a slice reads the healthy slice's table bit for bit); the same teeth for
  // the same k, no bands, no section. Throws InputError for a spur pair's
  // tables or a slice outside the face.
  MeshTables slice(double y0_m, double y1_m, std::shared_ptr<const StiffnessTable> healthy_slice,
                   HelicalHertz hertz) const;
  // How many tables were built beside the healthy one.
  std::size_t fault_table_count() const { return fault_tables_; }
  const std::vector<ToothFault>& faults() const { return faults_; }
  bool has_faults() const { return !faults_.empty(); }
  // Which gears have a tooth that differs, and the true period of the mesh
  // in mesh periods (true_period_mesh_periods).
  DistinctTeeth distinct() const { return distinct_; }
  long long true_period_mesh_periods() const;
  // The drive line's tables of the pairs 0, -1, ..., -(periods - 1) (one a
  // mesh period), each once, with how many of those pairs read it, in the
  // order the pairs come: a sum over them then does not depend on where the
  // tables lie in memory. A missing tooth's pairs (no table) are left out.
  std::vector<std::pair<const StiffnessTable*, long long>> table_repeats(long long periods) const;

 private:
  MeshTables() = default;
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
  // Per line (N1, N2), one entry per (pinion class, wheel class): the
  // healthy table, a fault table, or null (a missing tooth, or a combination
  // that never meets on that line).
  std::array<std::vector<std::shared_ptr<const StiffnessTable>>, 2> tables_;
  std::size_t fault_tables_ = 0;
  DistinctTeeth distinct_;
  // A helical pair's: the bands of each combination's table as tables_ holds
  // them, and the section tables they point to.
  std::array<std::vector<std::vector<FaceBand>>, 2> face_bands_;
  std::shared_ptr<const StiffnessTable> section_healthy_;
  std::vector<std::shared_ptr<const StiffnessTable>> section_tables_;
};

// The positions X1 (from C1) at which the contact meets an edge of the fault
// of a tooth of gear `which` in `state`: a spall's two radii, a chip's r_k;
// none for the other kinds. They may lie outside the contact segment.
std::vector<double> fault_breaks(const GearPair& pair, Gear which, const ToothState& state);

}  // namespace gearimpact
