#include "gearimpact/stiffness/tooth_state.hpp"

#include <cmath>
#include <string>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

std::string to_string(ToothKind kind) {
  switch (kind) {
    case ToothKind::healthy:
      return "healthy";
    case ToothKind::root_crack:
      return "root-crack";
    case ToothKind::missing:
      return "missing";
    case ToothKind::spall:
      return "spall";
    case ToothKind::tip_chip:
      return "tip-chip";
  }
  return "healthy";
}

bool operator==(const ToothState& a, const ToothState& b) {
  if (a.kind != b.kind || a.face_start_m != b.face_start_m) return false;
  if (a.kind == ToothKind::spall) {
    const Spall& p = a.spall;
    const Spall& q = b.spall;
    return p.flank == q.flank && p.start_radius_m == q.start_radius_m &&
           p.end_radius_m == q.end_radius_m && p.width_m == q.width_m && p.depth_m == q.depth_m;
  }
  if (a.kind == ToothKind::tip_chip) {
    return a.chip.radius_m == b.chip.radius_m && a.chip.width_m == b.chip.width_m;
  }
  if (a.kind != ToothKind::root_crack) return true;
  const RootCrack& p = a.crack;
  const RootCrack& q = b.crack;
  return p.profile == q.profile && p.depth_m == q.depth_m && p.end_depth_m == q.end_depth_m &&
         p.width_m == q.width_m && p.angle_rad == q.angle_rad &&
         p.start_radius_m == q.start_radius_m && p.flank == q.flank;
}

bool operator==(const ToothFault& a, const ToothFault& b) {
  return a.gear == b.gear && a.tooth == b.tooth && a.state == b.state;
}

void check_tooth_faults(const GearPair& pair, const StiffnessModel& model,
                        const std::vector<ToothFault>& faults) {
  for (std::size_t i = 0; i < faults.size(); ++i) {
    const ToothFault& f = faults[i];
    const std::string name = "faults[" + std::to_string(i) + "]";
    const int z = teeth(pair, f.gear);
    if (!(f.tooth >= 0 && f.tooth < z)) {
      throw InputError(name + ".tooth", f.tooth,
                       "0 ... " + std::to_string(z - 1) + ": the teeth of the " +
                           (f.gear == Gear::one ? "pinion" : "wheel") + " in mesh order");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (faults[j].gear == f.gear && faults[j].tooth == f.tooth) {
        throw InputError(name + ".tooth", f.tooth,
                         "a tooth not already faulted: faults[" + std::to_string(j) +
                             "] is on the same tooth, and a tooth has one state");
      }
    }
    if (f.state.face_start_m != 0.0) {
      const bool band = f.state.kind == ToothKind::spall || f.state.kind == ToothKind::tip_chip;
      const bool helical = pair.helix_angle_rad != 0.0 || pair.face_advance_m > 0.0;
      const double width =
          f.state.kind == ToothKind::spall ? f.state.spall.width_m : f.state.chip.width_m;
      if (!band || !helical) {
        throw InputError(name + ".face_start", format_number(f.state.face_start_m) + " m",
                         "0 but for a spall or a chip on a helical pair: a spur pair's teeth "
                         "are the same across the face");
      }
      if (!(f.state.face_start_m > 0.0 && f.state.face_start_m + width <= pair.face_width_m)) {
        throw InputError(name + ".face_start", format_number(f.state.face_start_m) + " m",
                         "[0, b - width] = [0, " + format_number(pair.face_width_m - width) +
                             "] m: the band within the face");
      }
    }
    const bool paper = model.kind == StiffnessModelKind::yang_lin_1987;
    if (f.state.kind == ToothKind::spall) {
      if (paper) {
        place_spall(f.state.spall, pair, f.gear);
      } else {
        const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
        place_spall(f.state.spall, f.gear == Gear::one ? geometry.gear1 : geometry.gear2,
                    geometry.contact_width_m);
      }
      continue;
    }
    if (f.state.kind == ToothKind::tip_chip) {
      if (paper) {
        place_chip(f.state.chip, pair, f.gear);
      } else {
        const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
        place_chip(f.state.chip, f.gear == Gear::one ? geometry.gear1 : geometry.gear2,
                   geometry.contact_width_m);
      }
      continue;
    }
    if (f.state.kind != ToothKind::root_crack) continue;
    if (paper) {
      check_paper_crack(tooth_of(pair, f.gear), pair.face_width_m, f.state.crack);
    } else {
      const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
      place_crack(f.state.crack, f.gear == Gear::one ? geometry.gear1 : geometry.gear2, model.kind,
                  geometry.contact_width_m);
    }
  }
}

CrackReach crack_reach(const GearPair& pair, const StiffnessModel& model, Gear gear,
                       const RootCrack& crack) {
  // The place and the section do not depend on the depth: placed without one.
  RootCrack shallow = crack;
  shallow.depth_m = 0.0;
  shallow.end_depth_m = 0.0;
  CrackReach reach;
  if (model.kind == StiffnessModelKind::yang_lin_1987) {
    check_paper_crack(tooth_of(pair, gear), pair.face_width_m, shallow);
    const InvoluteTooth tooth = tooth_of(pair, gear);
    reach.start_radius_m = tooth.base_radius_m;
    reach.start_half_thickness_m = paper_crack_start_half_thickness(tooth);
  } else {
    const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
    const PlacedCrack placed =
        place_crack(shallow, gear == Gear::one ? geometry.gear1 : geometry.gear2, model.kind,
                    geometry.contact_width_m);
    reach.start_radius_m = placed.start_radius_m;
    reach.start_half_thickness_m = placed.start_half_thickness_m;
  }
  reach.largest_depth_m = reach.start_half_thickness_m / std::sin(crack.angle_rad);
  return reach;
}

ToothState tooth_state(const std::vector<ToothFault>& faults, Gear gear, int tooth) {
  for (const ToothFault& f : faults) {
    if (f.gear == gear && f.tooth == tooth) return f.state;
  }
  return {};
}

std::vector<ToothState> tooth_classes(const std::vector<ToothFault>& faults, Gear gear, int z,
                                      std::vector<int>& tooth_class) {
  std::vector<ToothState> states{ToothState{}};
  tooth_class.assign(static_cast<std::size_t>(z), 0);
  for (const ToothFault& f : faults) {
    if (f.gear != gear) continue;
    std::size_t c = 0;
    while (c < states.size() && states[c] != f.state) ++c;
    if (c == states.size()) states.push_back(f.state);
    tooth_class[static_cast<std::size_t>(f.tooth)] = static_cast<int>(c);
  }
  return states;
}

}  // namespace gearimpact
