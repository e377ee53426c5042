#include "gearimpact/stiffness/helical_ste.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

#include "face_load_book.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"

namespace gearimpact {

namespace {

constexpr long long kMostSliceLoads = 10'000'000;

}  // namespace

void validate_helical_static_transmission_error(const GearPair& pair, const Modifications& m,
                                                double torque1_n_m, int face_slices,
                                                StaticTransmissionErrorOptions options) {
  if (!(pair.helix_angle_rad > 0.0)) {
    throw InputError("gears.helix_angle", format_number(pair.helix_angle_rad * 180.0 / pi) + " deg",
                     "(0, 45] deg for the slice model: a spur pair takes the spur STE");
  }
  if (face_slices < 1 || face_slices > kMostFaceSlices) {
    throw InputError("model.face_slices", std::to_string(face_slices),
                     "an integer in [1, " + std::to_string(kMostFaceSlices) + "]");
  }
  validate_static_transmission_error(pair, m, torque1_n_m, options);
  validate_modifications(pair, m);
  // Each angle keeps the load of every slice: the pair with its modifications and the
  // unmodified one beside it hold 16 bytes per slice and angle, 160 MB at this bound.
  const long long periods = options.mesh_periods > 0
                                ? options.mesh_periods
                                : true_period_mesh_periods(pair, distinct_teeth(m));
  const long long angles = periods * options.points_per_mesh_period;
  if (angles * face_slices > kMostSliceLoads) {
    throw InputError(
        "points", std::to_string(options.points_per_mesh_period),
        "at most " + std::to_string(kMostSliceLoads / (periods * face_slices)) +
            " per mesh period with model.face_slices = " + std::to_string(face_slices) +
            " over a true period of " + std::to_string(periods) + " mesh periods: at most " +
            std::to_string(kMostSliceLoads) + " slice loads (angles times slices)");
  }
}

HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, const Modifications& m, double torque1_n_m, const FaceStiffness& face,
    int face_slices, StaticTransmissionErrorOptions options) {
  validate_helical_static_transmission_error(pair, m, torque1_n_m, face_slices, options);
  const GearPair transverse = transverse_pair(pair);
  const HelicalMesh mesh(pair, face);
  const HelicalGeometry geometry = helical_geometry(pair);
  const double b = pair.face_width_m;
  const int n = face_slices;
  const double db = b / n;
  const double start = face.start_m();
  const double end = face.end_m();
  const double pitch = mesh.base_pitch_m();
  const double half_w = 0.5 * b * std::tan(mesh.base_helix_angle_rad());

  HelicalStaticTransmissionError result;
  result.torque1_n_m = torque1_n_m;
  result.force_n = torque1_n_m / mesh.base_radius1_m();
  result.face_slices = n;
  result.face_width_m = b;
  result.face_route = is_unmodified(m);
  result.mesh_periods = options.mesh_periods > 0
                            ? options.mesh_periods
                            : true_period_mesh_periods(pair, distinct_teeth(m));
  result.period_rad = static_cast<double>(result.mesh_periods) * mesh.mesh_period_rad();
  result.slice_y_m.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) result.slice_y_m[static_cast<std::size_t>(j)] = (j + 0.5) * db;
  // The lead gap of each slice on the drive flanks, the same for every pair.
  std::vector<double> lead(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    lead[static_cast<std::size_t>(j)] =
        lead_gap_m(m, Region::n1, b, geometry.working_pressure_angle_rad,
                   result.slice_y_m[static_cast<std::size_t>(j)]);
  }
  // The profile gaps act in the transverse section, where the spur pair's layout holds.
  const ToothGaps gaps(transverse, m);
  const long long angles = result.mesh_periods * options.points_per_mesh_period;
  FaceLoadBook book(result, angles);
  std::vector<PairSpring> springs;
  std::vector<int> slice_of;
  for (long long i = 0; i < angles; ++i) {
    HelicalStePoint p;
    p.theta1_rad = result.period_rad * static_cast<double>(i) / static_cast<double>(angles);
    p.load_per_width_n_per_m.assign(static_cast<std::size_t>(n), 0.0);
    const double reference = mesh.mid_face_position_m(Region::n1, p.theta1_rad, 0);
    // The pairs whose mid-face contact lies within W/2 of the path: the ones that may touch.
    const int k_first = static_cast<int>(std::floor((start - half_w - reference) / pitch)) - 1;
    const int k_last = static_cast<int>(std::ceil((end + half_w - reference) / pitch)) + 1;
    if (result.face_route) {
      // Every element at the same deflection: delta = F / K_B, and w(y_j) from kappa_t at X_kj.
      p.effective_stiffness_n_per_m = mesh.stiffness_face(Region::n1, p.theta1_rad);
      p.ste_m = result.force_n / p.effective_stiffness_n_per_m;
      p.kte_m = 0.0;
      for (int k = k_first; k <= k_last; ++k) {
        for (int j = 0; j < n; ++j) {
          const double x = reference + k * pitch + mesh.slice_offset_m(Region::n1, j, n);
          if (!(x >= start && x <= end)) continue;
          ++p.elements;
          ++p.loaded_elements;
          p.load_per_width_n_per_m[static_cast<std::size_t>(j)] += face.kappa(x) * p.ste_m;
        }
      }
    } else {
      springs.clear();
      slice_of.clear();
      p.kte_m = std::numeric_limits<double>::infinity();
      for (int k = k_first; k <= k_last; ++k) {
        for (int j = 0; j < n; ++j) {
          const double x = reference + k * pitch + mesh.slice_offset_m(Region::n1, j, n);
          if (!(x >= start && x <= end)) continue;
          const double gap = gaps.gap_m(Region::n1, k, x) + lead[static_cast<std::size_t>(j)];
          springs.push_back({face.kappa(x) * db, gap});
          slice_of.push_back(j);
          p.kte_m = std::min(p.kte_m, gap);
        }
      }
      p.elements = static_cast<int>(springs.size());
      p.ste_m = solve_deflection(springs, result.force_n);
      for (std::size_t e = 0; e < springs.size(); ++e) {
        const double penetration = p.ste_m - springs[e].gap_m;
        if (!(penetration > 0.0)) continue;
        ++p.loaded_elements;
        p.effective_stiffness_n_per_m += springs[e].stiffness_n_per_m;
        p.load_per_width_n_per_m[static_cast<std::size_t>(slice_of[e])] +=
            springs[e].stiffness_n_per_m * penetration / db;
      }
    }
    book.add(std::move(p));
  }
  book.finish();
  return result;
}

HelicalStaticTransmissionError helical_static_transmission_error(
    const GearPair& pair, const Modifications& m, double torque1_n_m, const StiffnessModel& model,
    StaticTransmissionErrorOptions options) {
  // Every refusal before the table's quadrature.
  validate_helical_static_transmission_error(pair, m, torque1_n_m, model.face_slices, options);
  const FaceStiffness face(pair, model, model.helical_hertz);
  return helical_static_transmission_error(pair, m, torque1_n_m, face, model.face_slices, options);
}

}  // namespace gearimpact
