#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "gearimpact/case/units.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/iso1328.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

namespace gearimpact::cli {

namespace {

// "[v0, v1, ...]" in SI, each value exact.
std::string values_text(const std::vector<double>& values) {
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    text += (i == 0 ? "" : ", ") + shortest_decimal(values[i]);
  }
  return text + "]";
}

// The tolerances of each gear with a tolerance class and the errors its seed
// draws, which the case file states only as the class and the seed.
void print_drawn_errors(const SimulationCase& c) {
  const Modifications drawn = with_drawn_errors(c.gears, c.modifications);
  for (const Gear gear : {Gear::one, Gear::two}) {
    const int tolerance_class =
        (gear == Gear::one ? c.modifications.gear1 : c.modifications.gear2).iso1328_class;
    if (tolerance_class == 0) continue;
    const GearModifications& g = gear == Gear::one ? drawn.gear1 : drawn.gear2;
    const Iso1328Tolerances t = iso1328_tolerances(c.gears, gear, tolerance_class);
    const char* n = gear == Gear::one ? "1" : "2";
    std::printf("#   gear %s, ISO 1328-1:2013 class %d: f_pT = %s m, f_HalphaT = %s m\n", n,
                tolerance_class, shortest_decimal(t.single_pitch_m).c_str(),
                shortest_decimal(t.profile_slope_m).c_str());
    std::printf("#     drawn with error_seed = %u, on the line of action, tooth 0 first:\n",
                static_cast<unsigned>(c.modifications.error_seed));
    std::printf("#     pitch_deviations%s = %s\n", n, values_text(g.pitch_m).c_str());
    std::printf("#     profile_slope_deviations%s = %s\n", n,
                values_text(g.profile_slope_m).c_str());
  }
}

// The bounds a run of the case is held to, before one is tried: the step (each integrator's, by
// the contact; by the mesh period at the case's speed), the relief diameters of each gear, and
// where a root crack starts and how deep it may reach.
void print_bounds(const SimulationCase& c, bool run) {
  const StepBounds b = step_bounds(c);
  std::printf("\n# Bounds a run is held to (SI):\n");
  std::printf(
      "#   period of the stiffest contact 2 pi sqrt(m_e / K) = %s s: integrator.step <= %s s "
      "with kind = \"rk4\" (the largest first step of \"adaptive\"), <= %s s with \"dopri5\"\n",
      shortest_decimal(b.contact_period_s).c_str(), shortest_decimal(b.rk4_step_s).c_str(),
      shortest_decimal(b.dopri5_step_s).c_str());
  if (run && b.mesh_period_s > 0.0) {
    std::printf(
        "#   mesh period 2 pi / (z1 |w1|) = %s s at initial.w1: integrator.step <= %s s with "
        "every kind\n",
        shortest_decimal(b.mesh_period_s).c_str(), shortest_decimal(b.mesh_step_s).c_str());
  }
  if (run) {
    std::printf("#   this case: integrator.kind = \"%s\", integrator.step = %s s\n",
                name_of(kIntegratorKinds, c.integrator.kind).c_str(),
                shortest_decimal(c.integrator.step_s).c_str());
  }
  if (c.bearings.kind == BearingKind::elastic) {
    std::printf(
        "#   elastic bearings: the planar model's own springs bound the step further (checked "
        "when the run starts)\n");
  }
  // A helical pair's profile modifications are measured in its transverse
  // section (docs/helical.md), and its teeth take no fault: no crack reach.
  const bool helical = c.gears.helix_angle_rad != 0.0;
  const GearPair transverse = transverse_pair(c.gears);
  for (const Gear gear : {Gear::one, Gear::two}) {
    const ActiveProfile p = active_profile(transverse, gear);
    const char* n = gear == Gear::one ? "1" : "2";
    std::printf(
        "#   gear %s: tip_relief_start%s in [d_SAP, d_a) = [%s, %s) m, root_relief_end%s in "
        "(d_SAP, d_a]; single tooth contact from the LPSTC d = %s m to the HPSTC d = %s m (a "
        "long tip relief starts at the HPSTC)\n",
        n, n, shortest_decimal(p.start_diameter_m).c_str(),
        shortest_decimal(p.tip_diameter_m).c_str(), n,
        shortest_decimal(p.lowest_single_contact_diameter_m).c_str(),
        shortest_decimal(p.highest_single_contact_diameter_m).c_str());
    if (helical) continue;
    RootCrack at_default;
    at_default.angle_rad = pi / 4.0;
    CrackReach reach;
    try {
      reach = crack_reach(c.gears, c.model.stiffness, gear, at_default);
    } catch (const InputError& e) {
      std::printf("#   gear %s: no root crack fits its tooth by default: %s\n", n, e.what());
      continue;
    }
    std::printf(
        "#   gear %s: a root crack starts at r_s = %s m (the model's default), where h_c = %s m; "
        "its depth q < h_c / sin(nu) (%s m at nu = 45 deg)\n",
        n, shortest_decimal(reach.start_radius_m).c_str(),
        shortest_decimal(reach.start_half_thickness_m).c_str(),
        shortest_decimal(reach.largest_depth_m).c_str());
  }
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const ToothFault& f = c.faults[i];
    if (f.state.kind != ToothKind::root_crack) continue;
    const CrackReach reach = crack_reach(c.gears, c.model.stiffness, f.gear, f.state.crack);
    std::printf(
        "#   faults[%zu] (gear %d, tooth %d): r_s = %s m, h_c = %s m; its deepest q = %s m, at "
        "most h_c / sin(nu) = %s m\n",
        i, f.gear == Gear::one ? 1 : 2, f.tooth, shortest_decimal(reach.start_radius_m).c_str(),
        shortest_decimal(reach.start_half_thickness_m).c_str(),
        shortest_decimal(largest_crack_depth(f.state.crack)).c_str(),
        shortest_decimal(reach.largest_depth_m).c_str());
  }
}

// Prints the case as a case file in SI units, which reads back to the same
// values, and the derived quantities the checks used. A pair file (only
// [gears] and [model]) is valid for the stiffness commands and `report`.
void check_case(const std::string& file) {
  const PairOrRunCase read = read_pair_or_run_file(file);
  const SimulationCase& c = read.simulation_case;
  // A helical pair's derived lengths are those of its transverse section; a
  // spur pair comes back unchanged.
  const GearPair g = transverse_pair(c.gears);
  if (read.kind == CaseFileKind::pair) {
    std::printf(
        "# %s: a valid pair file ([gears] and [model]: the stiffness commands, report, ste and "
        "modes read it; a run also needs [torque1], [torque2], [initial] and [integrator]). The "
        "pair in SI "
        "units (itself a pair file):\n",
        file.c_str());
    std::fputs(write_case_file(c, CaseUnits::si).c_str(), stdout);
  } else {
    std::printf("# %s: valid. The case in SI units (itself a case file):\n", file.c_str());
    std::fputs(write_case_file(c, CaseUnits::si).c_str(), stdout);
  }
  const ContactSegment segment = contact_segment(g);
  std::printf("\n# Derived (SI):\n");
  if (c.gears.helix_angle_rad != 0.0) {
    const HelicalGeometry h = helical_geometry(c.gears);
    std::printf(
        "#   helical pair: helix angle beta = %s rad, base helix angle beta_b = %s rad, m_t = %s "
        "m, alpha_t = %s rad, contact ratios eps_alpha = %s, eps_beta = %s, eps_gamma = %s; the "
        "lines below are its transverse section's, whose pairs the dynamics load over the contact "
        "segment widened by W / 2 at each end, W = b tan(beta_b) = %s m\n",
        shortest_decimal(h.helix_angle_rad).c_str(),
        shortest_decimal(h.base_helix_angle_rad).c_str(),
        shortest_decimal(h.transverse_module_m).c_str(),
        shortest_decimal(h.transverse_pressure_angle_rad).c_str(),
        shortest_decimal(h.transverse_contact_ratio).c_str(),
        shortest_decimal(h.overlap_ratio).c_str(), shortest_decimal(h.total_contact_ratio).c_str(),
        shortest_decimal(swept_transverse_pair(c.gears).face_advance_m).c_str());
  }
  std::printf("#   pitch radii r1, r2 = %s m, %s m\n",
              shortest_decimal(pitch_radius(g, Gear::one)).c_str(),
              shortest_decimal(pitch_radius(g, Gear::two)).c_str());
  std::printf("#   base radii Rb1, Rb2 = %s m, %s m\n",
              shortest_decimal(base_radius(g, Gear::one)).c_str(),
              shortest_decimal(base_radius(g, Gear::two)).c_str());
  std::printf("#   line of action C1C2 lp = %s m, contact segment [%s, %s] m\n",
              shortest_decimal(line_of_action_length(g)).c_str(),
              shortest_decimal(segment.start_m).c_str(), shortest_decimal(segment.end_m).c_str());
  std::printf("#   base pitch t0 = %s m, contact ratio = %s\n",
              shortest_decimal(base_pitch(g)).c_str(), shortest_decimal(contact_ratio(g)).c_str());
  std::printf("#   moments of inertia J1, J2 = %s kg m^2, %s kg m^2\n",
              shortest_decimal(moment_of_inertia(g, Gear::one)).c_str(),
              shortest_decimal(moment_of_inertia(g, Gear::two)).c_str());
  print_drawn_errors(c);
  print_bounds(c, read.kind == CaseFileKind::run);
  // A valid run can still surprise: said on stderr, as every command warns, and kept as
  // comments of the printed case.
  if (read.kind == CaseFileKind::run) {
    for (const std::string& w : run_warnings(c)) {
      std::printf("# warning: %s\n", w.c_str());
      std::fprintf(stderr, "gearimpact: warning: %s\n", w.c_str());
    }
  }
  // A valid planar case: what runs it, said before a run is tried.
  if (c.bearings.kind == BearingKind::elastic || c.shafts.kind == ShaftKind::elastic) {
    std::printf(
        "# note: elastic bearings or shafts are run by `gearimpact simulate`, `sweep` and "
        "`sweep-friction` (with elastic bearings) and `gearimpact modes`, and by the library's "
        "period map (shooting, Floquet multipliers, continuation) on the planar state\n");
  }
}

}  // namespace

void register_case_commands(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* check = app.add_subcommand(
      "check-case",
      "read and validate a case file (TOML); print its values in SI units, or every error "
      "(file:line, field, value, allowed range, fix), one per line, and exit non-zero");
  check->add_option("file", *file, "the case file, e.g. paper_data/case1.toml")->required();
  check->callback([file] { check_case(*file); });
}

}  // namespace gearimpact::cli
