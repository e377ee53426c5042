// The named stiffness models and ISO 6336-1 side by side for one gear pair:
// the mesh stiffness over one period and every term at the pitch point
// (docs/stiffness-models.md sections 3 and 4).
#pragma once

#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"

namespace gearimpact {

struct ModelComparison {
  StiffnessModelKind kind;
  TimeVaryingMeshStiffness tvms;
  MeshStiffness at_pitch_point;  // one pair in contact at the pitch point
};

struct StiffnessComparison {
  std::vector<ModelComparison> models;  // yang-lin-1987, potential-energy, ross-compatible
  Iso6336Stiffness iso;
  double iso_single_n_per_m;  // c' b
  double iso_mesh_n_per_m;    // c_gamma_alpha b
};

// Every model with all its terms on; the pair needs both bores (the
// foundation term). `samples` per period as in time_varying_mesh_stiffness.
StiffnessComparison compare_stiffness_models(const GearPair& pair, std::size_t samples = 200);

}  // namespace gearimpact
