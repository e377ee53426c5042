// The mesh stiffness of a helical pair by slices of its face (docs/helical.md,
// section The slice model): each slice a transverse spur pair, its contact
// shifted along the line of action by sigma (y - b/2) tan(beta_b). Route A sums
// N slices (midpoint rule), route B integrates over the face exactly through
// C(X), the cumulative per-width stiffness. Stiffnesses are transverse (force
// and deflection along the transverse line of action), N/m; per unit face
// width N/m^2.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/table.hpp"

namespace gearimpact {

// kappa_t(X) = [1 / kappa_beam(X) + 1 / (c_H cos(beta_b))]^-1 per unit face
// width along the transverse path of contact [X_SAP, X_EAP] (measured from C1
// as in MeshLayout), and its integral C(X) from X_SAP.
class FaceStiffness {
 public:
  // From the stiffness table of the pair's transverse spur section
  // (transverse_pair) at width b, by `model`: kappa_beam = 1 / (b (its beam
  // terms)), c_H = Kh / b. face_width: kappa_t = Ke / b of that table.
  FaceStiffness(const GearPair& pair, const StiffnessModel& model, HelicalHertz hertz,
                StiffnessTableOptions options = {});
  // `uniform`: kappa_t constant along the path.
  static FaceStiffness uniform(const GearPair& pair, double kappa_n_per_m2);

  double start_m() const { return start_; }
  double end_m() const { return end_; }
  // kappa_t at X in [X_SAP, X_EAP], N/m^2; InputError outside.
  double kappa(double x_m) const;
  // C(X) = integral of kappa_t from X_SAP to X, clamped to the path, N/m.
  double cumulative(double x_m) const;
  bool is_uniform() const { return !table_.has_value(); }
  // The terms of 1/kappa_t at X in [X_SAP, X_EAP], each per unit face width
  // (m^2/N), summing to 1/kappa_t: b times the width-b table's compliances,
  // the Hertzian one over cos(beta_b) when projected; `uniform` has the
  // Hertzian term alone.
  Compliances compliance_per_width(double x_m) const;

 private:
  FaceStiffness(double start_m, double end_m) : start_(start_m), end_(end_m) {}
  double start_;
  double end_;
  double face_width_;
  double cos_base_helix_ = 1.0;
  HelicalHertz hertz_ = HelicalHertz::projected;
  double uniform_kappa_ = 0.0;
  std::optional<StiffnessTable> table_;
  // C at the pieces' ends (Gauss-Legendre on each of the table's pieces).
  std::vector<double> nodes_m_;
  std::vector<double> cumulative_at_nodes_;
};

// The slices' layout on a line of action and the two routes.
class HelicalMesh {
 public:
  // Throws InputError naming gears.helix_angle for beta = 0 (the spur path
  // holds that pair) and for beta outside (0, 45] deg. `face` must outlive the mesh.
  HelicalMesh(const GearPair& pair, const FaceStiffness& face,
              CoastPhase coast_phase = CoastPhase::half_base_pitch);

  // X_k of pair k at mid-face on `line` at pinion rotation theta1:
  // N1 X_pitch + Rb1 theta1 + k p_bt, N2 X_pitch - Rb1 theta1 (+ p_bt / 2) + k p_bt.
  double mid_face_position_m(Region line, double theta1_rad, int k) const;
  // Slice j's (of n) offset from mid-face along `line`: on N1 sigma (y_j - b/2)
  // tan(beta_b), on N2 its negative.
  double slice_offset_m(Region line, int j, int slices) const;

  // Route A: the sum of kappa_t(X_kj) b / N over the (k, j) on the path.
  double stiffness_slices(Region line, double theta1_rad, int slices) const;
  // Route B: the sum over pairs of [C(min(X_k + W/2, X_EAP)) - C(max(X_k - W/2, X_SAP))] /
  // tan(beta_b).
  double stiffness_face(Region line, double theta1_rad) const;
  // One pair's route-B stiffness with its mid-face contact at X.
  double pair_stiffness_face(double x_mid_m) const;
  // The summed contact-line length in the zone: route B's exact, route A's
  // slices (each db / cos(beta_b) long while its midpoint is on the path).
  double contact_line_length(Region line, double theta1_rad) const;
  double contact_line_length_slices(Region line, double theta1_rad, int slices) const;

  double base_pitch_m() const { return p_bt_; }
  double base_radius1_m() const { return rb1_; }
  double face_width_m() const { return b_; }
  double base_helix_angle_rad() const { return beta_b_; }
  // The mesh period in pinion rotation, 2 pi / z1 = p_bt / Rb1.
  double mesh_period_rad() const { return p_bt_ / rb1_; }

 private:
  const FaceStiffness& face_;
  double x_pitch_;
  double rb1_;
  double p_bt_;
  double start_;
  double end_;
  double b_;
  double beta_b_;
  double tan_bb_;
  double half_w_;  // W / 2 = b tan(beta_b) / 2
  int sigma_;
  double coast_offset_;
};

// The mesh stiffness of a helical pair over one mesh period, both routes,
// from theta1 = 0 (pair 0's mid-face contact at the pitch point) on N1.
struct HelicalMeshStiffnessSample {
  double fraction;                      // of the mesh period
  double theta1_rad;                    // pinion rotation
  double slices_n_per_m;                // route A with model.face_slices slices
  double face_n_per_m;                  // route B
  double contact_line_length_m;         // the exact summed length in the zone
  double contact_line_length_slices_m;  // the slices' (each db / cos(beta_b) while on the path)
};
struct HelicalMeshStiffnessCurve {
  std::vector<HelicalMeshStiffnessSample> samples;
  HelicalGeometry geometry;
  int face_slices = 0;
  // The exact mean over the mesh period, b C(X_EAP) / p_bt: the same for
  // both routes and every N.
  double mean_n_per_m = 0.0;
  double min_face_n_per_m = 0.0;  // over the samples
  double max_face_n_per_m = 0.0;
  double min_slices_n_per_m = 0.0;
  double max_slices_n_per_m = 0.0;
  // b eps_alpha / cos(beta_b).
  double mean_contact_line_length_m = 0.0;
  // ISO 6336-1's c_gamma_alpha b (its helical c' with cos(beta) and zn), for comparison.
  double iso_mesh_stiffness_n_per_m = 0.0;
};
// `samples` in [2, 100000] per mesh period; the model's face_slices and helical_hertz.
HelicalMeshStiffnessCurve helical_mesh_stiffness(const GearPair& pair, const StiffnessModel& model,
                                                 int samples);

// The table a run reads for each tooth pair of a helical pair (route B, the
// extended pair table of docs/helical.md, Dynamics): over the widened segment
// pair_contact_segment(swept_transverse_pair(pair)), X the pair's mid-face
// contact, Ke(X) = HelicalMesh::pair_stiffness_face(X) by model's
// helical_hertz, cut at the kinks X_SAP + W/2 and X_EAP - W/2 (where a
// contact line's end reaches a path end) so that no piece straddles one. A
// face-wide line of stiffness kappa_t per unit width deflected by delta
// stores 1/2 delta^2 times the integral of kappa_t^2 c_i over the line in
// each term i (c_i per unit width, compliance_per_width): each term's
// compliance is 1/Ke times that term's share, so that the terms sum to 1/Ke
// and split a pair's energy as the face does. Throws InputError naming
// gears.helix_angle for a spur pair (its table is StiffnessTable(pair, model)).
StiffnessTable helical_pair_table(const GearPair& pair, const StiffnessModel& model,
                                  StiffnessTableOptions options = {});

// One band [start, end) of a helical tooth pair's face (y from the face end
// at smaller z) whose slices share one state: `section` the table of the
// pair's transverse section (swept with face_advance_m 0, width b) with that
// state across the whole face, so that its compliances per unit width are
// the band's slices'; nullptr where those slices carry nothing.
struct FaceBand {
  double start_m;
  double end_m;
  const StiffnessTable* section;
};

// The table of a helical tooth pair whose slices differ across the face (a
// spall, a chip or a crack: docs/helical.md, Faults), over the same domain
// pair_contact_segment(swept) as `healthy_pair` (helical_pair_table of the
// pair, swept = swept_transverse_pair of it): route B's face integral with
// each slice in its own state,
//   Ke(X) = sum over the face's bands of [integral of kappa_band over the
//           band's extent along `line`, clipped to the path] / tan(beta_b),
// `bands` (disjoint, within [0, b]) in their states and the rest of the face
// healthy, kappa_t from `healthy_section` (the section's healthy table); each
// kappa by `hertz` as FaceStiffness reads it. A band's extent on N1 is X +
// sigma (y - b/2) tan(beta_b) for y in the band, on N2 its mirror. Each term's
// compliance splits the line's energy as helical_pair_table's do. Cut at the
// healthy table's breaks and where a band's end reaches a path end or a
// break of a section table (a fault's edge), so that no piece straddles a
// kink; a part where no slice touches carries nothing
// (StiffnessTable::part_in_contact).
StiffnessTable helical_faulted_pair_table(const GearPair& swept, HelicalHertz hertz,
                                          const StiffnessTable& healthy_pair,
                                          const StiffnessTable& healthy_section,
                                          const std::vector<FaceBand>& bands, Region line,
                                          StiffnessTableOptions options = {});

// The friction of a helical tooth pair by route B (docs/helical.md, Friction
// on a helical pair). Each slice of the pair's contact line at X' on the
// transverse path carries kappa_t(X') delta per unit face width (all slices
// share the pair's deflection), slides at the spur pair's Vs(X') and has the
// spur pair's arms X' and lp - X'; y and X' differ by a factor tan(beta_b), so
// the face sums are integrals over the line's extent on the path,
//   weight = integral of kappa_t,  slip = integral of kappa_t sign(Vs) / weight,
//   arm = integral of kappa_t sign(Vs) X' / weight,
// and Vs is linear in X', so both follow from two primitives from X_SAP,
// C0(X) = integral of kappa_t and C1(X) = integral of kappa_t X', tabled
// (cubic Hermite between nodes, whose slopes kappa_t and kappa_t X are exact)
// and split where Vs changes sign: a look-up, as the stiffness is.
struct FaceSlip {
  double weight_n_per_m = 0.0;  // integral of kappa_t over the line on the path: tan(beta_b) K_pair
  double slip = 0.0;            // the load-weighted mean of sign(Vs), in [-1, 1]
  double arm_m = 0.0;           // the load-weighted mean of sign(Vs) X'
};
class FaceFriction {
 public:
  // `swept` a helical pair's swept transverse section (face_advance_m = W >
  // 0; InputError naming gears.helix_angle otherwise): kappa_t read from its
  // section's table at width b by `model.helical_hertz`, as the faulted
  // pair's table reads it.
  FaceFriction(const GearPair& swept, const StiffnessModel& model,
               StiffnessTableOptions options = {});
  double start_m() const { return start_; }  // X_SAP
  double end_m() const { return end_; }      // X_EAP
  // 1 / cos(beta_b): the flank's normal force over its transverse part, on
  // which Coulomb's law acts.
  double normal_per_transverse() const { return 1.0 / cos_base_helix_; }
  // kappa_t at X on the path, N/m^2 (0 outside it).
  double kappa(double x_m) const;
  // C0 and C1 at X, clamped to the path.
  double weight_primitive(double x_m) const { return primitive(x_m, 0); }
  double moment_primitive(double x_m) const { return primitive(x_m, 1); }
  // The pair whose mid-face contact is at X (its line [X - W/2, X + W/2]
  // clipped to the path) with the sliding speed Vs(X') = rate X' + offset.
  // A line with no extent on the path: the weight 0 and the spur pair's sign
  // and arm at X clamped to the path.
  FaceSlip slip(double x_mid_m, double rate_per_s, double offset_m_s) const;

 private:
  double primitive(double x_m, int which) const;
  std::optional<StiffnessTable> section_;
  double face_width_ = 0.0;
  double cos_base_helix_ = 1.0;
  HelicalHertz hertz_ = HelicalHertz::projected;
  double start_ = 0.0;
  double end_ = 0.0;
  double half_w_ = 0.0;
  double step_ = 0.0;
  std::vector<double> nodes_m_;
  std::vector<double> kappa_;                    // kappa_t at the nodes
  std::array<std::vector<double>, 2> integral_;  // C0, C1 at the nodes
};

// The slice [y0, y1) of a helical tooth pair whose face is `bands`
// (disjoint, as helical_faulted_pair_table takes them) and healthy elsewhere
// (`healthy_section`), at X on the section's path of contact: its stiffness
// per unit face width kappa, each band's kappa (as helical_faulted_pair_table
// reads it, Hertz by `hertz`) weighted by the share of the slice it covers and
// the healthy kappa for the rest; and the slice's compliance terms over its
// width y1 - y0, the covered parts in parallel at one deflection, each part's
// term i weighted by its share times kappa^2 c_i (c_i per unit width), as
// helical_faulted_pair_table splits a line's energy: they sum to 1 / (kappa
// (y1 - y0)), and all are 0 where kappa is. The STE's load across the face
// (route B) and route A's slice tables (MeshTables::slice) both read it.
// `swept` the pair's swept transverse section.
struct SliceStiffness {
  double kappa_n_per_m2 = 0.0;
  Compliances compliance;
};
SliceStiffness helical_slice_stiffness(const GearPair& swept, HelicalHertz hertz,
                                       const StiffnessTable& healthy_section,
                                       const std::vector<FaceBand>& bands, double y0_m, double y1_m,
                                       double x_m);

// The face-load factor of ISO 6336-1 from a slice solution: uniform stiffness
// c per unit face width, a gap linear across the face e(y) = F_betay (y/b - 1/2),
// transverse load F: the deflection delta with integral of c max(0, delta - e)
// over the face equal to F, solved exactly for a piecewise-linear gap, and
// K_Hbeta = max_y w(y) / (F / b).
double face_load_factor_linear_gap(double c_n_per_m2, double face_width_m, double force_n,
                                   double mismatch_m);

}  // namespace gearimpact
