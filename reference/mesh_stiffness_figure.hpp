// The figure of the mesh stiffness over the true period (`mesh-stiffness --figure DIR` and
// `report` of a pair with [[faults]]): against the same pairs all healthy, each stretch where a
// faulted tooth is in contact shaded and labelled by its gear and number.
#pragma once

#include <string>
#include <vector>

#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gnuplot.hpp"

namespace gearimpact::cli {

// The figure DIR/mesh_stiffness.png of the CSV DIR/mesh_stiffness.csv
// (true_period_mesh_stiffness_csv of `tvms`); `name` is the case's, in the title.
Figure mesh_stiffness_figure(const TruePeriodMeshStiffness& tvms,
                             const std::vector<ToothFault>& faults, const std::string& name);

}  // namespace gearimpact::cli
