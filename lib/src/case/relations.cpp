// The relations of a case: the checks across keys (validate_relations, relation_problems),
// the checks of every row's range (validate_fields) and of the library's parts (validate).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

// The rows of `section` that `holds` accepts, checked in `c`; errors name
// the key alone, as the library's types name their fields.
template <typename Holds>
void check_rows(const SimulationCase& c, std::string_view section, Holds holds,
                Problems& problems) {
  for (const Field& field : case_schema()) {
    if (field.section != section || !holds(field) || absent(field, c)) continue;
    const double value = field.get(c);
    problems.collect([&] { check_value(field, value, field.key, si_text(field, value)); });
  }
}

// The [model] rows that describe the StiffnessModel.
bool is_stiffness_row(const Field& field) {
  for (std::string_view key :
       {"stiffness_model", "moment_sign", "stiffness_method", "xform_rule", "stiffness_tolerance",
        "spall_reading", "face_slices", "helical_hertz"}) {
    if (field.key == key) return true;
  }
  for (const TermInfo& t : kTerms) {
    if (field.key == t.switch_key) return true;
  }
  return false;
}

}  // namespace

void validate(const GearPair& pair) {
  SimulationCase c;
  c.gears = pair;
  Problems problems;
  check_rows(
      c, "gears", [](const Field&) { return true; }, problems);
  // The relations only between values in their ranges.
  if (problems.empty()) problems.collect([&] { validate_geometry(pair); });
  problems.throw_if_any();
}

void validate(const StiffnessModel& model) {
  SimulationCase c;
  c.model.stiffness = model;
  Problems problems;
  check_rows(c, "model", is_stiffness_row, problems);
  if (problems.empty()) problems.collect([&] { validate_terms(model); });
  if (problems.empty()) problems.collect([&] { check_spall_reading(model); });
  problems.throw_if_any();
}

namespace {

// True when a key of `failed` starts with `prefix` ("gears." or "gears.module").
bool any_failed(const std::vector<std::string>& failed, std::string_view prefix) {
  return std::any_of(failed.begin(), failed.end(), [&](const std::string& key) {
    return key.compare(0, prefix.size(), prefix) == 0;
  });
}

// At most kMostSteps steps over the run, unless its end time or step is refused already.
void most_steps_problem(const IntegratorSettings& s, const std::vector<std::string>& failed,
                        Problems& problems) {
  const double most_steps = static_cast<double>(kMostSteps);
  if (!any_failed(failed, "integrator.end_time") && !any_failed(failed, "integrator.step") &&
      s.end_time_s / s.step_s > most_steps) {
    problems.add(range_problem("integrator.end_time", format_number(s.end_time_s) + " s",
                               "at most " + bound_text(most_steps) +
                                   " steps of integrator.step = " + format_number(s.step_s) +
                                   " s, i.e. end_time <= " + format_number(most_steps * s.step_s) +
                                   " s"));
  }
}

}  // namespace

void validate(const IntegratorSettings& integrator) {
  SimulationCase c;
  c.integrator = integrator;
  Problems problems;
  std::vector<std::string> failed;
  for (const Field& field : case_schema()) {
    if (field.section != "integrator" || !applies(field, c) || absent(field, c)) continue;
    const bool ok = problems.collect([&] {
      const double value = field.get(c);
      check_value(field, value, field.name(), si_text(field, value));
    });
    if (!ok) failed.push_back(field.name());
  }
  most_steps_problem(integrator, failed, problems);
  problems.throw_if_any();
}

namespace {

// The [[faults]] key a crack's refusal by the library names (root_crack.hpp).
std::string fault_key_of(const std::string& library_name) {
  if (library_name == "crack end depth q2") return "end_depth";
  if (library_name == "crack width W_c") return "width";
  if (library_name == "crack angle nu") return "angle";
  if (library_name == "crack start radius r_s") return "start_radius";
  return "depth";
}

// A length as the [[faults]] rows write it.
std::string in_mm(double length_m) {
  return format_quantity(length_m, Dimension::length, "mm");
}

// The [[faults]] key a spall's or a chip's refusal by the library names
// (surface_faults.hpp).
std::string surface_fault_key_of(const std::string& library_name) {
  if (library_name == "spall start radius") return "start_radius";
  if (library_name == "spall end radius") return "end_radius";
  if (library_name == "chip radius r_k") return "radius";
  if (library_name == "spall depth d_s") return "depth";
  return "width";
}

// The checks of a spall or a chip that need the gears and the model, each
// naming its key with the limit in mm: the spall's edges on the active
// profile of its tooth (where the mating tip meets the flank up to the tip),
// its depth below the half thickness at its thinner end, the chip's radius
// above the root (the base circle of the paper's tooth) up to the tip, and a
// width up to the face width. Then the library's own checks (place_spall,
// place_chip), should they find more.
void surface_fault_problems(const SimulationCase& c, const ToothFault& f, const std::string& name,
                            bool helical, Problems& problems) {
  const GearPair& pair = c.gears;
  const StiffnessModelKind kind = c.model.stiffness.kind;
  const std::string gear = f.gear == Gear::one ? "pinion" : "wheel";
  const std::size_t before = problems.list().size();
  const double b = pair.face_width_m;
  const double width =
      f.state.kind == ToothKind::spall ? f.state.spall.width_m : f.state.chip.width_m;
  if (!(width <= b)) {
    problems.add(range_problem(name + ".width", in_mm(width),
                               "at most the face width b = " + in_mm(b) +
                                   " (gears.face_width): a fault runs across the face at most"));
  } else if (f.state.face_start_m != 0.0 && !helical) {
    problems.add(range_problem(name + ".face_start", in_mm(f.state.face_start_m),
                               "0 on a spur pair (gears.helix_angle = 0): its sections and its "
                               "contact line are the same across the face, so that a band's "
                               "place there changes nothing"));
  } else if (!(f.state.face_start_m + width <= b)) {
    problems.add(
        range_problem(name + ".face_start", in_mm(f.state.face_start_m),
                      "[0, " + in_mm(b - width) + "]: the band [face_start, face_start + " +
                          "width) within the face width b = " + in_mm(b) + " (gears.face_width)"));
  }
  const double rb = base_radius(pair, f.gear);
  const double tip = tip_radius(pair, f.gear);
  if (f.state.kind == ToothKind::spall) {
    const Spall& spall = f.state.spall;
    // The active profile: the roll distances of the contact segment's ends on
    // this tooth (the wheel's measured from C2).
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    const double sap =
        radius_at_roll_distance(rb, f.gear == Gear::one ? segment.start_m : lp - segment.end_m);
    const std::string where =
        "on the active profile of the " + gear + " tooth, from r = " + in_mm(sap) +
        " (where the mating tip meets the flank) to the tip r = " + in_mm(tip);
    bool edges = true;
    if (!(spall.start_radius_m >= sap && spall.start_radius_m < tip)) {
      edges = false;
      problems.add(range_problem(name + ".start_radius", in_mm(spall.start_radius_m),
                                 "[" + in_mm(sap) + ", " + in_mm(tip) + "): " + where));
    } else if (!(spall.end_radius_m > spall.start_radius_m && spall.end_radius_m <= tip)) {
      edges = false;
      problems.add(range_problem(name + ".end_radius", in_mm(spall.end_radius_m),
                                 "(" + in_mm(spall.start_radius_m) + ", " + in_mm(tip) +
                                     "]: above start_radius, " + where));
    }
    if (edges) {
      const double x1 = flank_half_thickness(pair, f.gear, kind, spall.start_radius_m);
      const double x2 = flank_half_thickness(pair, f.gear, kind, spall.end_radius_m);
      const double x = std::min(x1, x2);
      const double r = x1 <= x2 ? spall.start_radius_m : spall.end_radius_m;
      if (!(spall.depth_m < x)) {
        problems.add(range_problem(name + ".depth", in_mm(spall.depth_m),
                                   "below x = " + in_mm(x) + ", the half thickness of the " + gear +
                                       " tooth at r = " + in_mm(r) +
                                       ", the thinner end of the spall: the pit may not reach "
                                       "the tooth's centre line"));
      }
    }
  } else {
    const bool paper = kind == StiffnessModelKind::yang_lin_1987;
    double root = rb;
    if (!paper) {
      const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
      root = (f.gear == Gear::one ? geometry.gear1 : geometry.gear2).root_radius_m;
    }
    const double r_k = f.state.chip.radius_m;
    if (!(r_k > root && r_k <= tip)) {
      problems.add(range_problem(
          name + ".radius", in_mm(r_k),
          "(" + in_mm(root) + ", " + in_mm(tip) + "]: above the " +
              (paper ? "base circle (the paper's tooth starts there)" : "root circle") +
              ", up to the tip of the " + gear + " tooth"));
    }
  }
  if (problems.list().size() != before) return;
  try {
    // The band's place across the face is checked above; the library's
    // check sees the transverse section, a spur pair.
    ToothFault placed = f;
    placed.state.face_start_m = 0.0;
    check_tooth_faults(pair, c.model.stiffness, {placed});
  } catch (const InputError& e) {
    for (const Problem& p : e.problems()) {
      problems.add(p.renamed(name + "." + surface_fault_key_of(p.field), p.value));
    }
  }
}

// The checks of [[faults]] that need the gears and the model: a constant
// stiffness has no teeth, a tooth number below the gear's teeth, one fault per
// tooth, and a crack that fits its tooth (place_crack).
void fault_problems(const SimulationCase& given, const std::vector<std::string>& failed,
                    Problems& problems) {
  if (given.faults.empty() || any_failed(failed, "faults")) return;
  if (given.model.mesh_stiffness == MeshStiffnessMode::constant) {
    if (!any_failed(failed, "model.mesh_stiffness")) {
      problems.add(range_problem("model.mesh_stiffness", "\"constant\"",
                                 "\"time-varying\" in a case with [[faults]]: a constant "
                                 "stiffness has no teeth to fault"));
    }
    return;
  }
  if (any_failed(failed, "gears.") || any_failed(failed, "model.")) return;
  // A helical tooth's fault is placed on its transverse section, the spur
  // pair its slices are (docs/helical.md, Faults); a spur pair is its own.
  // (A swept section, face_advance_m = W > 0, is the helical pair a run takes.)
  const bool helical = given.gears.helix_angle_rad != 0.0 || given.gears.face_advance_m > 0.0;
  SimulationCase section_case;
  if (helical) {
    section_case = given;
    section_case.gears = transverse_pair(given.gears);
  }
  const SimulationCase& c = helical ? section_case : given;
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const ToothFault& f = c.faults[i];
    const std::string name = "faults[" + std::to_string(i) + "]";
    const int z = teeth(c.gears, f.gear);
    const std::string gear = f.gear == Gear::one ? "pinion" : "wheel";
    if (f.tooth >= z) {
      problems.add(range_problem(name + ".tooth", std::to_string(f.tooth),
                                 "0 ... " + std::to_string(z - 1) + ", the " + std::to_string(z) +
                                     " teeth of the " + gear + " (gears.teeth" +
                                     (f.gear == Gear::one ? "1" : "2") + ")"));
      continue;
    }
    bool repeated = false;
    for (std::size_t j = 0; j < i && !repeated; ++j) {
      if (c.faults[j].gear == f.gear && c.faults[j].tooth == f.tooth) {
        repeated = true;
        problems.add(range_problem(name + ".tooth", std::to_string(f.tooth),
                                   "a " + gear + " tooth without a fault: faults[" +
                                       std::to_string(j) + "] is on it already (one per tooth)"));
      }
    }
    if (repeated) continue;
    if (f.state.kind == ToothKind::spall || f.state.kind == ToothKind::tip_chip) {
      surface_fault_problems(c, f, name, helical, problems);
      continue;
    }
    if (f.state.kind != ToothKind::root_crack) continue;
    try {
      check_tooth_faults(c.gears, c.model.stiffness, {f});
    } catch (const InputError& e) {
      for (const Problem& p : e.problems()) {
        problems.add(p.renamed(name + "." + fault_key_of(p.field), p.value));
      }
    }
  }
  // A gear with every tooth missing has no tooth left to carry the load: no
  // pair is ever loaded, so a run would only drift and the STE is undefined.
  for (const Gear gear : {Gear::one, Gear::two}) {
    const int z = teeth(c.gears, gear);
    std::vector<bool> missing(static_cast<std::size_t>(std::max(z, 0)), false);
    for (const ToothFault& f : c.faults) {
      if (f.gear == gear && f.state.kind == ToothKind::missing && f.tooth >= 0 && f.tooth < z) {
        missing[static_cast<std::size_t>(f.tooth)] = true;
      }
    }
    if (z > 0 && std::all_of(missing.begin(), missing.end(), [](bool m) { return m; })) {
      const std::string which = gear == Gear::one ? "pinion" : "wheel";
      problems.add(range_problem("faults",
                                 "all " + std::to_string(z) + " " + which + " teeth missing",
                                 "at least one " + which +
                                     " tooth not missing: with every tooth missing no tooth is "
                                     "left to carry the load"));
    }
  }
}

}  // namespace

void relation_problems(const SimulationCase& c, const std::vector<std::string>& failed,
                       Problems& problems) {
  bool geometry_valid = false;
  if (!any_failed(failed, "gears.")) {
    try {
      validate_geometry(c.gears);
      geometry_valid = true;
    } catch (const InputError& e) {
      for (const Problem& p : e.problems()) problems.add(p.renamed("gears." + p.field, p.value));
    }
    // B is half the total play, and the play 2B fits in a tooth space: half
    // the circular pitch, pi m / 2, for teeth of standard thickness.
    if (const double most = pi * c.gears.module_m / 4.0; c.gears.backlash_m > most) {
      problems.add(range_problem("gears.backlash", format_number(c.gears.backlash_m) + " m",
                                 "at most pi m / 4 = " + format_number(most) +
                                     " m: B is half the play, and the play fits in a tooth space "
                                     "of half the circular pitch"));
    }
  }
  if (!any_failed(failed, "model.")) {
    problems.collect([&] { validate_terms(c.model.stiffness, "model"); });
    problems.collect([&] { check_spall_reading(c.model.stiffness, "model"); });
  }
  // The diameters of a relief against the active profile need a valid pair.
  if (geometry_valid && !any_failed(failed, "modifications.")) {
    problems.collect([&] { validate_modifications(c.gears, c.modifications); });
  }
  const std::array<std::pair<const char*, const Torque*>, 2> torques{
      {{"torque1", &c.torque1}, {"torque2", &c.torque2}}};
  for (const auto& [name, torque] : torques) {
    if (any_failed(failed, std::string(name) + ".")) continue;
    if (torque->kind == Torque::Kind::user && !torque->user) {
      problems.add(range_problem(std::string(name) + ".user", "empty", "a callable T(t_s) in N m"));
    }
    if (torque->kind == Torque::Kind::harmonic) {
      // One harmonic is one element of each list.
      const std::size_t n = torque->harmonic_amplitudes_n_m.size();
      const std::array<std::pair<const char*, std::size_t>, 2> others{
          {{"angular_frequencies", torque->harmonic_angular_frequencies_rad_per_s.size()},
           {"phases", torque->harmonic_phases_rad.size()}}};
      for (const auto& [key, size] : others) {
        if (size != n) {
          problems.add(range_problem(std::string(name) + "." + key,
                                     std::to_string(size) + " values",
                                     "as many values as " + std::string(name) + ".amplitudes (" +
                                         std::to_string(n) + ")"));
        }
      }
    }
    // The section's name as a copy: a lambda may not capture a structured binding in C++17.
    const std::string section = std::string(name) + ".";
    const auto check_profile = [&](const char* times_key, const std::vector<double>& times,
                                   const char* values_key, const std::size_t values,
                                   bool steps_allowed) {
      if (times.size() != values) {
        problems.add(range_problem(section + values_key, std::to_string(values) + " values",
                                   "as many values as " + section + times_key + " (" +
                                       std::to_string(times.size()) + ")"));
        return false;
      }
      for (std::size_t i = 1; i < times.size(); ++i) {
        const bool ok = steps_allowed ? times[i] >= times[i - 1] : times[i] > times[i - 1];
        if (ok) continue;
        problems.add(range_problem(
            section + times_key + "[" + std::to_string(i) + "]", format_number(times[i]) + " s",
            (steps_allowed ? "at least the time before it, " : "more than the time before it, ") +
                format_number(times[i - 1]) + " s" +
                (steps_allowed ? std::string()
                               : std::string(": a kinematic driver cannot step its speed (it "
                                             "would need an infinite torque); "
                                             "kind = \"speed-controlled\" may step its "
                                             "reference"))));
        return false;
      }
      return true;
    };
    if (torque->kind == Torque::Kind::profile) {
      if (torque->profile_times_s.empty()) {
        problems.add(range_problem(std::string(name) + ".profile_times", "0 values",
                                   "at least one point (one point is a constant torque)"));
      } else {
        check_profile("profile_times", torque->profile_times_s, "profile_torques",
                      torque->profile_torques_n_m.size(), true);
      }
    }
    bool profile_valid = true;
    if (has_speed_reference(*torque) && (!torque->speed_profile_speeds_rad_per_s.empty() ||
                                         !torque->speed_profile_times_s.empty())) {
      profile_valid =
          check_profile("speed_profile_times", torque->speed_profile_times_s,
                        "speed_profile_speeds", torque->speed_profile_speeds_rad_per_s.size(),
                        torque->kind == Torque::Kind::speed_controlled);
    }
    if (torque->kind == Torque::Kind::prescribed_speed) {
      // One order is one element of each list.
      const std::size_t n = torque->driver_speed_amplitudes_rad_per_s.size();
      const std::array<std::pair<const char*, std::size_t>, 2> others{
          {{"orders", torque->driver_orders.size()},
           {"phases", torque->harmonic_phases_rad.size()}}};
      bool lists_agree = true;
      for (const auto& [key, size] : others) {
        if (size != n) {
          lists_agree = false;
          problems.add(range_problem(std::string(name) + "." + key,
                                     std::to_string(size) + " values",
                                     "as many values as " + std::string(name) +
                                         ".speed_amplitudes (" + std::to_string(n) + ")"));
        }
      }
      // The driver sets w1(0); a different initial.w1 would be ignored.
      if (lists_agree && profile_valid && !any_failed(failed, "initial.w1")) {
        const double w0 = driver_speed_at(*torque, 0.0);
        const double written = c.initial.w1_rad_per_s;
        if (std::fabs(written - w0) > 1e-9 * std::fabs(w0)) {
          problems.add(range_problem(
              "initial.w1", format_number(written) + " rad/s",
              "the driver's w1(0) = mean_speed + sum_i speed_amplitudes[i] sin(phases[i]) = " +
                  format_number(w0) +
                  " rad/s (to 1e-9 of it), as [torque1] kind = \"prescribed-speed\" prescribes "
                  "w1",
              "initial.w1 = \"" + format_number(w0) + " rad/s\""));
        }
      }
    }
  }
  // A helical pair's faults are placed on its transverse section, which needs its geometry.
  if (c.gears.helix_angle_rad == 0.0 || geometry_valid) fault_problems(c, failed, problems);
  if (c.model.friction_law == FrictionLaw::table &&
      !any_failed(failed, "model.friction_table_slide_to_roll") &&
      !any_failed(failed, "model.friction_table_coefficients")) {
    problems.collect([&] {
      const FrictionTable& table = c.model.friction_table;
      if (table.slide_to_roll.empty()) {
        throw InputError("model.friction_table_slide_to_roll", "0 values",
                         "at least one slide-to-roll ratio (one entry is a constant f)");
      }
      if (table.coefficient.size() != table.slide_to_roll.size()) {
        throw InputError("model.friction_table_coefficients",
                         std::to_string(table.coefficient.size()) + " values",
                         "as many values as model.friction_table_slide_to_roll (" +
                             std::to_string(table.slide_to_roll.size()) + ")");
      }
      for (std::size_t i = 1; i < table.slide_to_roll.size(); ++i) {
        if (!(table.slide_to_roll[i] > table.slide_to_roll[i - 1])) {
          throw InputError("model.friction_table_slide_to_roll[" + std::to_string(i) + "]",
                           shortest_decimal(table.slide_to_roll[i]),
                           "a value above the one before it, " +
                               shortest_decimal(table.slide_to_roll[i - 1]) +
                               ": the ratios are strictly increasing");
        }
      }
    });
  }
  most_steps_problem(c.integrator, failed, problems);
}

void validate_relations(const SimulationCase& c) {
  Problems problems;
  relation_problems(c, {}, problems);
  problems.throw_if_any();
}

void validate_run_keys(const SimulationCase& c) {
  // Before anything else: the runs that read this take spur meshes only, and
  // a helical pair run as spur would be silently wrong. (simulate, the steady
  // state and the sweeps run a helical pair by its pair table, checked by
  // refuse_helical_run instead.)
  if (c.gears.helix_angle_rad != 0.0) {
    throw_helical_not_taken(c.gears.helix_angle_rad,
                            "a run other than the torsional model's simulate, steady state and "
                            "sweeps (trains)");
  }
  validate_absent_run_keys(c);
}

void validate_absent_run_keys(const SimulationCase& c) {
  Problems problems;
  for (const std::string& key : c.run_keys_absent) {
    const Field* field = find_field(key);
    problems.add(refused_problem(
        key, "absent",
        "a run needs it, and this case is a gear pair alone (the stiffness, STE, ISO 6336, modes "
        "and report need no more)",
        field != nullptr ? allowed_text(*field) : std::string("a value"),
        "give " + key + " (and the other keys of a run: the torques and integrator.end_time)"));
  }
  problems.throw_if_any();
}

void validate_fields(const SimulationCase& c) {
  Problems problems;
  std::vector<std::string> failed;
  for (const Field& field : case_schema()) {
    const bool ok = problems.collect([&] {
      if (field.kind == FieldKind::text) {
        check_text(field, field.get_text(c), field.name());
      } else if (is_list(field.kind)) {
        if (applies(field, c)) check_list(field, field.get_list(c), field.name());
      } else if (applies(field, c) && !absent(field, c)) {
        const double value = field.get(c);
        check_value(field, value, field.name(), si_text(field, value));
      }
    });
    if (!ok) failed.push_back(field.name());
  }
  relation_problems(c, failed, problems);
  problems.throw_if_any();
}

}  // namespace gearimpact
