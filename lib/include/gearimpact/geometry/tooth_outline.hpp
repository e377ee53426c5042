// The outline of one rack-cut tooth and the gear body under it, as a
// polyline, for a model that meshes the tooth (the finite-element check of
// the stiffness models, docs/verification.md): the flanks exactly as the
// stiffness models draw them (rack_generation.hpp: the trochoid from the root
// circle, then the involute to the tip) and the rim down to the bore, which
// the fillet-foundation term assumes. Tooth frame of rack_generation.hpp: y
// along the centre line from the gear's centre, the loaded flank at x > 0.
#pragma once

#include <cstddef>
#include <vector>

#include "gearimpact/geometry/rack_generation.hpp"

namespace gearimpact {

struct OutlinePoint {
  double x_m;
  double y_m;
};

struct ToothOutline {
  // The loaded flank from the root circle to the tip circle: the trochoid
  // (gamma from pi/2 down to a0), then the involute (tau from the form point
  // to the tip). The other flank is its mirror x -> -x.
  std::vector<OutlinePoint> flank;
  // Where each requested involute point (tooth_outline's `vertices_tau_rad`)
  // lies in `flank`, in the order asked.
  std::vector<std::size_t> vertex_index;
  double root_radius_m;
  double tip_radius_m;
  double bore_radius_m;
  double root_half_angle_rad;  // theta_f: the flank's foot on the root circle
};

// The outline of `gear`'s tooth with `fillet_segments` segments on the
// trochoid (even steps of gamma) and `involute_segments` on the involute
// (even steps of tau), with each tau of `vertices_tau_rad` (in [form, tip])
// added as a vertex, so that a load there falls on a node. Throws InputError
// naming the bore when the gear has none (bore_diameter1 / bore_diameter2 by
// `gear_name`), or a tau off the involute, or fewer than 2 segments.
ToothOutline tooth_outline(const RackGearGeometry& gear, const char* bore_key, int fillet_segments,
                           int involute_segments, const std::vector<double>& vertices_tau_rad);

}  // namespace gearimpact
