// The loaded static transmission error of a helical pair by slices
// (docs/helical.md, "Loaded STE and the load across the face"): at each pinion
// angle the drive-side deflection delta with
//
//     sum over elements (k, j) of k_kj max(0, delta - e_kj) = F_bt = T1 / Rb1,
//
// element (k, j) slice j (width b / N, mid-plane y_j) of tooth pair k, at
// X_kj = X_k + sigma (y_j - b/2) tan(beta_b) on N1, k_kj = kappa_t(X_kj) b / N,
// e_kj its profile gap at X_kj plus the lead gap at y_j (modifications.hpp),
// solved by the spur STE's sorted-gap solver (solve_deflection). Without any
// gap every element has the same deflection and the face integral (route B)
// gives delta = F_bt / K_B(theta) exactly, the dynamics' route.
#pragma once

#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"

namespace gearimpact {

// One pinion angle.
struct HelicalStePoint {
  double theta1_rad = 0.0;
  double ste_m = 0.0;  // delta, along the transverse line of action
  double kte_m = 0.0;  // min e_kj over the elements on the path
  // Sum of k_kj over the loaded elements; route B: K_B(theta).
  double effective_stiffness_n_per_m = 0.0;
  int elements = 0;         // (pair, slice) elements on the path of contact
  int loaded_elements = 0;  // those with delta > e_kj
  // w(y_j) = sum_k F_kj / db, N/m (route B: sum_k kappa_t(X_kj) delta).
  std::vector<double> load_per_width_n_per_m;
  double load_centre_m = 0.0;     // y_c = sum w y_j / sum w
  double face_load_factor = 0.0;  // K_Hbeta(theta) = max_j w(y_j) / (F_bt / b)
};

struct HelicalStaticTransmissionError {
  double torque1_n_m = 0.0;
  double force_n = 0.0;  // F_bt = T1 / Rb1
  long long mesh_periods = 1;
  double period_rad = 0.0;
  int face_slices = 0;
  double face_width_m = 0.0;  // b
  // True where every gap is 0: the face integral (route B), else the slices (route A).
  bool face_route = true;
  std::vector<double> slice_y_m;  // y_j = (j + 1/2) b / N
  std::vector<HelicalStePoint> points;
  // wbar(y_j), the mean of w over the points (the true period).
  std::vector<double> mean_load_per_width_n_per_m;
  double ste_mean_m = 0.0;
  double ste_peak_to_peak_m = 0.0;
  double face_load_factor = 0.0;          // K_Hbeta = max_j wbar(y_j) / (F_bt / b)
  double largest_face_load_factor = 0.0;  // max over the points of K_Hbeta(theta)
  double mean_load_centre_m = 0.0;        // the centre of wbar
};

// The checks before any work on a helical pair (helix angle > 0): those of
// validate_static_transmission_error, model.face_slices in [1, kMostFaceSlices],
// the modifications (validate_modifications), and at most 1e7 slice loads (angles over
// the true period times slices, naming "points"). Throws InputError naming the key.
void validate_helical_static_transmission_error(const GearPair& pair, const Modifications& m,
                                                double torque1_n_m, int face_slices,
                                                StaticTransmissionErrorOptions options);

// The STE of the helical pair with its modifications under T1 with the per-width stiffness
// `face` and `face_slices` slices, over the true period of the teeth (options.mesh_periods 0).
// Throws as validate_helical_static_transmission_error.
HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, const Modifications& m, double torque1_n_m, const FaceStiffness& face,
    int face_slices, StaticTransmissionErrorOptions options = {});
// The same with the model's per-width stiffness (its helical_hertz) and face_slices.
HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, const Modifications& m, double torque1_n_m, const StiffnessModel& model,
    StaticTransmissionErrorOptions options = {});

}  // namespace gearimpact
