// Helical meshes in a gear train (dynamics/train.hpp; docs/helical.md, Dynamics). References:
// the two-gear torsional run of the same helical case (route B), which a two-body train must
// equal bit for bit; route B's face integral, which route A's sum over slices approaches as the
// slices narrow; the helical loaded STE (stiffness/helical_ste.hpp), a static solver of the same
// slices and gaps (its sorted-gap solve), which a slow, damped route-A run must sit on; and the
// energy ledger.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/mesh_line.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/sliced_pair.hpp"
#include "gearimpact/dynamics/train.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/tooth_identity.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

using namespace gearimpact;

namespace {

// GEARpie's H501 (examples/helical_h501_run.toml): m_n 3.5 mm, alpha_n 20 deg, beta 15 deg,
// z 20/30, b 23 mm; eps_alpha 1.45, eps_beta 0.54.
SimulationCase h501_case() {
  SimulationCase c = paper_case(2);
  c.name = "h501";
  GearPair& p = c.gears;
  p = GearPair{};
  p.teeth1 = 20;
  p.teeth2 = 30;
  p.module_m = 3.5e-3;
  p.pressure_angle_rad = 20.0 * pi / 180.0;
  p.helix_angle_rad = 15.0 * pi / 180.0;
  p.face_width_m = 23e-3;
  p.profile_shift1 = 0.1809;
  p.profile_shift2 = 0.0891;
  p.youngs_modulus_pa = 206e9;
  p.poisson_ratio = 0.3;
  p.density_kg_m3 = 7830.0;
  p.backlash_m = 0.05e-3;
  c.model.friction_coefficient = 0.0;
  c.torque1.constant_n_m = 200.0;
  c.torque2.constant_n_m = -300.0;
  c.initial.w1_rad_per_s = 6000.0 * 2.0 * pi / 60.0;
  c.initial.w2_rad_per_s = c.initial.w1_rad_per_s * 20.0 / 30.0;
  c.integrator.step_s = 0.1e-6;
  c.integrator.end_time_s = 1e-3;
  return c;
}

// The stiffness of a line at rest in contact on N1 with deflection delta, as its run reads it:
// 2 U / delta^2, U the stored energy of the mode it classifies, the line's pairs shifted by
// line_offset as the train shifts them.
double line_stiffness(const MeshLine& line, const TrainMesh& mesh, double theta1, double delta) {
  const double rb1 = line.base_radius_a();
  const double rb2 = line.base_radius_b();
  // s = Rb1 theta1 - Rb2 theta2 = B + delta, kept by the shift.
  const double theta2 = (rb1 * theta1 - mesh.pair.gears.backlash_m - delta) / rb2;
  const MeshMotion q{theta1 + mesh.line_offset_m / rb1, theta2 + mesh.line_offset_m / rb2, 0.0,
                     0.0};
  const Mode m = line.classify_geometry(q);
  if (m.region == Region::free) return 0.0;
  return 2.0 * line.stored_energy(q, m).total_j() / (delta * delta);
}
double line_stiffness(const TrainMesh& mesh, const StiffnessTable& table, double theta1,
                      double delta) {
  return line_stiffness(MeshLine(mesh.pair, table), mesh, theta1, delta);
}

// The sum of line_stiffness over lines (a route-A mesh's slices, or route B's one line), each
// line built once with its pairs' tables (TrainMesh::teeth).
class RestLines {
 public:
  explicit RestLines(std::vector<TrainMesh> meshes) : meshes_(std::move(meshes)) {
    for (const TrainMesh& m : meshes_) {
      lines_.push_back(std::make_unique<MeshLine>(m.pair, *m.table, 0.0, m.teeth));
    }
  }
  double stiffness(double theta1, double delta) const {
    double k = 0.0;
    for (std::size_t i = 0; i < meshes_.size(); ++i) {
      k += line_stiffness(*lines_[i], meshes_[i], theta1, delta);
    }
    return k;
  }

 private:
  std::vector<TrainMesh> meshes_;
  std::vector<std::unique_ptr<MeshLine>> lines_;
};

// Route B's one line of a helical case: the transverse section reading the extended pair table.
TrainMesh route_b_line(const SimulationCase& c) {
  TrainMesh m;
  m.name = "route-b";
  m.pair = dynamics_case(c);
  m.table = run_table(c);
  return m;
}

// A 0.2 mm deep spall on pinion tooth `tooth`'s drive flank over 40 % to 65 % of the transverse
// path of contact, over [y0, y0 + width) of the face.
ToothFault pinion_spall(const SimulationCase& c, int tooth, double y0, double width) {
  const GearPair t = transverse_pair(c.gears);
  const ContactSegment path = contact_segment(t);
  const auto radius = [&](double u) {
    return radius_at_roll_distance(base_radius(t, Gear::one),
                                   path.start_m + u * (path.end_m - path.start_m));
  };
  ToothFault f;
  f.gear = Gear::one;
  f.tooth = tooth;
  f.state.kind = ToothKind::spall;
  f.state.spall.start_radius_m = radius(0.40);
  f.state.spall.end_radius_m = radius(0.65);
  f.state.spall.width_m = width;
  f.state.spall.depth_m = 0.2e-3;
  f.state.face_start_m = y0;
  return f;
}

ToothFault missing_pinion_tooth(int tooth) {
  ToothFault f;
  f.gear = Gear::one;
  f.tooth = tooth;
  f.state.kind = ToothKind::missing;
  return f;
}

}  // namespace

TEST_CASE("a two-body train with a helical mesh is the two-gear helical run, bit for bit") {
  // Route B on both sides: the transverse section reading the extended pair table. The wheel
  // starts in the backlash and strikes; pairs enter and leave at 6000 rpm.
  // Each builds its table: the two-gear run by run_table, the train's mesh by simulate_train.
  const SimulationCase c = h501_case();
  const SimulationResult two_gear = simulate(c);
  const TrainResult result = simulate_train(two_gear_train(c));
  REQUIRE(two_gear.summary.events > 10);
  REQUIRE(result.series.size() == two_gear.series.size());
  for (std::size_t i = 0; i < two_gear.series.size(); ++i) {
    const SeriesRow& a = two_gear.series[i];
    const TrainRow& b = result.series[i];
    const TrainMeshRow& m = b.meshes[0];
    const bool same = a.t_s == b.t_s && a.theta1_rad == b.theta_rad[0] &&
                      a.theta2_rad == b.theta_rad[1] && a.w1_rad_per_s == b.w_rad_per_s[0] &&
                      a.w2_rad_per_s == b.w_rad_per_s[1] && a.s_m == m.s_m &&
                      a.delta_m == m.delta_m && a.region == m.region && a.pairs == m.pairs &&
                      a.normal_force_n == m.normal_force_n;
    if (!same) {
      INFO("row " << i << " at t = " << a.t_s);
      REQUIRE(same);
    }
  }
  MESSAGE("events " << two_gear.summary.events << ", impacts " << two_gear.summary.impacts_n1);
  CHECK(result.summary.steps == two_gear.summary.steps);
  CHECK(result.summary.events == two_gear.summary.events);
  CHECK(result.summary.impacts_n1 == two_gear.summary.impacts_n1);
  CHECK(result.summary.damping_loss_j == two_gear.summary.damping_loss_j);
  CHECK(result.summary.ledger_residual_max_j == two_gear.summary.ledger_residual_max_j);
  CHECK(result.meshes[0].max_penetration_m == two_gear.summary.max_penetration_m);
  CHECK(result.bodies[1].final_w_rad_per_s == two_gear.summary.final_w2_rad_per_s);
}

TEST_CASE("route A's slices sum to route B's stiffness as the slices narrow") {
  // Without gaps, at rest in contact: the sum over the slice lines of 2 U / delta^2 against the
  // route-B line's, over one mesh period. Each slice's exact mean over a period is b / N of the
  // face's (the integral of kappa_t over the path), so only sampling the period at 64 angles
  // parts the means (measured: 3e-4, 1e-3, 4e-5 for N = 4, 8, 16); the pointwise difference is
  // the midpoint rule's across a face whose contact lines end at the path's ends: kappa_t jumps
  // to 0 there, so it falls as 1/N (measured 5.3 %, 2.7 %, 1.25 %), not 1/N^2.
  const SimulationCase c = h501_case();
  TrainMesh face;
  face.name = "h501";
  face.pair = c;
  const std::shared_ptr<const StiffnessTable> table_b = run_table(c);
  TrainMesh route_b = face;
  route_b.pair = dynamics_case(c);
  const double delta = 10e-6;
  const GearPair transverse = transverse_pair(c.gears);
  const double period = base_pitch(transverse) / base_radius(transverse, Gear::one);
  constexpr int kAngles = 64;
  std::vector<double> worst;
  std::vector<double> mean_gap;
  for (const int n : {4, 8, 16}) {
    face.pair.model.stiffness.face_slices = n;
    const std::vector<TrainMesh> slices = helical_slice_meshes(face);
    REQUIRE(static_cast<int>(slices.size()) == n);
    double largest = 0.0;
    double sum_a = 0.0;
    double sum_b = 0.0;
    for (int i = 0; i < kAngles; ++i) {
      const double theta = period * i / kAngles;
      double k_a = 0.0;
      for (const TrainMesh& s : slices) k_a += line_stiffness(s, *s.table, theta, delta);
      const double k_b = line_stiffness(route_b, *table_b, theta, delta);
      largest = std::max(largest, std::fabs(k_a - k_b) / k_b);
      sum_a += k_a;
      sum_b += k_b;
    }
    worst.push_back(largest);
    mean_gap.push_back(std::fabs(sum_a - sum_b) / sum_b);
    MESSAGE("N = " << n << ": largest |K_A - K_B| / K_B = " << largest
                   << ", period means differ by " << mean_gap.back());
  }
  for (std::size_t i = 1; i < worst.size(); ++i) {
    // 1/N: each doubling at least a third off (0.5 for exactly 1/N, slack for the sampling).
    CHECK(worst[i] < 0.67 * worst[i - 1]);
  }
  // The means: sampling 64 angles sees the jumps at different phases for each N, by at most a
  // sample's share of a jump (1/64 of the largest pointwise difference, with room).
  for (std::size_t i = 0; i < worst.size(); ++i) CHECK(mean_gap[i] < worst[i] / 16.0);
  CHECK(worst.back() < 0.05);
}

TEST_CASE("a slow, damped route-A run with crowning and misalignment sits on the helical STE") {
  // The pinion driven at a constant 40 rad/s against the wheel's brake of 300 N*m (T1 = 200 N*m
  // through the ratio), crowning 10 um on the pinion and the wheel's axis tilted across the plane
  // of the axes (gamma_y: F_beta = b gamma_y cos(alpha_wt) = 8.6 um on the drive flanks), 8
  // slices. The static solver (helical_static_transmission_error, the same slices and gaps
  // solved for the deflection that carries F_bt) gives delta_qs(theta1). The run differs from it
  // by the wheel's inertia force: m_e s'' = F_bt - F(delta, t), so |delta - delta_qs| <= m_e
  // |s''| / K, K the loaded elements' stiffness, s'' from the rows' second differences; twice
  // that bound covers the slope of F between its kinks, and the start's transient has decayed
  // (zeta = 0.3 of the mesh damper, e-folding in 1 / (zeta w_n) = 0.16 ms, rows after 2 ms).
  SimulationCase c = h501_case();
  c.name = "h501-crowned-misaligned";
  c.model.stiffness.face_slices = 8;
  // A contact that starts at rest would take (32)'s damping at the smallest impact speed, a
  // stiff damper no fixed step carries: the viscous mesh damper damps this run instead.
  c.model.damping_update = DampingUpdate::off;
  c.model.mesh_damping_ratio = 0.3;
  c.modifications.gear1.lead.crowning_m = 10e-6;
  c.modifications.misalignment.gamma_y_rad = 4e-4;
  const double speed = 40.0;
  c.torque1 = Torque{};
  c.torque1.kind = Torque::Kind::prescribed_speed;
  c.torque1.mean_speed_rad_per_s = speed;
  c.torque2.constant_n_m = -300.0;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 400;
  options.mesh_periods = 1;
  const HelicalStaticTransmissionError ste = helical_static_transmission_error(
      c.gears, c.modifications, 200.0, c.model.stiffness, options);
  REQUIRE_FALSE(ste.face_route);
  const GearPair transverse = transverse_pair(c.gears);
  const double rb1 = base_radius(transverse, Gear::one);
  const double rb2 = base_radius(transverse, Gear::two);
  c.initial.w1_rad_per_s = speed;
  c.initial.w2_rad_per_s = speed * rb1 / rb2;
  c.initial.theta2_rad = -(c.gears.backlash_m + ste.ste_mean_m) / rb2;
  c.integrator.step_s = 0.5e-6;
  // A quarter of a mesh period (2 pi / (z1 w) = 7.9 ms) from 2 ms on.
  c.integrator.end_time_s = 4e-3;
  const GearTrain train = two_gear_train(c);
  const TrainResult result = simulate_train(train);
  const GearTrain run = dynamics_train(train);
  REQUIRE(run.meshes.size() == 8);
  const double m_e = moment_of_inertia(transverse, Gear::two) / (rb2 * rb2);
  const double h = c.integrator.step_s;
  const std::vector<TrainRow>& rows = result.series;
  // Per row: the static deflection at its angle (linear between the solver's 400 points), the
  // loaded elements' stiffness K there, and the residue's deflection (m_e s'' + c s') / K, c the
  // damper's 2 zeta sqrt(K m_e).
  std::vector<double> qs(rows.size(), 0.0);
  std::vector<double> residue(rows.size(), 0.0);
  double stiffest = 0.0;
  for (std::size_t i = 1; i + 1 < rows.size(); ++i) {
    const double u = rows[i].theta_rad[0] / ste.period_rad * static_cast<double>(ste.points.size());
    const auto p = static_cast<std::size_t>(u);
    REQUIRE(p + 1 < ste.points.size());
    const double f = u - static_cast<double>(p);
    qs[i] = (1.0 - f) * ste.points[p].ste_m + f * ste.points[p + 1].ste_m;
    const double k = std::min(ste.points[p].effective_stiffness_n_per_m,
                              ste.points[p + 1].effective_stiffness_n_per_m);
    stiffest = std::max(stiffest, k);
    const double s_d = (rows[i + 1].meshes[0].s_m - rows[i - 1].meshes[0].s_m) / (2.0 * h);
    const double s_dd =
        (rows[i + 1].meshes[0].s_m - 2.0 * rows[i].meshes[0].s_m + rows[i - 1].meshes[0].s_m) /
        (h * h);
    residue[i] = (m_e * std::fabs(s_dd) + 0.6 * std::sqrt(k * m_e) * std::fabs(s_d)) / k;
  }
  // A kink of the STE (an element starting to carry) rings at w_n = sqrt(K / m_e): over one
  // period of that ringing its deflection r reaches |r| <= max |r''| / w_n^2 = max m_e |s''| / K,
  // so each row's bound is the residue's largest within a ringing period either side (that of
  // half the stiffest K, longer than any here: K varies by less than half over a period), and
  // twice that for the interpolation of the static curve across the kinks.
  const double ring_period = 2.0 * pi / std::sqrt(0.5 * stiffest / m_e);
  const auto window = static_cast<std::ptrdiff_t>(std::ceil(ring_period / h));
  double largest = 0.0;
  double widest = 0.0;
  double worst_gap = 0.0;
  int compared = 0;
  const auto n = static_cast<std::ptrdiff_t>(rows.size());
  for (std::ptrdiff_t i = 1; i + 1 < n; ++i) {
    if (rows[static_cast<std::size_t>(i)].t_s < 2e-3) continue;
    double bound = 0.0;
    for (std::ptrdiff_t j = std::max<std::ptrdiff_t>(1, i - window);
         j <= std::min(n - 2, i + window); ++j) {
      bound = std::max(bound, residue[static_cast<std::size_t>(j)]);
    }
    bound *= 2.0;
    const auto u = static_cast<std::size_t>(i);
    const double gap = std::fabs(rows[u].meshes[0].s_m - c.gears.backlash_m - qs[u]);
    largest = std::max(largest, gap / bound);
    widest = std::max(widest, bound);
    worst_gap = std::max(worst_gap, gap);
    ++compared;
  }
  MESSAGE("rows " << compared << ", STE mean " << ste.ste_mean_m << " m, peak-to-peak "
                  << ste.ste_peak_to_peak_m << " m; largest |delta - delta_qs| " << worst_gap
                  << " m, largest ratio to its bound " << largest << ", widest bound " << widest
                  << " m");
  CHECK(compared > 1000);
  CHECK(largest < 1.0);
  // The ledger closes over the eight lines (measured 2.7e-12 J of 1.29 J, RK4 at w_n h = 0.02):
  // 1e-9 of the energy scale leaves room for rounding elsewhere, and is six orders below one
  // slice's stored energy (F delta / 16 = 1.4e-3 J), which a line left out of the books would
  // leave in the residual.
  const SimulationSummary& sum = result.summary;
  MESSAGE("ledger residual " << sum.ledger_residual_max_j << " J of " << sum.ledger_scale_j
                             << " J");
  CHECK(sum.ledger_residual_max_j < 1e-9 * sum.ledger_scale_j);
  // Each slice's own losses sum to the train's.
  double damper = 0.0;
  for (const TrainMeshSummary& m : result.meshes) damper += m.mesh_damping_loss_j;
  REQUIRE(result.meshes.size() == 8);
  CHECK(std::fabs(damper - sum.mesh_damping_loss_j) <= 1e-12 * sum.mesh_damping_loss_j);
}

TEST_CASE("a helical mesh run by slices refuses what its slices cannot take, naming the key") {
  SimulationCase c = h501_case();
  c.modifications.gear1.lead.crowning_m = 5e-6;
  c.model.stiffness.face_slices = 4;
  GearTrain train = two_gear_train(c);
  REQUIRE(runs_by_slices(train.meshes[0]));
  SUBCASE("tooth errors, which a slice's shift would renumber") {
    train.meshes[0].pair.modifications.gear2.pitch_m.assign(30, 1e-6);
    CHECK_THROWS_WITH_AS(simulate_train(train),
                         doctest::Contains("meshes.mesh.modifications.pitch_deviations2"),
                         InputError);
  }
  SUBCASE("the adaptive integrator, whose step bound is a face-wide pair's") {
    train.integrator.kind = IntegratorKind::adaptive;
    CHECK_THROWS_WITH_AS(simulate_train(train), doctest::Contains("integrator.kind"), InputError);
  }
  SUBCASE("more slices than a run holds lines") {
    train.meshes[0].pair.model.stiffness.face_slices = 65;
    CHECK_THROWS_WITH_AS(simulate_train(train), doctest::Contains("meshes.mesh.model.face_slices"),
                         InputError);
  }
  SUBCASE("a misalignment that closes the play across part of the face") {
    // gamma_x moves the wheel's section towards the pinion at one face end: at the first of 4
    // slices (u = -3/8) both flanks close by b u gamma_x sin(alpha_wt) = 62 um each, more than
    // the 50 um of backlash (validate_gaps on each slice).
    train.meshes[0].pair.modifications.misalignment.gamma_x_rad = 0.02;
    CHECK_THROWS_WITH_AS(simulate_train(train), doctest::Contains("meshes.mesh.gears.backlash"),
                         InputError);
  }
  SUBCASE("a friction smoothing speed, as the two-gear run refuses it") {
    train.meshes[0].pair.model.friction_coefficient = 0.05;
    train.meshes[0].pair.model.friction_smoothing_speed_m_s = 0.1;
    CHECK_THROWS_WITH_AS(simulate_train(train),
                         doctest::Contains("meshes.mesh.model.friction_smoothing_speed"),
                         InputError);
  }
  SUBCASE("friction with a fault, as the two-gear run refuses it") {
    ToothFault missing;
    missing.state.kind = ToothKind::missing;
    train.meshes[0].pair.faults.push_back(missing);
    train.meshes[0].pair.model.friction_coefficient = 0.05;
    CHECK_THROWS_WITH_AS(simulate_train(train),
                         doctest::Contains("meshes.mesh.model.friction_coefficient"), InputError);
    // Route B's mesh refuses it alike.
    train.meshes[0].pair.modifications = Modifications{};
    CHECK_THROWS_WITH_AS(simulate_train(train), doctest::Contains("[[faults]]"), InputError);
  }
}

TEST_CASE(
    "a two-gear helical case with modifications runs route A: the train file's run, bit for bit") {
  // The same crowned, misaligned H501 as a two-gear case file (simulate) and as a train file
  // (examples/helical_crowned_train.toml, read by the train reader, its own bodies' inertias and
  // speeds): both must run the same slices through the same loop, so the bodies' angles and
  // speeds agree to the bit, row by row, and each slice's contacts and losses. 1 ms of the
  // examples' 5 ms keeps the test short; the wheel starts in the backlash and strikes.
  const std::filesystem::path examples = std::filesystem::path(GEARIMPACT_PAPER_DATA_DIR) / "..";
  SimulationCase c = read_case_file(examples / "examples/helical_crowned_run.toml");
  c.integrator.end_time_s = 1e-3;
  REQUIRE(runs_by_slices(c));
  const SimulationResult pair = simulate(c);
  const GearTrain file = read_train_file(examples / "examples/helical_crowned_train.toml",
                                         {"integrator.end_time=1 ms"});
  const TrainResult train = simulate_train(file);
  const GearTrain sliced = dynamics_train(file);
  REQUIRE(sliced.meshes.size() == 8);
  REQUIRE(pair.series.size() == train.series.size());
  REQUIRE(pair.series.size() > 1000);
  for (std::size_t i = 0; i < pair.series.size(); ++i) {
    const SeriesRow& a = pair.series[i];
    const TrainRow& b = train.series[i];
    // The series' choices (sliced_pair.hpp): the force summed over the slices, the pairs
    // counted over them, delta and region the most pressed slice's, s slice 1's.
    double force = 0.0;
    int pairs = 0;
    double deepest = 0.0;
    int region = 0;
    for (const TrainMeshRow& m : b.meshes) {
      force += m.normal_force_n;
      pairs += m.pairs;
      if (m.region != 0 && (region == 0 || m.delta_m > deepest)) {
        deepest = m.delta_m;
        region = m.region;
      }
    }
    const bool same = a.t_s == b.t_s && a.theta1_rad == b.theta_rad[0] &&
                      a.theta2_rad == b.theta_rad[1] && a.w1_rad_per_s == b.w_rad_per_s[0] &&
                      a.w2_rad_per_s == b.w_rad_per_s[1] && a.s_m == b.meshes[0].s_m &&
                      a.normal_force_n == force && a.pairs == pairs && a.delta_m == deepest &&
                      a.region == region;
    if (!same) {
      INFO("row " << i << " at t = " << a.t_s);
      REQUIRE(same);
    }
  }
  const SimulationSummary& s = pair.summary;
  MESSAGE("events " << s.events << ", impacts N1 " << s.impacts_n1 << ", N2 " << s.impacts_n2);
  CHECK(s.impacts_n1 > 8);  // every slice strikes at least once
  CHECK(s.steps == train.summary.steps);
  CHECK(s.events == train.summary.events);
  CHECK(s.ledger_residual_max_j == train.summary.ledger_residual_max_j);
  CHECK(s.final_w2_rad_per_s == train.bodies[1].final_w_rad_per_s);
  // Impacts per slice, and summed (the train's own count of all its meshes together).
  REQUIRE(s.slices.size() == 8);
  int n1 = 0;
  int n2 = 0;
  for (std::size_t k = 0; k < s.slices.size(); ++k) {
    const SliceSummary& slice = s.slices[k];
    CHECK(slice.name == "mesh_slice" + std::to_string(k + 1));
    CHECK(slice.impacts_n1 + slice.impacts_n2 == train.meshes[k].impacts);
    CHECK(slice.max_penetration_m == train.meshes[k].max_penetration_m);
    CHECK(slice.damping_loss_j == train.meshes[k].damping_loss_j);
    CHECK(slice.mesh_damping_loss_j == train.meshes[k].mesh_damping_loss_j);
    n1 += slice.impacts_n1;
    n2 += slice.impacts_n2;
  }
  CHECK(n1 == s.impacts_n1);
  CHECK(n2 == s.impacts_n2);
  CHECK(pair.impacts.size() == static_cast<std::size_t>(n1 + n2));
  CHECK(std::is_sorted(
      pair.impacts.begin(), pair.impacts.end(),
      [](const ImpactRecord& x, const ImpactRecord& y) { return x.start_s < y.start_s; }));
}

TEST_CASE("route A in the two-gear run: refusals name the two-gear keys; route B stays") {
  SimulationCase c = h501_case();
  // Without modifications: route B, the section's extended pair table (its run unchanged: the
  // test above it and the program's byte comparison).
  CHECK_FALSE(runs_by_slices(c));
  c.integrator.end_time_s = 1e-5;
  CHECK(simulate(c).summary.slices.empty());
  c.modifications.gear1.lead.crowning_m = 5e-6;
  c.model.stiffness.face_slices = 4;
  REQUIRE(runs_by_slices(c));
  SUBCASE("tooth errors, named without the train's mesh") {
    c.modifications.gear2.pitch_m.assign(30, 1e-6);
    CHECK_THROWS_WITH_AS(simulate(c), doctest::Contains("modifications.pitch_deviations2"),
                         InputError);
    try {
      (void)simulate(c);
    } catch (const InputError& e) {
      CHECK(e.field() == "modifications.pitch_deviations2");
    }
  }
  SUBCASE("elastic shafts on elastic bearings, which the planar train does not hold") {
    c.bearings.kind = BearingKind::elastic;
    c.bearings.gear1.stiffness_x_n_per_m = 1e9;
    c.bearings.gear2.stiffness_x_n_per_m = 1e9;
    c.shafts.kind = ShaftKind::elastic;
    c.shafts.motor_inertia_kg_m2 = 1e-3;
    c.shafts.load_inertia_kg_m2 = 1e-3;
    c.shafts.motor_stiffness_n_m_per_rad = 1e4;
    c.shafts.load_stiffness_n_m_per_rad = 1e4;
    CHECK_THROWS_WITH_AS(simulate(c), doctest::Contains("shafts.kind"), InputError);
  }
  SUBCASE("friction with a fault, named as the two-gear key") {
    ToothFault missing;
    missing.state.kind = ToothKind::missing;
    c.faults.push_back(missing);
    c.model.friction_coefficient = 0.05;
    try {
      (void)simulate(c);
      FAIL("no refusal");
    } catch (const InputError& e) {
      CHECK(e.field() == "model.friction_coefficient");
    }
  }
  SUBCASE("a friction smoothing speed, which the face's friction does not need") {
    c.model.friction_coefficient = 0.05;
    c.model.friction_smoothing_speed_m_s = 0.1;
    CHECK_THROWS_WITH_AS(simulate(c), doctest::Contains("model.friction_smoothing_speed"),
                         InputError);
  }
  SUBCASE("samples, which the train's loop does not take") {
    RunControl control;
    control.sample_rate_hz = 1e6;
    CHECK_THROWS_WITH_AS(simulate(c, control), doctest::Contains("sample_rate"), InputError);
  }
  SUBCASE("the run pool and check_run still refuse it, pointing to route A") {
    CHECK_THROWS_WITH_AS(check_run(c), doctest::Contains("route A"), InputError);
  }
}

TEST_CASE("route A with a fault over the first half of the face changes only that half's slices") {
  // A spall on pinion tooth 0 over [0, b/2) and 8 slices: slices 1-4 lie in the band, 5-8 out of
  // it. Out of it every pair reads the healthy slice's table itself; in it the pairs with pinion
  // tooth 0 read their own, and every other pair the healthy one. The reference for a slice in
  // the band: with the face-width Hertz (each slice a plain spur pair of its width) its Ke is
  // db / b times the transverse section's Ke with the spall across the whole face (that spur
  // pair's own MeshTables, the fault's table of docs/faults.md).
  SimulationCase c = h501_case();
  c.model.stiffness.face_slices = 8;
  c.model.stiffness.helical_hertz = HelicalHertz::face_width;
  const double b = c.gears.face_width_m;
  c.faults = {pinion_spall(c, 0, 0.0, 0.5 * b)};
  TrainMesh face;
  face.name = "h501";
  face.pair = c;
  const std::vector<TrainMesh> slices = helical_slice_meshes(face);
  TrainMesh healthy_face = face;
  healthy_face.pair.faults.clear();
  const std::vector<TrainMesh> healthy = helical_slice_meshes(healthy_face);
  REQUIRE(slices.size() == 8);
  SimulationCase across = c;
  across.gears = transverse_pair(c.gears);
  across.faults = {pinion_spall(c, 0, 0.0, b)};
  const MeshTables section(across.gears, c.model.stiffness, across.faults);
  const double db = b / 8.0;
  const StiffnessTable& first = *slices[0].table;
  const double lo = first.domain_start_m();
  const double hi = first.domain_end_m();
  double worst = 0.0;
  double least_change = 1.0;  // on the drive line N1, the spalled flank's
  for (std::size_t j = 0; j < slices.size(); ++j) {
    const TrainMesh& s = slices[j];
    REQUIRE(s.teeth);
    // The slice's healthy table is the unfaulted face's, to the bit.
    for (int i = 0; i <= 50; ++i) {
      const double x = lo + (hi - lo) * i / 50.0;
      CHECK(s.table->stiffness(x) == healthy[j].table->stiffness(x));
    }
    for (const Region line : {Region::n1, Region::n2}) {
      // Every pair of a hunting period, lcm(20, 30) = 60.
      for (int k = 0; k > -60; --k) {
        const StiffnessTable* t = s.teeth->table(line, k);
        const bool spalled = teeth_of_pair(20, 30, line, k).pinion_tooth == 0;
        if (j >= 4 || !spalled) {
          CHECK(t == s.table.get());
          continue;
        }
        REQUIRE(t != nullptr);
        CHECK(t != s.table.get());
        const TeethInContact teeth = teeth_of_pair(20, 30, line, k);
        const StiffnessTable* reference =
            section.table_of_teeth(teeth.pinion_tooth, teeth.wheel_tooth, line);
        REQUIRE(reference != nullptr);
        double change = 0.0;
        for (int i = 1; i < 400; ++i) {
          const double x = lo + (hi - lo) * (i + 0.37) / 400.0;
          const double want = db / b * reference->stiffness(x);
          const double k_healthy = s.table->stiffness(x);
          worst = std::max(worst, std::fabs(t->stiffness(x) - want) / k_healthy);
          change = std::max(change, (k_healthy - t->stiffness(x)) / k_healthy);
        }
        if (line == Region::n1) least_change = std::min(least_change, change);
      }
    }
  }
  MESSAGE("slices in the band: largest |Ke - db/b Ke_section| / Ke = "
          << worst << "; the spall takes at least " << least_change << " of a slice's Ke");
  // Each table is a fit of its function to about 1e-12 (table.hpp): the slice's table fits the
  // section table's values scaled, so the two agree to a few fits' errors; 1e-9 leaves room.
  CHECK(worst < 1e-9);
  // The band matters: on the drive flank the spall removes the contact over its extent.
  CHECK(least_change > 0.5);
  CHECK(least_change <= 1.0);
}

TEST_CASE("route A's faulted slices sum to route B's faulted pair as the slices narrow") {
  // Pinion tooth 0 missing and tooth 1 spalled over the first half of the face, at rest in
  // contact on N1 with 10 um of deflection, over the angles in which both teeth pass the
  // widened segment: route A's lines (each slice's pairs reading its slice of the tables, the
  // teeth k of the slice's shifted line) against route B's line (the faulted pair tables). As
  // for the healthy face (the test above), the midpoint rule across jumps of kappa (the path's
  // ends and the spall's edges) falls as 1/N. A slice reading another pair's teeth would be off
  // by a whole pair's share of the mesh (a tooth missing or not: a third of K and more).
  SimulationCase c = h501_case();
  const double b = c.gears.face_width_m;
  c.faults = {missing_pinion_tooth(0), pinion_spall(c, 1, 0.0, 0.5 * b)};
  const RestLines route_b({route_b_line(c)});
  SimulationCase healthy = c;
  healthy.faults.clear();
  const RestLines route_b_healthy({route_b_line(healthy)});
  const double delta = 10e-6;
  const GearPair transverse = transverse_pair(c.gears);
  const double period = base_pitch(transverse) / base_radius(transverse, Gear::one);
  constexpr int kAngles = 320;
  TrainMesh face;
  face.name = "h501";
  face.pair = c;
  std::vector<double> worst;
  double fault_loss = 0.0;
  for (const int n : {4, 8, 16}) {
    face.pair.model.stiffness.face_slices = n;
    const RestLines route_a(helical_slice_meshes(face));
    double largest = 0.0;
    for (int i = 0; i < kAngles; ++i) {
      // Five mesh periods from -2.5: pairs 0 and -1 (teeth 0 and 1) cross the segment.
      const double theta = period * (-2.5 + 5.0 * (i + 0.5) / kAngles);
      const double k_b = route_b.stiffness(theta, delta);
      const double k_a = route_a.stiffness(theta, delta);
      const double k_h = route_b_healthy.stiffness(theta, delta);
      largest = std::max(largest, std::fabs(k_a - k_b) / k_h);
      fault_loss = std::max(fault_loss, (k_h - k_b) / k_h);
    }
    worst.push_back(largest);
    MESSAGE("N = " << n << ": largest |K_A - K_B| / K_healthy = " << largest);
  }
  MESSAGE("the faults take up to " << fault_loss << " of the healthy K");
  CHECK(fault_loss > 0.3);
  for (std::size_t i = 1; i < worst.size(); ++i) {
    // 1/N: each doubling at least a third off (0.5 for exactly 1/N, slack for the sampling).
    CHECK(worst[i] < 0.67 * worst[i - 1]);
  }
  CHECK(worst.back() < 0.05);
}

TEST_CASE("a train's helical mesh with friction is the two-gear helical run, bit for bit") {
  // Route B on both sides, as the first test, with f = 0.05 summed over the face (FaceFriction):
  // the same MeshLine forces in either loop, so every row and the friction's loss agree to the
  // bit.
  SimulationCase c = h501_case();
  c.model.friction_coefficient = 0.05;
  c.integrator.end_time_s = 0.5e-3;
  const SimulationResult two_gear = simulate(c);
  const TrainResult result = simulate_train(two_gear_train(c));
  REQUIRE(two_gear.summary.events > 5);
  REQUIRE(result.series.size() == two_gear.series.size());
  for (std::size_t i = 0; i < two_gear.series.size(); ++i) {
    const SeriesRow& a = two_gear.series[i];
    const TrainRow& b = result.series[i];
    const TrainMeshRow& m = b.meshes[0];
    const bool same = a.t_s == b.t_s && a.theta1_rad == b.theta_rad[0] &&
                      a.theta2_rad == b.theta_rad[1] && a.w1_rad_per_s == b.w_rad_per_s[0] &&
                      a.w2_rad_per_s == b.w_rad_per_s[1] && a.delta_m == m.delta_m &&
                      a.normal_force_n == m.normal_force_n &&
                      a.friction_force_n == m.friction_force_n;
    if (!same) {
      INFO("row " << i << " at t = " << a.t_s);
      REQUIRE(same);
    }
  }
  MESSAGE("friction loss " << two_gear.summary.friction_loss_j << " J");
  CHECK(two_gear.summary.friction_loss_j > 0.0);
  CHECK(result.summary.friction_loss_j == two_gear.summary.friction_loss_j);
  CHECK(result.meshes[0].friction_loss_j == two_gear.summary.friction_loss_j);
  CHECK(result.summary.ledger_residual_max_j == two_gear.summary.ledger_residual_max_j);
}

TEST_CASE("route A's friction and faults on slices run as route B's face sums") {
  // A crowning of 1 nm makes the pair run by slices (route A, 16 slices) while its gaps stay far
  // below the 10 um deflections, so route A and route B differ only by the slices' midpoint rule
  // across the face, which the rest stiffness tests above bound pointwise (1.25 % of K at N =
  // 16 healthy, 3.3 % with the faults below). Both runs start from h501_case's state in the
  // backlash and strike; 0.3 ms. Quasi-statically a stiffness off by eps moves the deflection,
  // a part of s, by eps of it: |s_A - s_B| <= eps max |s|.
  SimulationCase c = h501_case();
  c.integrator.end_time_s = 0.3e-3;
  c.model.stiffness.face_slices = 16;
  SimulationCase sliced = c;
  sliced.modifications.gear1.lead.crowning_m = 1e-9;
  REQUIRE(runs_by_slices(sliced));
  REQUIRE_FALSE(runs_by_slices(c));
  const auto compare = [](const SimulationResult& a, const SimulationResult& b) {
    REQUIRE(a.series.size() == b.series.size());
    double worst = 0.0;
    double scale = 0.0;
    for (std::size_t i = 0; i < a.series.size(); ++i) {
      worst = std::max(worst, std::fabs(a.series[i].s_m - b.series[i].s_m));
      scale = std::max(scale, std::fabs(b.series[i].s_m));
    }
    return worst / scale;
  };
  SUBCASE("friction") {
    c.model.friction_coefficient = 0.05;
    sliced.model.friction_coefficient = 0.05;
    const SimulationResult a = simulate(sliced);
    const SimulationResult b = simulate(c);
    const double ds = compare(a, b);
    const double loss =
        (a.summary.friction_loss_j - b.summary.friction_loss_j) / b.summary.friction_loss_j;
    MESSAGE("route A against B: s differs by "
            << ds << " of its largest; friction loss by " << loss << "; A's ledger residual "
            << a.summary.ledger_residual_max_j << " J of " << a.summary.ledger_scale_j);
    CHECK(ds < 0.0125);
    // The slices' sum of sign(Vs) and sign(Vs) X' over the face is the face sum's within 2 / N
    // (the midpoint rule's first order, as the by-hand check of FaceFriction bounds it).
    CHECK(b.summary.friction_loss_j > 0.0);
    CHECK(std::fabs(loss) < 2.0 / 16.0);
    // The frictionless runs' bound (docs/helical.md): the slices' friction is in the books.
    CHECK(a.summary.ledger_residual_max_j < 1e-9 * a.summary.ledger_scale_j);
  }
  SUBCASE("a missing tooth and a half-face spall") {
    const double b = c.gears.face_width_m;
    c.faults = {missing_pinion_tooth(0), pinion_spall(c, 1, 0.0, 0.5 * b)};
    sliced.faults = c.faults;
    const SimulationResult a = simulate(sliced);
    const SimulationResult r = simulate(c);
    const double ds = compare(a, r);
    MESSAGE("route A against B: s differs by " << ds << " of its largest; A's ledger residual "
                                               << a.summary.ledger_residual_max_j << " J of "
                                               << a.summary.ledger_scale_j);
    CHECK(ds < 0.033);
    CHECK(a.summary.ledger_residual_max_j < 1e-9 * a.summary.ledger_scale_j);
  }
}
