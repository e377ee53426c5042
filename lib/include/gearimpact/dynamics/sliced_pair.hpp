// The two-gear run of a helical pair with modifications (docs/helical.md, "Route A in the
// two-gear run"): a gap that varies along an inclined contact line needs each slice of the face
// as its own contact (route A), which a train runs. The two-gear run builds the train of its
// pair (two_gear_train: the pinion, the wheel and the one mesh, which the train's run cuts into
// model.face_slices slice meshes, helical_slice_meshes) and runs it through the train's loop
// (simulate_train): the slices' numbers are the train's bit for bit, with no second
// implementation. Its outputs are the two-gear result's where they are defined, summed or
// chosen over the slices as simulate_by_slices says, and each slice's summary.
#pragma once

#include <functional>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"

namespace gearimpact {

// Whether the two-gear run of c runs by route A: a helical pair (gears.helix_angle > 0) with
// modifications (a relief, a lead modification or a misalignment; tooth errors are refused).
bool runs_by_slices(const SimulationCase& c);

// Runs c by route A and returns the two-gear result:
// - series (SeriesRow; to control.on_row and, with keep_series, the result): t, theta1, theta2,
//   w1, w2 the bodies' (the pinion's and the wheel's, as the train's bodies 0 and 1); s_m slice
//   1's s (every slice's s is Rb1 theta1 - Rb2 theta2 of its angles shifted by its line offset,
//   equal to rounding); normal_force_n and friction_force_n summed over the slices; pairs the
//   loaded tooth pairs summed over the slices (slice-pairs in contact); delta_m and region
//   those of the most pressed slice (the largest delta among the slices in contact; 0 and free
//   when none is).
// - impacts: every slice's contacts, in the order of their start times (ties by slice).
// - summary: the train's (the energy ledger of the whole face, steps, events, impacts_n1 and
//   impacts_n2 summed over the slices, the first and last impact times over them); the largest
//   penetration over the slices; the case's name, stiffness model, damping reading and friction
//   (0); each slice's own summary in `slices`. final_state is left empty (resume is refused).
// - on elastic bearings ([bearings] kind = "elastic"), the train's two bodies carry the gears'
//   bearings (the planar model's masses, planar_mounting) and its sensor, and run as a planar
//   train; the planar series (PlanarRow; to control.on_planar_row and, with keep_series, the
//   result) gives the bodies' centres, bearing forces, angles and speeds, each line's force
//   summed over the slices and its penetration the largest of theirs, and the axial forces and
//   tilting moments of the summed forces (HelicalThrustLevers, as route B); the summary adds the
//   bearings' energies and losses, without route B's thrust maxima.
// Refused before any work, naming the key as a two-gear case file has it: what the two-gear run
// refuses of a helical pair but its modifications (refuse_helical_run), on elastic bearings
// elastic shafts (shafts.kind), a tacho (tacho.pulses_per_revolution), a speed controller
// (torque1.kind, torque2.kind), the bearings' values (validate_planar) and the Lagrangian mesh
// force (model.mesh_force), [[faults]] (faults[0]: a fault's band
// across the face is not laid out over route A's slices), a kinematic driver (torque1.kind: the
// rattle summary is a single contact's), the controls the train's loop has no place for
// (sample_rate, resume, locate_events = false), the series bound (integrator.end_time), and
// what the train's run refuses of the mesh (docs/helical.md, "A helical mesh in a train":
// tooth errors, model.damping_stiffness = "hertz", the adaptive integrator, gaps closing the
// play on a slice; on bearings the step the planar train's bound lets through,
// integrator.step). `fields_checked`, when given, is called once the keys, fields and gaps
// pass, before the run, as check_run calls it.
SimulationResult simulate_by_slices(const SimulationCase& c, const RunControl& control = {},
                                    const std::function<void()>& fields_checked = {});

}  // namespace gearimpact
