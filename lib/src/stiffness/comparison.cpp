#include "gearimpact/stiffness/comparison.hpp"

namespace gearimpact {

StiffnessComparison compare_stiffness_models(const GearPair& pair, std::size_t samples) {
  validate_geometry(pair);
  StiffnessComparison result{};
  for (StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy,
        StiffnessModelKind::ross_compatible}) {
    StiffnessModel model;
    model.kind = kind;
    result.models.push_back({kind, time_varying_mesh_stiffness(pair, model, samples),
                             mesh_stiffness(pair, pitch_point_position(pair), model)});
  }
  result.iso = iso6336_method_b(iso6336_pair(pair, 0.0));
  result.iso_single_n_per_m = result.iso.single_stiffness_n_per_m2 * pair.face_width_m;
  result.iso_mesh_n_per_m = result.iso.mesh_stiffness_n_per_m2 * pair.face_width_m;
  return result;
}

}  // namespace gearimpact
