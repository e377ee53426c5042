// What a root crack in one tooth of a pair changes in that tooth's terms, at
// many contact positions X1 of the pair: the change of root_crack.hpp
// (PaperCrackChange, RackCrackChange) prepared once, with X1 placed on the
// tooth as mesh_stiffness places it. MeshTables builds a cracked tooth's
// terms as the healthy tooth's plus this.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/root_crack.hpp"

namespace gearimpact {

class PairCrackChange {
 public:
  // Throws InputError as mesh_stiffness would for this crack and model.
  PairCrackChange(const GearPair& pair, const StiffnessModel& model, Gear gear,
                  const RootCrack& crack);
  // Bending, shear and axial of the cracked tooth less the healthy one's at
  // X1 (InputError for X1 off the range mesh_stiffness takes).
  Compliances at(double x1_m) const;
  // The positions X1 on the contact segment where `at` kinks (the contact
  // meets a section where the cut starts or kinks), ascending: the breaks
  // of a table of the cracked tooth.
  std::vector<double> kinks_x1_m() const;

 private:
  GearPair pair_;
  StiffnessModel model_;
  Gear gear_;
  // The rack-cut models' pair, where RackCrackChange finds its gear.
  std::shared_ptr<const RackGearPairGeometry> geometry_;
  std::optional<PaperCrackChange> paper_;
  std::optional<RackCrackChange> rack_;
};

}  // namespace gearimpact
