// docs/helical.md: helical pairs by slices of the face. Every reference here
// comes from outside the code under test: the contact lines clipped to the
// zone of action as segments, the closed-form series of their summed length
// (Poisson summation), the spur pair's mesh stiffness by direct quadrature,
// GEARpie's printed H501 report, ISO 6336-1's face-load factor by hand.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <complex>
#include <memory>
#include <vector>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/planar.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/helical.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/steady/period_map.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "gearimpact/steady/steady_state.hpp"
#include "gearimpact/stiffness/helical.hpp"
#include "gearimpact/stiffness/helical_faults.hpp"
#include "gearimpact/stiffness/helical_ste.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::check_refused;
using gearimpact::verify::degree;
using gearimpact::verify::relative_difference;

namespace {

constexpr double pi_ = 3.141592653589793238462643383279502884;

// GEARpie's H501 (REPORT/H501.txt, CLASSES/GEAR_LIBRARY.py): FZG-type helical.
GearPair h501_pair() {
  GearPair p;
  p.teeth1 = 20;
  p.teeth2 = 30;
  p.module_m = 3.5e-3;
  p.pressure_angle_rad = 20.0 * degree;
  p.helix_angle_rad = 15.0 * degree;
  p.face_width_m = 23e-3;
  p.profile_shift1 = 0.1809;
  p.profile_shift2 = 0.0891;
  p.youngs_modulus_pa = 206e9;
  p.poisson_ratio = 0.3;
  return p;
}

// The same with the report's printed centre distance and tips.
HelicalInputs h501_printed() {
  HelicalInputs in = helical_inputs(h501_pair());
  in.centre_distance_m = 91.5e-3;
  in.tip_radius1_m = 40.336e-3;
  in.tip_radius2_m = 58.132e-3;
  return in;
}

// The summed length of the contact lines in the zone [S, E] x [0, b] of the
// plane of action, each line clipped as a segment (Liang-Barsky on its arc
// length s): line k crosses z = b/2 at X_k, runs at beta_b to the axis, and
// moves by sigma sin(beta_b) along X per unit length.
double clipped_length(const HelicalGeometry& g, double start, double end, double x0, int sigma) {
  const double sb = std::sin(g.base_helix_angle_rad);
  const double cb = std::cos(g.base_helix_angle_rad);
  const double b = g.face_width_m;
  const double p = g.transverse_base_pitch_m;
  double total = 0.0;
  for (int k = -8; k <= 8; ++k) {
    const double xk = x0 + k * p;
    // At s = 0 the line is at z = 0, X = xk - sigma (b/2) tan(beta_b).
    const double xs = xk - sigma * 0.5 * b * sb / cb;
    const double dx = sigma * sb;
    double lo = 0.0;
    double hi = b / cb;
    const double a1 = (start - xs) / dx;
    const double a2 = (end - xs) / dx;
    lo = std::max(lo, std::min(a1, a2));
    hi = std::min(hi, std::max(a1, a2));
    total += std::max(0.0, hi - lo);
  }
  return total;
}

// (1/p) integral over one period of f(x) exp(-i 2 pi n x / p) for f linear
// between the sorted breakpoints xs (spanning exactly one period), with values
// at the segments' ends given by left/right: exact.
std::complex<double> fourier_piecewise_linear(const std::vector<double>& xs,
                                              const std::vector<double>& left_values,
                                              const std::vector<double>& right_values, double p,
                                              int n) {
  std::complex<double> sum = 0.0;
  const std::complex<double> i(0.0, 1.0);
  for (std::size_t s = 0; s + 1 < xs.size(); ++s) {
    const double x0 = xs[s];
    const double x1 = xs[s + 1];
    const double h = x1 - x0;
    if (h <= 0.0) continue;
    const double f0 = right_values[s];
    const double f1 = left_values[s + 1];
    if (n == 0) {
      sum += 0.5 * (f0 + f1) * h;
      continue;
    }
    const double w = 2.0 * pi_ * n / p;
    const std::complex<double> e0 = std::exp(-i * w * x0);
    const std::complex<double> e1 = std::exp(-i * w * x1);
    const std::complex<double> m = -i * w;
    const std::complex<double> integral_1 = (e1 - e0) / m;
    const std::complex<double> integral_x = h * e1 / m - (e1 - e0) / (m * m);
    sum += f0 * integral_1 + (f1 - f0) / h * integral_x;
  }
  return sum / p;
}

// Breakpoints x = c (mod p) in [base, base + p], sorted, with both ends.
std::vector<double> breakpoints(const std::vector<double>& cs, double base, double p) {
  std::vector<double> xs{base, base + p};
  for (double c : cs) {
    double r = std::fmod(c - base, p);
    if (r < 0.0) r += p;
    xs.push_back(base + r);
  }
  std::sort(xs.begin(), xs.end());
  return xs;
}

// A_n of L / Lmean, the closed form of docs/helical.md.
double series_amplitude(double ea, double eb, int n) {
  return 2.0 * std::abs(std::sin(pi_ * n * ea) * std::sin(pi_ * n * eb)) /
         (pi_ * pi_ * n * n * ea * eb);
}
double series_amplitude_slices(double ea, double eb, int n, int slices) {
  return 2.0 * std::abs(std::sin(pi_ * n * ea) * std::sin(pi_ * n * eb)) /
         (pi_ * n * ea * slices * std::abs(std::sin(pi_ * n * eb / slices)));
}

}  // namespace

TEST_CASE("helix angle 0: the transverse pair is the spur pair itself, the keys refuse beyond 45") {
  const GearPair spur = paper_gear_pair();
  CHECK(transverse_pair(spur) == spur);
  GearPair h = spur;
  h.helix_angle_rad = 46.0 * degree;
  check_refused([&] { validate(h); }, "helix_angle", "45");
}

TEST_CASE(
    "the transverse section's reference-circle thickness is the normal rack's over cos(beta)") {
  // docs/helical.md: (pi/2 + 2 x tan alpha_n) m_n / cos(beta), against the
  // mapped spur pair's 2 r (theta_b - inv alpha_t) (its (13) with the shift).
  for (double beta_deg : {8.0, 15.0, 30.0}) {
    GearPair h = h501_pair();
    h.helix_angle_rad = beta_deg * degree;
    const GearPair t = transverse_pair(h);
    for (Gear gear : {Gear::one, Gear::two}) {
      const double thickness =
          2.0 * pitch_radius(t, gear) *
          (half_tooth_angle(t, gear) - involute_function(t.pressure_angle_rad));
      const double expected =
          (pi_ / 2.0 + 2.0 * profile_shift(h, gear) * std::tan(h.pressure_angle_rad)) * h.module_m /
          std::cos(h.helix_angle_rad);
      CHECK(relative_difference(thickness, expected) < 1e-14);
    }
    // The transverse pair's spur lengths are the helical geometry's.
    const HelicalGeometry g = helical_geometry(h);
    CHECK(relative_difference(base_pitch(t), g.transverse_base_pitch_m) < 1e-14);
    CHECK(relative_difference(contact_ratio(t), g.transverse_contact_ratio) < 1e-12);
    CHECK(relative_difference(base_radius(t, Gear::two), g.base_radius2_m) < 1e-14);
    // p_bn = p_bt cos(beta_b); sin(beta_b) = sin(beta) cos(alpha_n).
    CHECK(relative_difference(g.normal_base_pitch_m, g.transverse_base_pitch_m *
                                                         std::cos(g.base_helix_angle_rad)) < 1e-14);
    CHECK(relative_difference(std::sin(g.base_helix_angle_rad),
                              std::sin(h.helix_angle_rad) * std::cos(h.pressure_angle_rad)) <
          1e-14);
    // eps_beta = b sin(beta) / (pi m_n).
    CHECK(relative_difference(g.overlap_ratio, h.face_width_m * std::sin(h.helix_angle_rad) /
                                                   (pi_ * h.module_m)) < 1e-14);
  }
}

TEST_CASE("GEARpie's H501 geometry and forces to the printed digits") {
  // REPORT/H501.txt. The shifts give a_w 91.5003 mm; the report prints 91.5.
  CHECK(std::abs(helical_inputs(h501_pair()).centre_distance_m - 91.5003e-3) < 0.5e-7);
  const HelicalGeometry g = helical_geometry(h501_printed());
  const auto printed = [](double value, double digits, double half_unit) {
    CAPTURE(value);
    CAPTURE(digits);
    return std::abs(value - digits) <= half_unit * (1.0 + 1e-9);
  };
  CHECK(printed(g.normal_base_pitch_m * 1e3, 10.332, 0.0005));
  CHECK(printed(g.transverse_base_pitch_m * 1e3, 10.652, 0.0005));
  CHECK(printed(g.pitch_radius1_m * 1e3, 36.235, 0.0005));
  CHECK(printed(g.pitch_radius2_m * 1e3, 54.352, 0.0005));
  // Working radii r_b / cos(alpha_wt), T1T2 = a_w sin(alpha_wt), AE = g_alpha.
  CHECK(printed(g.base_radius1_m / std::cos(g.working_pressure_angle_rad) * 1e3, 36.600, 0.0005));
  CHECK(printed(g.base_radius2_m / std::cos(g.working_pressure_angle_rad) * 1e3, 54.900, 0.0005));
  CHECK(printed(g.centre_distance_m * std::sin(g.working_pressure_angle_rad) * 1e3, 34.45, 0.005));
  CHECK(printed(g.path_of_contact_m * 1e3, 15.55, 0.005));
  CHECK(printed(g.transverse_contact_ratio, 1.46, 0.005));
  CHECK(printed(g.overlap_ratio, 0.54, 0.005));
  CHECK(printed(g.total_contact_ratio, 2.00, 0.005));
  const HelicalForces f = helical_forces(g, 200.0);
  CHECK(printed(f.transverse_n, 5898.4, 0.05));
  CHECK(printed(f.tangential_n, 5464.5, 0.05));
  CHECK(printed(f.radial_n, 2220.6, 0.05));
  CHECK(printed(f.axial_n, 1479.0, 0.05));
  CHECK(printed(f.normal_n, 6081.0, 0.05));
}

TEST_CASE("contact-line length: clipped segments, the closed-form mean and harmonics") {
  // H501 with the pair's own tips: eps_alpha 1.46, eps_beta 0.54.
  for (HelixHand hand : {HelixHand::right, HelixHand::left}) {
    GearPair h = h501_pair();
    h.helix_hand = hand;
    const HelicalGeometry g = helical_geometry(h);
    const FaceStiffness face = FaceStiffness::uniform(h, 1.5e10);
    const HelicalMesh mesh(h, face);
    const double start = face.start_m();
    const double end = face.end_m();
    const double p = g.transverse_base_pitch_m;
    const double w = g.face_width_m * std::tan(g.base_helix_angle_rad);
    const int sigma = hand_sign(hand);
    // The library's L against the clipped segments, on both lines.
    for (int i = 0; i < 37; ++i) {
      const double theta = -0.3 + 0.017 * i;
      for (Region line : {Region::n1, Region::n2}) {
        const double x0 = mesh.mid_face_position_m(line, theta, 0);
        const int line_sigma = line == Region::n1 ? sigma : -sigma;
        CHECK(relative_difference(mesh.contact_line_length(line, theta),
                                  clipped_length(g, start, end, x0, line_sigma)) < 1e-13);
      }
    }
    // Mean and harmonics of the clipped L, integrated exactly (L is linear
    // between the breakpoints X0 = S +- W/2, E +- W/2 mod p_bt).
    const std::vector<double> xs =
        breakpoints({start - 0.5 * w, start + 0.5 * w, end - 0.5 * w, end + 0.5 * w}, 0.0, p);
    std::vector<double> values;
    for (double x : xs) values.push_back(clipped_length(g, start, end, x, sigma));
    const double mean = fourier_piecewise_linear(xs, values, values, p, 0).real();
    const double mean_closed =
        g.face_width_m * g.transverse_contact_ratio / std::cos(g.base_helix_angle_rad);
    CHECK(relative_difference(mean, mean_closed) < 1e-14);
    for (int n = 1; n <= 6; ++n) {
      const double amplitude =
          2.0 * std::abs(fourier_piecewise_linear(xs, values, values, p, n)) / mean_closed;
      CAPTURE(n);
      CHECK(std::abs(amplitude - series_amplitude(g.transverse_contact_ratio, g.overlap_ratio, n)) <
            1e-10);
    }
  }
}

TEST_CASE("uniform stiffness: K = k'_L L exactly, route A's harmonics are A_n(N)") {
  const GearPair h = h501_pair();
  const HelicalGeometry g = helical_geometry(h);
  const double kappa = 1.5e10;
  const FaceStiffness face = FaceStiffness::uniform(h, kappa);
  const HelicalMesh mesh(h, face);
  // k'_L = kappa_t cos(beta_b) per unit length of contact line.
  const double k_line = kappa * std::cos(g.base_helix_angle_rad);
  for (int i = 0; i < 41; ++i) {
    const double theta = -0.2 + 0.013 * i;
    CHECK(relative_difference(mesh.stiffness_face(Region::n1, theta),
                              k_line * mesh.contact_line_length(Region::n1, theta)) < 1e-12);
    for (int slices : {1, 7, 32}) {
      CHECK(relative_difference(
                mesh.stiffness_slices(Region::n2, theta, slices),
                k_line * mesh.contact_line_length_slices(Region::n2, theta, slices)) < 1e-12);
    }
  }
  // Route A is piecewise constant in X0, with steps where a slice's midpoint
  // crosses S or E: its Fourier coefficients exactly, against A_n(N).
  const double p = g.transverse_base_pitch_m;
  const double x_pitch = mesh.mid_face_position_m(Region::n1, 0.0, 0);
  const double rb1 = mesh.base_radius1_m();
  for (int slices : {1, 4, 8, 32}) {
    std::vector<double> cs;
    for (int j = 0; j < slices; ++j) {
      const double off = mesh.slice_offset_m(Region::n1, j, slices);
      cs.push_back(face.start_m() - off);
      cs.push_back(face.end_m() - off);
    }
    const std::vector<double> xs = breakpoints(cs, 0.0, p);
    std::vector<double> left(xs.size(), 0.0);
    std::vector<double> right(xs.size(), 0.0);
    for (std::size_t s = 0; s + 1 < xs.size(); ++s) {
      if (xs[s + 1] <= xs[s]) continue;
      const double mid = 0.5 * (xs[s] + xs[s + 1]);
      const double value = mesh.stiffness_slices(Region::n1, (mid - x_pitch) / rb1, slices);
      right[s] = value;
      left[s + 1] = value;
    }
    const double mean = fourier_piecewise_linear(xs, left, right, p, 0).real();
    const double mean_closed =
        k_line * g.face_width_m * g.transverse_contact_ratio / std::cos(g.base_helix_angle_rad);
    CAPTURE(slices);
    CHECK(relative_difference(mean, mean_closed) < 1e-12);
    for (int n = 1; n <= 4; ++n) {
      CAPTURE(n);
      const double amplitude =
          2.0 * std::abs(fourier_piecewise_linear(xs, left, right, p, n)) / mean_closed;
      CHECK(std::abs(amplitude - series_amplitude_slices(g.transverse_contact_ratio,
                                                         g.overlap_ratio, n, slices)) < 1e-10);
    }
  }
}

TEST_CASE("route B is the window average of the spur pair's mesh stiffness at width b") {
  // face-width: kappa_t = Ke / b of the transverse spur pair. The reference
  // Ke is mesh_stiffness's own quadrature (not the table), summed over the
  // spur pairs and averaged over W = eps_beta p_bt by Gauss-Legendre between
  // the steps of the spur curve.
  const GearPair h = h501_pair();
  const GearPair t = transverse_pair(h);
  const StiffnessModel model;  // yang-lin-1987
  const FaceStiffness face(h, model, HelicalHertz::face_width);
  const HelicalMesh mesh(h, face);
  const HelicalGeometry g = helical_geometry(h);
  const double p = g.transverse_base_pitch_m;
  const double w = g.face_width_m * std::tan(g.base_helix_angle_rad);
  const double start = face.start_m();
  const double end = face.end_m();
  const auto spur = [&](double x0) {
    double sum = 0.0;
    for (int k = -6; k <= 6; ++k) {
      const double x = x0 + k * p;
      if (x >= start && x <= end) sum += mesh_stiffness(t, x, model).ke;
    }
    return sum;
  };
  using Rule = boost::math::quadrature::gauss<double, 20>;
  for (double theta : {-0.031, 0.0, 0.0123, 0.047}) {
    const double x0 = mesh.mid_face_position_m(Region::n1, theta, 0);
    const std::vector<double> xs = breakpoints({start, end}, x0 - 0.5 * w, p);
    double integral = 0.0;
    for (std::size_t s = 0; s + 1 < xs.size(); ++s) {
      const double a = xs[s];
      const double b = std::min(xs[s + 1], x0 + 0.5 * w);
      if (b > a) integral += Rule::integrate(spur, a, b);
    }
    CAPTURE(theta);
    // Tolerance: the table's fit of Ke (1e-12 relative, docs/verification.md)
    // and the quadratures' 1e-12.
    CHECK(relative_difference(mesh.stiffness_face(Region::n1, theta), integral / w) < 1e-10);
  }
  // The mean over a mesh period, b C(X_EAP) / p_bt, is the spur pair's mean.
  double spur_integral = 0.0;
  const int pieces = 16;
  for (int i = 0; i < pieces; ++i) {
    const double a = start + (end - start) * i / pieces;
    const double b = start + (end - start) * (i + 1) / pieces;
    spur_integral +=
        Rule::integrate([&](double x) { return mesh_stiffness(t, x, model).ke; }, a, b);
  }
  CHECK(relative_difference(face.cumulative(end) * h.face_width_m, spur_integral) < 1e-10);
}

TEST_CASE("eps_beta an integer: route B constant for a named model") {
  for (int overlap : {1, 2}) {
    GearPair h = h501_pair();
    const HelicalGeometry g0 = helical_geometry(h);
    // b = eps_beta p_bt / tan(beta_b).
    h.face_width_m = overlap * g0.transverse_base_pitch_m / std::tan(g0.base_helix_angle_rad);
    const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
    const HelicalMesh mesh(h, face);
    const double reference = mesh.stiffness_face(Region::n1, 0.0);
    for (int i = 1; i < 23; ++i) {
      const double theta = 0.0047 * i;
      CHECK(relative_difference(mesh.stiffness_face(Region::n1, theta), reference) < 1e-12);
    }
  }
}

TEST_CASE("route A converges to route B at first order in N") {
  const GearPair h = h501_pair();
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double period = mesh.mesh_period_rad();
  std::vector<double> errors;
  for (int slices : {8, 16, 32, 64}) {
    double worst = 0.0;
    for (int i = 0; i < 1500; ++i) {
      const double theta = period * i / 1500.0;
      worst = std::max(worst, std::abs(mesh.stiffness_slices(Region::n1, theta, slices) -
                                       mesh.stiffness_face(Region::n1, theta)));
    }
    errors.push_back(worst);
  }
  // A slice enters whole: the largest pointwise difference is about one
  // slice's kappa_t b / N, halving with N (the bound allows the sampling's miss).
  for (std::size_t i = 0; i + 1 < errors.size(); ++i) {
    CAPTURE(errors[i]);
    CAPTURE(errors[i + 1]);
    CHECK(errors[i] / errors[i + 1] > 1.6);
    CHECK(errors[i] / errors[i + 1] < 2.5);
  }
}

TEST_CASE("normal backlash: j_bn = 2 B cos(beta_b) = j_t cos(alpha_n) cos(beta), and back") {
  const GearPair h = h501_pair();
  const HelicalGeometry g = helical_geometry(h);
  const double b = 0.05e-3;
  const double jbn = normal_backlash_m(g, b);
  // j_t on the reference circle: 2B along the transverse line of action over cos(alpha_t).
  const double jt = 2.0 * b / std::cos(g.transverse_pressure_angle_rad);
  CHECK(relative_difference(
            jbn, jt * std::cos(h.pressure_angle_rad) * std::cos(h.helix_angle_rad)) < 1e-14);
  CHECK(relative_difference(backlash_from_normal_m(g, jbn), b) < 1e-15);
}

TEST_CASE("K_Hbeta: the slice solver of a linear mismatch against ISO 6336-1's two branches") {
  // c 17 N/(mm um), b 20 mm; by hand: 10 um at 200 N/mm gives 1 + 170/400 = 1.425;
  // 30 um at 200 N/mm: 1 + 510/400 > 2, so sqrt(2 * 510 / 200) = sqrt(5.1);
  // 40 um at 100 N/mm: sqrt(2 * 680 / 100) = sqrt(13.6).
  const double c = 17e9;
  const double b = 20e-3;
  struct Case {
    double mismatch_m;
    double load_per_width;
    double by_hand;
  };
  for (const Case k : {Case{10e-6, 200e3, 1.425}, Case{30e-6, 200e3, std::sqrt(5.1)},
                       Case{40e-6, 100e3, std::sqrt(13.6)}}) {
    const double iso = iso6336_face_load_factor(k.mismatch_m, c, k.load_per_width);
    const double solver = face_load_factor_linear_gap(c, b, k.load_per_width * b, k.mismatch_m);
    CHECK(std::abs(iso - k.by_hand) < 1e-12);
    CHECK(std::abs(solver - k.by_hand) < 1e-12);
  }
}

TEST_CASE("the dynamics refuse a helical pair, naming gears.helix_angle") {
  SimulationCase c;
  c.gears = h501_pair();
  check_refused([&] { validate_run_keys(c); }, "gears.helix_angle", "never run as a spur pair");
  SimulationCase faulted = c;
  faulted.faults.emplace_back();
  check_refused([&] { natural_modes(faulted); }, "gears.helix_angle", "never run as a spur pair");
  check_refused([&] { MeshLayout(c.gears, CoastPhase::half_base_pitch); }, "gears.helix_angle",
                "never run as a spur pair");
  // The geometry itself is valid: its transverse section's relations hold.
  CHECK_NOTHROW(validate(c.gears));
}

// --- Lead modifications, misalignment and the loaded STE by slices ---------------------------

namespace {

// A helical pair whose transverse contact ratio is 2 to rounding (the addendum chosen by
// bisection on eps_alpha), so that every slice has exactly two pairs on the path at every
// angle: with a stiffness uniform per unit face width each slice is then a spring of 2 c db,
// the uncoupled foundation ISO 6336-1's K_Hbeta assumes.
GearPair integer_eps_alpha_pair() {
  GearPair p;
  p.teeth1 = 30;
  p.teeth2 = 45;
  p.module_m = 3e-3;
  p.pressure_angle_rad = 20.0 * degree;
  p.helix_angle_rad = 15.0 * degree;
  p.face_width_m = 30e-3;
  p.youngs_modulus_pa = 206e9;
  p.poisson_ratio = 0.3;
  double low = 1.0;
  double high = 1.4;
  for (int i = 0; i < 200 && high - low > 0.0; ++i) {
    p.addendum_coefficient = 0.5 * (low + high);
    (helical_geometry(p).transverse_contact_ratio < 2.0 ? low : high) = p.addendum_coefficient;
  }
  p.dedendum_coefficient = p.addendum_coefficient + 0.25;
  return p;
}

// F_bt / b.
double nominal_load(const GearPair& p, double torque) {
  return torque / helical_geometry(p).base_radius1_m / p.face_width_m;
}

}  // namespace

TEST_CASE("K_Hbeta of the slice model under a linear misalignment: ISO 6336-1's two branches") {
  const GearPair p = integer_eps_alpha_pair();
  const HelicalGeometry g = helical_geometry(p);
  REQUIRE(std::abs(g.transverse_contact_ratio - 2.0) < 1e-12);
  // ISO's c_gamma_beta per unit face width is the slices' 2 kappa (two pairs at every y).
  const double kappa = 8.5e9;  // N/m^2: c_gamma_beta = 17 N/(mm um)
  const double c = 2.0 * kappa;
  const FaceStiffness face = FaceStiffness::uniform(p, kappa);
  const int slices = 1000;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 5;
  const double b = p.face_width_m;
  // gamma_y alone: F_betay = b gamma_y cos(alpha_wt) on N1 (docs/helical.md).
  struct Case {
    double torque;
    double mismatch;
  };
  // 200 N/mm and 10 um: the linear branch (1 + 17 * 10 / 400 = 1.425); 30 um at 200 N/mm and
  // 40 um at 100 N/mm: the square-root branch.
  const double rb1 = g.base_radius1_m;
  for (const Case k :
       {Case{200e3 * b * rb1, 10e-6}, Case{200e3 * b * rb1, 30e-6}, Case{100e3 * b * rb1, 40e-6}}) {
    Modifications m;
    m.misalignment.gamma_y_rad = k.mismatch / (b * std::cos(g.working_pressure_angle_rad));
    const HelicalStaticTransmissionError ste =
        helical_static_transmission_error(p, m, k.torque, face, slices, options);
    CHECK_FALSE(ste.face_route);
    const double load = nominal_load(p, k.torque);
    const double iso = iso6336_face_load_factor(k.mismatch, c, load);
    // The slices sample the face at their mid-planes: the most loaded one, db/2 in from the
    // face end, sits c F_betay / (2 N) below the face end's load (the gap's slope times db/2),
    // which is exactly the difference in the linear branch and the first-order one in the
    // square-root branch, where the loaded width's discretisation adds O(1/N^2) (measured
    // 2e-7 and 7e-7 at N = 1000, below the bound K_Hbeta / N^2).
    const double first_order = iso - c * k.mismatch / (2.0 * slices) / load;
    const double second_order = iso > 2.0 ? iso / (1.0 * slices * slices) : 1e-12;
    CAPTURE(iso);
    for (const HelicalStePoint& point : ste.points) {
      CHECK(std::abs(point.face_load_factor - first_order) < second_order);
    }
    CHECK(std::abs(ste.face_load_factor - first_order) < second_order);
    // And so to ISO's own value as N grows: within its 1/N term.
    CHECK(std::abs(ste.face_load_factor - iso) < 1.01 * c * k.mismatch / (2.0 * slices) / load);
  }
}

TEST_CASE("a crowning and end reliefs symmetric about mid-face load the face symmetrically") {
  const GearPair p = integer_eps_alpha_pair();
  const FaceStiffness face = FaceStiffness::uniform(p, 8.5e9);
  Modifications m;
  m.gear1.lead.crowning_m = 6e-6;
  m.gear2.lead.crowning_m = 2e-6;
  for (GearModifications* gear : {&m.gear1, &m.gear2}) {
    gear->lead.end_relief_i_m = 5e-6;
    gear->lead.end_relief_ii_m = 5e-6;
    gear->lead.end_relief_i_length_m = 4e-3;
    gear->lead.end_relief_ii_length_m = 4e-3;
    gear->lead.end_relief_shape = ReliefShape::parabolic;
  }
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 16;
  const int slices = 40;
  const double torque = 150.0;
  const HelicalStaticTransmissionError ste =
      helical_static_transmission_error(p, m, torque, face, slices, options);
  const double b = p.face_width_m;
  const double scale = nominal_load(p, torque);
  for (const HelicalStePoint& point : ste.points) {
    for (int j = 0; j < slices; ++j) {
      const double w = point.load_per_width_n_per_m[static_cast<std::size_t>(j)];
      const double mirrored =
          point.load_per_width_n_per_m[static_cast<std::size_t>(slices - 1 - j)];
      CHECK(std::abs(w - mirrored) < 1e-12 * scale);
    }
    CHECK(std::abs(point.load_centre_m - 0.5 * b) < 1e-14 * b);
    // The crowning concentrates the load at mid-face.
    CHECK(point.face_load_factor > 1.1);
  }
}

TEST_CASE("the hand mirrors the face: w(y; right) = w(b - y; left) with mirrored lead gaps") {
  GearPair right = h501_pair();
  GearPair left = right;
  left.helix_hand = HelixHand::left;
  const StiffnessModel model;  // the default model, not uniform
  const FaceStiffness face_right(right, model, HelicalHertz::projected);
  const FaceStiffness face_left(left, model, HelicalHertz::projected);
  Modifications m;
  m.gear1.lead.crowning_m = 4e-6;
  m.gear1.lead.end_relief_i_m = 8e-6;
  m.gear1.lead.end_relief_i_length_m = 3e-3;
  Modifications mirrored = m;
  std::swap(mirrored.gear1.lead.end_relief_i_m, mirrored.gear1.lead.end_relief_ii_m);
  std::swap(mirrored.gear1.lead.end_relief_i_length_m, mirrored.gear1.lead.end_relief_ii_length_m);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 12;
  const int slices = 24;
  const HelicalStaticTransmissionError a =
      helical_static_transmission_error(right, m, 200.0, face_right, slices, options);
  const HelicalStaticTransmissionError c =
      helical_static_transmission_error(left, mirrored, 200.0, face_left, slices, options);
  const double scale = nominal_load(right, 200.0);
  REQUIRE(a.points.size() == c.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    CHECK(relative_difference(a.points[i].ste_m, c.points[i].ste_m) < 1e-13);
    for (int j = 0; j < slices; ++j) {
      CHECK(std::abs(a.points[i].load_per_width_n_per_m[static_cast<std::size_t>(j)] -
                     c.points[i].load_per_width_n_per_m[static_cast<std::size_t>(slices - 1 - j)]) <
            1e-12 * scale);
    }
  }
}

TEST_CASE("the loaded STE with modifications against a slice sum solved by bisection") {
  // The elements laid out here from the geometry alone (the plane of action of
  // docs/helical.md), each gap from the formulas of its "Lead modifications" section and the
  // profile gap of the spur pair's tip relief, and delta found by bisection on the carried
  // force, not by the sorted-gap solver.
  const GearPair p = h501_pair();
  const HelicalGeometry g = helical_geometry(p);
  const GearPair t = transverse_pair(p);
  const StiffnessModel model;
  const FaceStiffness face(p, model, HelicalHertz::projected);
  Modifications m;
  m.gear1.tip = {6e-6, 0.0, ReliefShape::linear};
  m.gear1.tip.diameter_m = 2.0 * tip_radius(t, Gear::one) - 2e-3;
  m.gear1.lead.crowning_m = 3e-6;
  m.gear2.lead.helix_slope_m = -4e-6;
  m.misalignment.gamma_x_rad = 2e-4;
  m.misalignment.gamma_y_rad = 1e-4;
  const int slices = 10;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 9;
  const double torque = 120.0;
  const HelicalStaticTransmissionError ste =
      helical_static_transmission_error(p, m, torque, face, slices, options);
  const double force = torque / g.base_radius1_m;
  const double b = p.face_width_m;
  const double db = b / slices;
  const double tan_bb = std::tan(g.base_helix_angle_rad);
  const double alpha = g.working_pressure_angle_rad;
  const ContactSegment segment = contact_segment(t);
  const ToothGaps profile(t, m);
  for (const HelicalStePoint& point : ste.points) {
    struct Element {
      double k;
      double gap;
      int slice;
    };
    std::vector<Element> elements;
    for (int k = -6; k <= 6; ++k) {
      for (int j = 0; j < slices; ++j) {
        const double y = (j + 0.5) * db;
        const double x = pitch_point_position(t) + g.base_radius1_m * point.theta1_rad +
                         k * g.transverse_base_pitch_m + (y - 0.5 * b) * tan_bb;
        if (x < segment.start_m || x > segment.end_m) continue;
        const double u = y / b - 0.5;
        const double lead = 3e-6 * 4.0 * u * u + (-4e-6) * u +
                            b * u * (2e-4 * std::sin(alpha) + 1e-4 * std::cos(alpha));
        elements.push_back({face.kappa(x) * db, profile.gap_m(Region::n1, k, x) + lead, j});
      }
    }
    const auto carried = [&](double delta) {
      double f = 0.0;
      for (const Element& e : elements) f += e.k * std::max(0.0, delta - e.gap);
      return f;
    };
    double low = -1e-3;
    double high = 1e-3;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (low + high);
      (carried(mid) < force ? low : high) = mid;
    }
    const double delta = 0.5 * (low + high);
    CHECK(point.elements == static_cast<int>(elements.size()));
    // Bisection to the doubles' resolution: the two deltas agree to rounding in the sums.
    CHECK(relative_difference(point.ste_m, delta) < 1e-12);
    std::vector<double> w(static_cast<std::size_t>(slices), 0.0);
    for (const Element& e : elements) {
      w[static_cast<std::size_t>(e.slice)] += e.k * std::max(0.0, delta - e.gap) / db;
    }
    for (int j = 0; j < slices; ++j) {
      CHECK(std::abs(point.load_per_width_n_per_m[static_cast<std::size_t>(j)] -
                     w[static_cast<std::size_t>(j)]) < 1e-9 * force / b);
    }
  }
}

TEST_CASE("no modifications: the face integral's F / K_B; equal gaps: F / K_A above the gap") {
  const GearPair p = h501_pair();
  const StiffnessModel model;
  const FaceStiffness face(p, model, HelicalHertz::projected);
  const HelicalMesh mesh(p, face);
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 20;
  const double torque = 200.0;
  const double force = torque / mesh.base_radius1_m();
  const HelicalStaticTransmissionError none =
      helical_static_transmission_error(p, Modifications{}, torque, face, 32, options);
  CHECK(none.face_route);
  for (const HelicalStePoint& point : none.points) {
    // Bit for bit: the route the dynamics takes without gaps.
    CHECK(point.ste_m == force / mesh.stiffness_face(Region::n1, point.theta1_rad));
    CHECK(point.kte_m == 0.0);
  }
  // Every tooth of the pinion 3 um thinner on each flank: every element's gap 3 um, all in
  // contact, delta = 3 um + F / K_A with route A's slice sum.
  Modifications thinner;
  thinner.gear1.thickness_m.assign(static_cast<std::size_t>(p.teeth1), 3e-6);
  const HelicalStaticTransmissionError shifted =
      helical_static_transmission_error(p, thinner, torque, face, 32, options);
  CHECK_FALSE(shifted.face_route);
  for (const HelicalStePoint& point : shifted.points) {
    const double k_a = mesh.stiffness_slices(Region::n1, point.theta1_rad, 32);
    CHECK(relative_difference(point.ste_m, 3e-6 + force / k_a) < 1e-13);
    CHECK(relative_difference(point.effective_stiffness_n_per_m, k_a) < 1e-13);
  }
}

TEST_CASE("lead keys: a spur pair refuses them by name, an end relief longer than b is refused") {
  GearPair spur = h501_pair();
  spur.helix_angle_rad = 0.0;
  Modifications m;
  m.misalignment.gamma_x_rad = 1e-4;
  check_refused([&] { validate_modifications(spur, m); }, "modifications.misalignment_x",
                "slice model of a helical pair");
  Modifications relief;
  relief.gear2.lead.end_relief_ii_m = 5e-6;
  relief.gear2.lead.end_relief_ii_length_m = 30e-3;
  check_refused([&] { validate_modifications(h501_pair(), relief); },
                "modifications.end_relief_ii_length2", "(0, b]");
  check_refused(
      [&] { helical_static_transmission_error(spur, Modifications{}, 100.0, StiffnessModel{}); },
      "gears.helix_angle", "spur STE");
  // 4096 slices at 100000 angles would hold 4e8 slice loads: refused before any work, naming
  // the most points, floor(1e7 / 4096) = 2441.
  StiffnessModel fine;
  fine.face_slices = 4096;
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 100000;
  check_refused(
      [&] {
        helical_static_transmission_error(h501_pair(), Modifications{}, 100.0, fine, options);
      },
      "points", "at most 2441 per mesh period with model.face_slices = 4096");
}

namespace {

// A helical run of H501 in the torsional model: no friction (a helical run
// refuses it), balanced constant torques T1 and T2 = -T1 z2/z1 (Rb2/Rb1 =
// z2/z1 in every section), rolling at w1, no Hertzian damping unless asked.
SimulationCase helical_run(const GearPair& pair, double t1_n_m, double w1_rad_s, double end_s) {
  SimulationCase c;
  c.name = "helical";
  c.gears = pair;
  c.model.friction_coefficient = 0.0;
  c.torque1.constant_n_m = t1_n_m;
  c.torque2.constant_n_m = -t1_n_m * pair.teeth2 / pair.teeth1;
  c.initial.w1_rad_per_s = w1_rad_s;
  c.initial.w2_rad_per_s = w1_rad_s * pair.teeth1 / pair.teeth2;
  c.integrator.end_time_s = end_s;
  return c;
}

// The summed table of the loaded pairs of `line` at theta1, as the run places them.
double table_sum(const MeshLayout& layout, const StiffnessTable& table, Region line,
                 double theta1_rad) {
  const double reference = layout.reference_m(line, theta1_rad);
  const LoadedRange range = layout.loaded(reference);
  double sum = 0.0;
  for (int j = 0; j < range.count; ++j) {
    sum += table.stiffness(layout.position_m(reference, range.k_first + j));
  }
  return sum;
}

}  // namespace

TEST_CASE("dynamics: the extended pair table summed over the loaded pairs is route B") {
  // Route B (HelicalMesh::stiffness_face, C(X) by Gauss-Legendre) is checked
  // above against the spur pair's window average; here the table a run reads,
  // one per tooth pair over [X_SAP - W/2, X_EAP + W/2], placed by MeshLayout
  // on the swept section, must sum to it at every angle on both lines.
  for (const HelicalHertz hertz : {HelicalHertz::projected, HelicalHertz::face_width}) {
    for (const HelixHand hand : {HelixHand::right, HelixHand::left}) {
      GearPair h = h501_pair();
      h.helix_hand = hand;
      StiffnessModel model;
      model.helical_hertz = hertz;
      const FaceStiffness face(h, model, hertz);
      const HelicalMesh mesh(h, face);
      const StiffnessTable table = helical_pair_table(h, model);
      const GearPair swept = swept_transverse_pair(h);
      const MeshLayout layout(swept, CoastPhase::half_base_pitch);
      // The segment is W/2 wider at each end, W = b tan(beta_b).
      const double w = h.face_width_m * std::tan(mesh.base_helix_angle_rad());
      CHECK(relative_difference(layout.end_m() - layout.start_m(),
                                face.end_m() - face.start_m() + w) < 1e-13);
      const double period = mesh.mesh_period_rad();
      double worst = 0.0;
      for (const Region line : {Region::n1, Region::n2}) {
        for (int i = 0; i < 97; ++i) {
          const double theta = period * (i / 97.0 - 3.0);
          worst = std::max(worst, relative_difference(table_sum(layout, table, line, theta),
                                                      mesh.stiffness_face(line, theta)));
        }
      }
      // Tolerance: the table's degree-7 fit of a smooth K_pair on 64 pieces
      // per part (the spur table's 1e-12 bound, docs/verification.md).
      CHECK(worst < 1e-10);
      // The mean a run's damper sees: b C(X_EAP) / p_bt, exact for route B.
      SimulationCase c;
      c.gears = h;
      c.model.stiffness = model;
      const double mean = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
      CHECK(relative_difference(mean_mesh_stiffness_n_per_m(dynamics_case(c), table), mean) <
            1e-10);
    }
  }
}

TEST_CASE("dynamics: helix angle 0 runs the spur case itself") {
  SimulationCase c;
  CHECK(dynamics_case(c).gears == c.gears);
  CHECK(swept_transverse_pair(c.gears) == c.gears);
  CHECK(pair_contact_segment(c.gears).start_m == contact_segment(c.gears).start_m);
  CHECK(pair_contact_segment(c.gears).end_m == contact_segment(c.gears).end_m);
}

TEST_CASE("dynamics: eps_beta = 1 holds the static deflection T1 / (Rb1 K) exactly") {
  // eps_beta an integer: each point of the path is covered by the same number
  // of contact lines, so K is constant (7.4); balanced constant torques then
  // hold a pair started at its static deflection there, with no ripple.
  GearPair h = h501_pair();
  const HelicalGeometry g0 = helical_geometry(h);
  const auto run = [&](const GearPair& pair) {
    const FaceStiffness face(pair, StiffnessModel{}, HelicalHertz::projected);
    const HelicalMesh mesh(pair, face);
    // The closed form: K = b C(X_EAP) / p_bt, the mean, at every angle.
    const double k = pair.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
    const double t1 = 200.0;
    SimulationCase c = helical_run(pair, t1, 200.0, 2.0 * 2.0 * pi_ / (pair.teeth1 * 200.0));
    c.model.damping_update = DampingUpdate::off;
    const double rb1 = mesh.base_radius1_m();
    const double rb2 = rb1 * pair.teeth2 / pair.teeth1;
    const double deflection = t1 / (rb1 * k);
    c.initial.theta2_rad = -(c.gears.backlash_m + deflection) / rb2;
    RunControl control;
    control.keep_series = true;
    const SimulationResult r = simulate(c, control);
    double lo = 1e300;
    double hi = -1e300;
    for (const SeriesRow& row : r.series) {
      lo = std::min(lo, row.delta_m);
      hi = std::max(hi, row.delta_m);
    }
    // No impact beyond the contact the run starts in.
    CHECK(struck_impacts(r).empty());
    return std::array<double, 3>{lo / deflection - 1.0, hi / deflection - 1.0, 0.0};
  };
  h.face_width_m = g0.transverse_base_pitch_m / std::tan(g0.base_helix_angle_rad);
  const std::array<double, 3> integer = run(h);
  CAPTURE(integer[0]);
  CAPTURE(integer[1]);
  // Tolerance: K is constant to the table's fit (1e-10), which the run
  // holds. An integer eps_beta makes a pair's leaving and the next pair's
  // kink one instant: their event values cross within a few ulps in one grid
  // step. Were the step cut where the first turns negative with the second
  // exactly 0, the next step would have no bracket for it and would change
  // its mode only at the grid step's end: 45 ns of a stale pair here, an
  // impulse (1/2) (dK_pair/dX) v delta tau^2 leaving an undamped oscillation
  // of 2.5e-8 of the deflection (measured before earliest_event carried the
  // cut past such a zero). 1e-9: ten times the table's fit, forty times below
  // that oscillation.
  CHECK(std::abs(integer[0]) < 1e-9);
  CHECK(std::abs(integer[1]) < 1e-9);
  // H501's own face (eps_beta 0.54) ripples: the check above could fail.
  const std::array<double, 3> ripple = run(h501_pair());
  CHECK(ripple[1] - ripple[0] > 1e-3);
}

TEST_CASE("dynamics: the ledger closes, pairs enter without a stored-energy jump, impacts") {
  // A light load started in the backlash with the pinion gaining on the
  // wheel: the teeth strike on N1, bounce, and the mesh ripples. Lagrangian
  // mesh force: a route-B pair enters and leaves with Ke = 0, so the stored
  // energy never jumps (7.10), unlike a spur pair's.
  SimulationCase c = helical_run(h501_pair(), 5.0, 200.0, 3.0 * 2.0 * pi_ / (20 * 200.0));
  c.model.mesh_force = MeshForce::lagrangian;
  const GearPair t = transverse_pair(c.gears);
  c.initial.w1_rad_per_s = 200.0 * (1.0 + 1e-2);
  c.initial.w2_rad_per_s = 200.0 * c.gears.teeth1 / c.gears.teeth2;
  const SimulationSummary s = simulate(c).summary;
  CHECK(s.impacts_n1 >= 1);
  REQUIRE(s.stored_energy_jumps_j);
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  MESSAGE("helical: residual " << s.ledger_residual_max_j << " J of " << throughput << " J, jumps "
                               << *s.stored_energy_jumps_j << " J, impacts " << s.impacts_n1
                               << " + " << s.impacts_n2);
  CHECK(*s.stored_energy_jumps_j < 1e-12 * throughput);
  // As for spur (test_dynamics): RK4 at h w ~ 0.01 closes to ~1e-8 of the throughput.
  CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
  CHECK(s.damping_loss_j > 0.0);
  static_cast<void>(t);
  // The adaptive integrator takes its first step from the pair table.
  SimulationCase adaptive = c;
  adaptive.integrator.kind = IntegratorKind::adaptive;
  const SimulationSummary a = simulate(adaptive).summary;
  CHECK(a.impacts_n1 >= 1);
  CHECK(a.ledger_residual_max_j < 1e-6 * throughput);
}

TEST_CASE("dynamics: what a helical run refuses, naming the key") {
  SimulationCase c = helical_run(h501_pair(), 50.0, 100.0, 1e-3);
  // Friction runs under the constant law (section Friction on a helical pair, below); another
  // law is refused.
  SimulationCase friction = c;
  friction.model.friction_law = FrictionLaw::benedict_kelley;
  friction.model.benedict_kelley.viscosity_pa_s = 0.05;
  friction.model.benedict_kelley.roughness_m = 0.5e-6;
  check_refused([&] { check_run(friction); }, "model.friction_law", "helical");
  SimulationCase wide = c;
  wide.gears.face_width_m = 0.2;  // eps_beta about 4.7
  check_refused([&] { check_run(wide); }, "gears.face_width", "eps_gamma");
  // A table for another pair (the spur one of the same fields) is refused.
  check_refused([&] { check_run(c, std::make_shared<const StiffnessTable>(c.gears)); }, "table",
                "another gear pair");
}

// --- The planar model: the transverse section on elastic bearings --------------------------

namespace {

// a from inv(a) = tan(a) - a by Newton, the test's own.
double involute_angle_by_hand(double inv) {
  double a = std::cbrt(3.0 * inv);
  for (int i = 0; i < 60; ++i) a -= (std::tan(a) - a - inv) / std::pow(std::tan(a), 2);
  return a;
}

// A helical pair on isotropic elastic bearings of stiffness kb, balanced constant torques T1,
// no Hertzian damping.
SimulationCase planar_helical(const GearPair& pair, double kb, double t1_n_m, double w1_rad_s,
                              double end_s) {
  SimulationCase c = helical_run(pair, t1_n_m, w1_rad_s, end_s);
  c.model.damping_update = DampingUpdate::off;
  c.bearings.kind = BearingKind::elastic;
  c.bearings.gear1.stiffness_x_n_per_m = kb;
  c.bearings.gear2.stiffness_x_n_per_m = kb;
  return c;
}

}  // namespace

TEST_CASE("planar: balanced torques hold the bearing force F_bt along n1 and F_a by hand") {
  // eps_beta = 1 (b = p_bt / tan(beta_b)): K is constant (7.4), so the pair started at its
  // static equilibrium on the bearings stays there. By hand, from the normal-section inputs:
  // alpha_t = atan(tan(alpha_n) / cos(beta)), r_b1 = z1 m_n cos(alpha_t) / (2 cos(beta)),
  // tan(beta_b) = tan(beta) cos(alpha_t), inv(alpha_wt) = inv(alpha_t) + 2 tan(alpha_n)
  // (x1 + x2) / (z1 + z2), n1 = (sin(alpha_wt), cos(alpha_wt)). F = T1 / r_b1 pushes the
  // wheel along n1 and the pinion along -n1, so the bearings, each k_b u, hold the pinion's
  // centre at u1 = -F n1 / k_b, the wheel's at +F n1 / k_b, and exert +F n1 on the pinion; the
  // angles then close s_d = r_b1 theta1 - r_b2 theta2 + (u1 - u2) . n1 to B + F / K. The axial
  // force on a right-hand pinion driving on N1 is +F tan(beta_b) along +z, the moments about +y
  // -r_w1 F_a1 and -r_w2 F_a1, r_w = r_b / cos(alpha_wt).
  GearPair h = h501_pair();
  const double beta = h.helix_angle_rad;
  const double an = h.pressure_angle_rad;
  const double at = std::atan(std::tan(an) / std::cos(beta));
  const double rb1 = h.teeth1 * h.module_m * std::cos(at) / (2.0 * std::cos(beta));
  const double rb2 = rb1 * h.teeth2 / h.teeth1;
  const double tan_bb = std::tan(beta) * std::cos(at);
  h.face_width_m = 2.0 * pi_ * rb1 / h.teeth1 / tan_bb;
  const double awt = involute_angle_by_hand(
      std::tan(at) - at +
      2.0 * std::tan(an) * (h.profile_shift1 + h.profile_shift2) / (h.teeth1 + h.teeth2));
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double t1 = 200.0;
  const double kb = 1e9;
  const double f = t1 / rb1;
  // Two mesh periods at 1000 rad/s, so that pairs enter and leave.
  const SimulationCase c = planar_helical(h, kb, t1, 1000.0, 2.0 * 2.0 * pi_ / (20 * 1000.0));
  const SimulationCase d = dynamics_case(c);
  PlanarState start = planar_initial_state(d);
  const double n1x = std::sin(awt);
  const double n1y = std::cos(awt);
  start.x1_m = -f * n1x / kb;
  start.y1_m = -f * n1y / kb;
  start.x2_m = f * n1x / kb;
  start.y2_m = f * n1y / kb;
  start.theta1_rad = 0.0;
  start.theta2_rad = -(c.gears.backlash_m + f / k + 2.0 * f / kb) / rb2;
  RunControl control;
  control.keep_series = true;
  const SimulationResult r = simulate_planar(d, *run_table(c), planar_mounting(d), start, control);
  REQUIRE(r.planar_series.size() > 100);
  const double fa = f * tan_bb;
  const double rw1 = rb1 / std::cos(awt);
  const double rw2 = rb2 / std::cos(awt);
  double most = 0.0;  // the largest relative departure of any force or moment from its hand value
  const auto off = [&](double value, double reference) {
    most = std::max(most, std::fabs(value - reference) / std::fabs(reference));
  };
  for (const PlanarRow& row : r.planar_series) {
    off(row.drive_force_n, f);
    off(row.bearing_fx1_n, f * n1x);
    off(row.bearing_fy1_n, f * n1y);
    off(row.bearing_fx2_n, -f * n1x);
    off(row.bearing_fy2_n, -f * n1y);
    off(row.axial_force1_n, fa);
    off(row.axial_force2_n, -fa);
    off(row.tilting_moment1_n_m, -rw1 * fa);
    off(row.tilting_moment2_n_m, -rw2 * fa);
  }
  MESSAGE("planar helical static: largest relative departure " << most << ", F_a " << fa << " N");
  // K constant to the table's fit (1e-10) and the events' rounding (the torsional run holds its
  // deflection to 5e-8, above): 1e-6 leaves room, and a wrong sign, lever or tan(beta_b) is
  // off by O(1).
  CHECK(most < 1e-6);
  REQUIRE(r.summary.helical_thrust);
  CHECK(relative_difference(r.summary.helical_thrust->axial_force_max_n, fa) < 1e-6);
  CHECK(relative_difference(r.summary.helical_thrust->tilting_moment1_max_n_m, rw1 * fa) < 1e-6);
  CHECK(relative_difference(r.summary.helical_thrust->tilting_moment2_max_n_m, rw2 * fa) < 1e-6);
}

TEST_CASE("planar: stiff bearings approach the torsional helical run, by eps = k (1/kb1 + 1/kb2)") {
  // H501 (eps_beta 0.54: the face ripples) under balanced torques, started at the mean
  // stiffness's static deflection, no Hertzian damping, by the torsional model and by the planar
  // one on bearings of kb each way. The bearings' springs are in series with the mesh's along
  // the line of action (eps = k (1/kb1 + 1/kb2), k the mean): quasi-statically they open the
  // angles' deflection r_b1 theta1 - r_b2 theta2 by eps F / k over the torsional one, and
  // started on unloaded bearings the planar pair oscillates about that by as much again.
  const GearPair h = h501_pair();
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double rb1 = mesh.base_radius1_m();
  const double rb2 = rb1 * h.teeth2 / h.teeth1;
  const double t1 = 200.0;
  const double f = t1 / rb1;
  const auto start = [&](SimulationCase& c) {
    c.integrator.step_s = 2e-8;
    c.initial.theta2_rad = -(c.gears.backlash_m + f / k) / rb2;
  };
  const double end = 2e-4;
  SimulationCase torsional = helical_run(h, t1, 1000.0, end);
  torsional.model.damping_update = DampingUpdate::off;
  start(torsional);
  RunControl control;
  control.keep_series = true;
  const SimulationResult t = simulate(torsional, control);
  std::vector<double> scaled;
  for (const double kb : {1e11, 1e12}) {
    SimulationCase planar = planar_helical(h, kb, t1, 1000.0, end);
    start(planar);
    const SimulationResult p = simulate(planar, control);
    REQUIRE(p.series.size() == t.series.size());
    REQUIRE(p.summary.impacts_n1 == 1);  // the contact it starts in, never left
    double most = 0.0;
    for (std::size_t i = 0; i < t.series.size(); ++i) {
      const SeriesRow& a = p.series[i];
      const SeriesRow& b = t.series[i];
      most = std::max(most, std::fabs((rb1 * a.theta1_rad - rb2 * a.theta2_rad) -
                                      (rb1 * b.theta1_rad - rb2 * b.theta2_rad)));
    }
    const double eps = k * 2.0 / kb;
    scaled.push_back(most / (eps * f / k));
  }
  MESSAGE("largest deflection difference over eps F / k: " << scaled[0] << " at 1e11 N/m, "
                                                           << scaled[1] << " at 1e12 N/m");
  // Measured 3.04 and 2.78: the offset eps F / k, the oscillation about it and the ripple's
  // response, whose phase the mesh mode's shift by about eps / 2 moves over the run. At least
  // the offset (a model without the bearings' compliance would give 0) and at most 4 of it;
  // the difference itself falls tenfold per tenfold stiffer bearing (10 scaled[0] /
  // scaled[1], measured 11.0) within that phase's 15 %.
  for (const double x : scaled) {
    CHECK(x > 1.0);
    CHECK(x < 4.0);
  }
  CHECK(std::fabs(10.0 * scaled[0] / scaled[1] - 10.0) < 1.5);
}

TEST_CASE("planar: the mirrored hand flips the axial force and the moments only") {
  // Route B's pair table does not depend on the hand, so the run is the same to the bit; the
  // hand mirrors the contact lines, which flips sigma and with it F_a and both moments.
  SimulationCase right = planar_helical(h501_pair(), 1e9, 50.0, 1000.0, 3e-4);
  right.initial.w1_rad_per_s = 1000.0 * (1.0 + 1e-2);  // strikes, then rolls on both flanks
  SimulationCase left = right;
  left.gears.helix_hand = HelixHand::left;
  RunControl control;
  control.keep_series = true;
  const SimulationResult a = simulate(right, control);
  const SimulationResult b = simulate(left, control);
  REQUIRE(a.planar_series.size() == b.planar_series.size());
  bool same = true;
  bool flipped = true;
  bool loaded = false;
  for (std::size_t i = 0; i < a.planar_series.size(); ++i) {
    const PlanarRow& p = a.planar_series[i];
    const PlanarRow& q = b.planar_series[i];
    same = same && p.state.x1_m == q.state.x1_m && p.state.y2_m == q.state.y2_m &&
           p.state.theta2_rad == q.state.theta2_rad && p.drive_force_n == q.drive_force_n &&
           p.coast_force_n == q.coast_force_n && p.bearing_fy1_n == q.bearing_fy1_n;
    flipped = flipped && q.axial_force1_n == -p.axial_force1_n &&
              q.axial_force2_n == -p.axial_force2_n &&
              q.tilting_moment1_n_m == -p.tilting_moment1_n_m &&
              q.tilting_moment2_n_m == -p.tilting_moment2_n_m;
    loaded = loaded || p.axial_force1_n != 0.0;
  }
  CHECK(same);
  CHECK(flipped);
  CHECK(loaded);
  CHECK(a.summary.impacts_n1 >= 1);
}

TEST_CASE("modes: a helical pair's torsional mode at its mean route-B stiffness") {
  // By hand: discs of the transverse reference radius r = z m_n / (2 cos beta)
  // and width b, J = rho pi r^4 b / 2, Rb = r cos(alpha_t), m_e = 1 / (Rb1^2
  // / J1 + Rb2^2 / J2); the mean stiffness b C(X_EAP) / p_bt of route B.
  SimulationCase c;
  c.gears = h501_pair();
  const GearPair& h = c.gears;
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double cos_beta = std::cos(h.helix_angle_rad);
  const double alpha_t = std::atan(std::tan(h.pressure_angle_rad) / cos_beta);
  double inverse_mass = 0.0;
  for (const int z : {h.teeth1, h.teeth2}) {
    const double r = z * h.module_m / (2.0 * cos_beta);
    const double j = h.density_kg_m3 * pi_ * std::pow(r, 4) * h.face_width_m / 2.0;
    const double rb = r * std::cos(alpha_t);
    inverse_mass += rb * rb / j;
  }
  const Modes modes = natural_modes(c);
  double highest = 0.0;
  for (const NaturalMode& m : modes.modes) {
    if (!m.rigid) highest = std::max(highest, m.angular_frequency);
  }
  // Tolerance: the mean's quadrature (1e-12) and the eigen solver's rounding.
  CHECK(relative_difference(highest, std::sqrt(k * inverse_mass)) < 1e-9);
}

TEST_CASE("modes: on stiff bearings the helical pair's mesh mode tends to sqrt(k_mean / m_e)") {
  // The planar modes of the transverse section on bearings of kb each way: the bearings'
  // springs in series with the mesh's lower the mesh mode's w^2 by about eps = k (1/kb1 +
  // 1/kb2) of it (the centres' own modes, far above, barely shift it), so its relative
  // departure from the torsional sqrt(k_mean / m_e) (checked above) falls tenfold per tenfold
  // stiffer bearing and stays below eps.
  SimulationCase c;
  c.gears = h501_pair();
  const Modes torsional = natural_modes(c);
  double reference = 0.0;
  for (const NaturalMode& m : torsional.modes) {
    if (!m.rigid) reference = std::max(reference, m.angular_frequency);
  }
  const FaceStiffness face(c.gears, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(c.gears, face);
  const double k = c.gears.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  std::vector<double> departures;
  for (const double kb : {1e11, 1e12}) {
    SimulationCase planar = c;
    planar.bearings.kind = BearingKind::elastic;
    planar.bearings.gear1.stiffness_x_n_per_m = kb;
    planar.bearings.gear2.stiffness_x_n_per_m = kb;
    const Modes modes = natural_modes(planar);
    // The planar mode nearest the torsional one.
    double nearest = 0.0;
    for (const NaturalMode& m : modes.modes) {
      if (!m.rigid && std::fabs(m.angular_frequency - reference) < std::fabs(nearest - reference)) {
        nearest = m.angular_frequency;
      }
    }
    const double departure = (reference - nearest) / reference;
    MESSAGE("kb " << kb << " N/m: mesh mode " << nearest << " rad/s, torsional " << reference
                  << ", departure " << departure << ", eps " << 2.0 * k / kb);
    CHECK(departure > 0.0);
    CHECK(departure < 2.0 * k / kb);
    departures.push_back(departure);
  }
  CHECK(std::fabs(departures[0] / departures[1] - 10.0) < 1.0);
}

TEST_CASE("the run pool runs a helical case as simulate does, to the bit") {
  SimulationCase c = helical_run(h501_pair(), 50.0, 100.0, 0.5e-3);
  const SimulationSummary direct = simulate(c).summary;
  RunPool pool(1);
  const SimulationSummary pooled = pool.submit(c, false).get().summary;
  CHECK(pooled.steps == direct.steps);
  CHECK(pooled.damping_loss_j == direct.damping_loss_j);
  CHECK(pooled.final_w1_rad_per_s == direct.final_w1_rad_per_s);
  CHECK(pooled.max_penetration_m == direct.max_penetration_m);
}

TEST_CASE("steady sweep: eps_beta = 1 is the transverse pair at constant K, point by point") {
  // eps_beta an integer: the helical mesh stiffness is the constant K = b C(X_EAP) / p_bt at
  // every angle (checked above), so the helical pair's steady states must be those of its
  // transverse section run with model.mesh_stiffness = "constant" at that K. A sinusoidal
  // pinion torque at the mesh frequency, swept in amplitude from a linear response to one
  // that leaves the drive flank and strikes it, the damper zeta = 0.05 and D off in both.
  GearPair h = h501_pair();
  const HelicalGeometry g0 = helical_geometry(h);
  h.face_width_m = g0.transverse_base_pitch_m / std::tan(g0.base_helix_angle_rad);
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double w1 = 150.0;
  SimulationCase helical = helical_run(h, 0.0, w1, 1e-3);
  helical.model.mesh_damping_ratio = 0.05;
  helical.model.damping_update = DampingUpdate::off;
  helical.torque1 = Torque{};
  helical.torque1.kind = Torque::Kind::sinusoidal;
  helical.torque1.mean_n_m = 100.0;
  helical.torque1.angular_frequency_rad_per_s = h.teeth1 * w1;
  helical.torque2.constant_n_m = -100.0 * h.teeth2 / h.teeth1;
  SimulationCase spur = helical;
  // The transverse section as a spur pair (without the face advance W, which only places the
  // pairs of a time-varying table).
  spur.gears = transverse_pair(h);
  spur.model.mesh_stiffness = MeshStiffnessMode::constant;
  spur.model.constant_mesh_stiffness_n_per_m = k;
  SteadySweepSpec spec;
  spec.vary = "torque1.amplitude";
  spec.from_si = 20.0;
  spec.to_si = 400.0;
  spec.points = 3;
  spec.directions = {SweepDirection::up};
  spec.threads = 1;
  spec.base = helical;
  const SteadySweep a = run_steady_sweep(spec);
  spec.base = spur;
  const SteadySweep b = run_steady_sweep(spec);
  REQUIRE(a.rows.size() == 3);
  REQUIRE(b.rows.size() == 3);
  bool struck = false;
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    const SteadyPoint& p = a.rows[i].point;
    const SteadyPoint& q = b.rows[i].point;
    CAPTURE(i);
    REQUIRE(p.converged);
    REQUIRE(q.converged);
    CHECK(p.regime == q.regime);
    CHECK(p.period == q.period);
    CHECK(*p.impacts_drive_per_period == *q.impacts_drive_per_period);
    CHECK(*p.impacts_coast_per_period == *q.impacts_coast_per_period);
    struck = struck || *p.impacts_drive_per_period > 0.0;
    // Tolerance: the two runs take different RK4 steps (the helical one also resolves the
    // mesh period, the constant one its contact period alone) and the helical one cuts its
    // steps where pairs enter and leave (an integer eps_beta makes the sum constant, not each
    // pair); RK4 at >= 128 steps a contact period errs by ~1e-7 of the motion, the
    // periodicity test by 1e-6 B (B = 50 um here): 1e-6 of the amplitude plus 1e-11 m.
    const double amplitude = *q.dte_amplitude_m;
    MESSAGE("point " << i << ": amplitude " << amplitude << " m, helical - spur: mean "
                     << *p.dte_mean_m - *q.dte_mean_m << " m, amplitude "
                     << *p.dte_amplitude_m - amplitude << " m, s_min " << *p.s_min_m - *q.s_min_m
                     << " m");
    const double bound = 1e-6 * amplitude + 1e-11;
    CHECK(std::abs(*p.dte_mean_m - *q.dte_mean_m) < bound);
    CHECK(std::abs(*p.dte_amplitude_m - amplitude) < bound);
    CHECK(std::abs(*p.s_min_m - *q.s_min_m) < bound);
    CHECK(std::abs(*p.s_max_m - *q.s_max_m) < bound);
    // The mesh frequency is z1 times the mean speed each run measured over its period, which
    // the different steps move by ~1e-9 (a constant-torque share of the motion's RK4 error).
    CHECK(relative_difference(*p.mesh_frequency_hz, *q.mesh_frequency_hz) < 1e-8);
  }
  // The last point strikes: the comparison covers the nonlinear regime too.
  CHECK(struck);
}

TEST_CASE("steady state: a helical pair's refusals name the key, as simulate's") {
  SimulationCase c = helical_run(h501_pair(), 50.0, 100.0, 1e-3);
  const std::shared_ptr<const StiffnessTable> table = run_table(c);
  SimulationCase misaligned = c;
  misaligned.modifications.misalignment.gamma_x_rad = 1e-4;
  check_refused([&] { (void)GearPeriodMap(misaligned, *table, SteadySettings{}); }, "modifications",
                "route A");
  SteadySweepSpec spec;
  spec.base = c;
  spec.base.model.friction_coefficient = 0.04;
  spec.vary = "initial.w1";
  spec.from_si = 100.0;
  spec.to_si = 200.0;
  spec.points = 2;
  spec.threads = 1;
  // A helical pair's friction runs in simulate; a steady state refuses friction for every pair.
  check_refused([&] { run_steady_sweep(spec); }, "model.friction_coefficient", "steady state");
}

TEST_CASE("planar steady state of H501: stiff bearings approach the torsional one, by eps") {
  // The steady orbit of the period-map case below (balanced 200 N*m at 150 rad/s, D off: the
  // rippling stiffness's period-1 response, no impact), found by running, on rigid bearings (the
  // torsional model) and on bearings of kb each way damped at zeta_b = 0.05 of each centre's mode
  // (the planar model, its 10-coordinate Poincare state). The bearings are in series with the mesh
  // along the line of action (eps = k (1/kb1 + 1/kb2), k the mean): k becomes k / (1 + eps), w_n
  // moves by eps / 2 and a linear oscillator's amplitude by at most eps / (4 zeta) relative; twice
  // that for the ripple's parametric share (as the spur planar period map's rigid-bearing limit,
  // test_gear_floquet): a bound falling tenfold per decade. The Poincare sample's s, in the planar
  // model, adds the bearings' deflections along the line of action, F_b (1/kb1 + 1/kb2): at F_b = F
  // = T1 / r_b1 that is eps F / k. At the sample the bearing force is the mesh force, F plus the
  // ripple's dynamic force, about m_e Omega^2 A (Omega the mesh frequency, A the torsional
  // amplitude; 4 times that for the ripple's harmonics), and the mesh's own deflection moves by the
  // amplitude's share (the bound above).
  const GearPair h = h501_pair();
  SimulationCase c = helical_run(h, 200.0, 150.0, 1e-3);
  const double zeta = 0.1;  // twice the period map case's: half the periods to converge
  c.model.mesh_damping_ratio = zeta;
  c.model.damping_update = DampingUpdate::off;
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double rb1 = helical_geometry(h).base_radius1_m;
  const double f = 200.0 / rb1;
  c.initial.theta1_rad = (h.backlash_m + f / k) / rb1;
  const std::shared_ptr<const StiffnessTable> table = run_table(c);
  const double m_e = effective_mass_kg(dynamics_case(c).gears);
  const double omega = h.teeth1 * 150.0;
  const SteadyPoint rigid = find_steady_state(c, *table, SteadySettings{});
  REQUIRE(rigid.verdict == PeriodicityVerdict::periodic);
  const double amplitude_t = *rigid.dte_amplitude_m;
  std::vector<double> changes;
  for (const double kb : {1e11, 1e12}) {
    CAPTURE(kb);
    SimulationCase planar = c;
    planar.bearings.kind = BearingKind::elastic;
    planar.bearings.gear1.stiffness_x_n_per_m = kb;
    planar.bearings.gear2.stiffness_x_n_per_m = kb;
    const PlanarMounting mounting = planar_mounting(dynamics_case(planar));
    planar.bearings.gear1.damping_x_n_s_per_m = 2.0 * 0.05 * std::sqrt(kb * mounting.mass_kg[0]);
    planar.bearings.gear2.damping_x_n_s_per_m = 2.0 * 0.05 * std::sqrt(kb * mounting.mass_kg[1]);
    const SteadyPoint p = find_steady_state(planar, *table, SteadySettings{});
    REQUIRE(p.verdict == PeriodicityVerdict::periodic);
    CHECK(p.period == 1);
    CHECK(p.regime == Regime::no_impact);
    REQUIRE(p.poincare.size() == 1);
    // The planar Poincare state: s, s', the four centre coordinates and their speeds.
    CHECK(poincare_state(planar, p.final_state).size() == 10);
    const double eps = 2.0 * k / kb;
    const double change = std::fabs(*p.dte_amplitude_m - amplitude_t) / amplitude_t;
    const double bound = 2.0 * eps / (4.0 * zeta);
    const double mean_shift = p.poincare[0].s_m - rigid.poincare[0].s_m;
    MESSAGE("kb " << kb << " N/m: amplitude " << *p.dte_amplitude_m << " m against " << amplitude_t
                  << " m, relative " << change << " (bound " << bound
                  << "); sample's s shift over eps F / k " << mean_shift / (eps * f / k)
                  << " (bound 1 +- " << 4.0 * m_e * omega * omega * amplitude_t / f + bound << ")");
    CHECK(change <= bound);
    // A model without the bearings' compliance in series would give a shift of 0.
    const double dynamic = 4.0 * m_e * omega * omega * amplitude_t / f;
    CHECK(std::fabs(mean_shift / (eps * f / k) - 1.0) <= dynamic + bound);
    changes.push_back(change);
  }
  MESSAGE("amplitude change at 1e11 over that at 1e12 N/m: " << changes[0] / changes[1]);
}

TEST_CASE("period map of H501: Newton's fixed point is the steady state's sample") {
  // H501 (eps_beta 0.54: a rippling stiffness) loaded by balanced constant torques, zeta =
  // 0.05, no Hertzian damping: the teeth stay in contact, the steady state is a period-1 orbit
  // of the mesh period, found by running (find_steady_state) and independently by Newton on
  // the period map from the mean stiffness's static deflection. They agree to the periodicity
  // tolerance (1e-6 of B and B w_n) times the contraction factor of periodicity.hpp (below 10
  // at zeta = 0.05), as for the spur pair (test_steady_state).
  const GearPair h = h501_pair();
  SimulationCase c = helical_run(h, 200.0, 150.0, 1e-3);
  c.model.mesh_damping_ratio = 0.05;
  c.model.damping_update = DampingUpdate::off;
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double rb1 = helical_geometry(h).base_radius1_m;
  const double deflection = h.backlash_m + 200.0 / (rb1 * k);
  c.initial.theta1_rad = deflection / rb1;
  const std::shared_ptr<const StiffnessTable> table = run_table(c);
  const SteadyPoint point = find_steady_state(c, *table, SteadySettings{});
  REQUIRE(point.verdict == PeriodicityVerdict::periodic);
  CHECK(point.period == 1);
  CHECK(point.regime == Regime::no_impact);
  const GearPeriodMap map(c, *table, SteadySettings{});
  ShootingSettings shooting;
  shooting.scale = map.scale();
  const PeriodicOrbit orbit = find_periodic_orbit(map, Eigen::Vector2d(deflection, 0.0), shooting);
  REQUIRE(point.poincare.size() == 1);
  const double ds = std::abs(point.poincare[0].s_m - orbit.fixed_point[0]) / map.scale()[0];
  const double dv = std::abs(point.poincare[0].s_rate_m_s - orbit.fixed_point[1]) / map.scale()[1];
  MESSAGE("helical steady sample against the shot fixed point: "
          << ds << " B, " << dv << " B w_n; amplitude " << *point.dte_amplitude_m);
  CHECK(ds <= 1e-5);
  CHECK(dv <= 1e-5);
  // The orbit ripples (the check above compares a moving orbit, not a rest point).
  CHECK(*point.dte_amplitude_m > 1e-3 * (deflection - h.backlash_m));
}

// Faults on a helical tooth (docs/helical.md, Faults): a band of the face in
// the fault's state, the face integral of the slices.
namespace {

// The pinion's radius at fraction u of H501's transverse path of contact.
double h501_pinion_radius(double u) {
  const GearPair t = transverse_pair(h501_pair());
  const ContactSegment s = contact_segment(t);
  return radius_at_roll_distance(base_radius(t, Gear::one), s.start_m + u * (s.end_m - s.start_m));
}

// A 0.2 mm deep spall on the pinion's drive flank over 40 % to 65 % of the
// path, over [y0, y0 + width) of the face.
ToothState h501_spall(double y0, double width) {
  ToothState s;
  s.kind = ToothKind::spall;
  s.spall.start_radius_m = h501_pinion_radius(0.40);
  s.spall.end_radius_m = h501_pinion_radius(0.65);
  s.spall.width_m = width;
  s.spall.depth_m = 0.2e-3;
  s.face_start_m = y0;
  return s;
}

ToothState h501_crack(double depth_m) {
  ToothState s;
  s.kind = ToothKind::root_crack;
  s.crack.profile = CrackProfile::uniform;
  s.crack.depth_m = depth_m;
  s.crack.angle_rad = 45.0 * degree;
  return s;
}

std::vector<ToothFault> pinion_tooth0(const ToothState& state) {
  ToothFault f;
  f.gear = Gear::one;
  f.tooth = 0;
  f.state = state;
  return {f};
}

// The helical tables of a case with these faults, as a run builds them.
MeshTables helical_tables(const GearPair& h, const std::vector<ToothFault>& faults,
                          const StiffnessModel& model = {}) {
  return MeshTables(swept_transverse_pair(h), model, faults,
                    std::make_shared<const StiffnessTable>(helical_pair_table(h, model)));
}

// Pinion tooth 0 meets wheel tooth 0 on N1 and wheel tooth 1 on N2 (gcd(20, 30) = 10).
const StiffnessTable& tooth0_table(const MeshTables& tables, Region line) {
  const StiffnessTable* t = tables.table_of_teeth(0, line == Region::n1 ? 0 : 1, line);
  REQUIRE(t != nullptr);
  return *t;
}

}  // namespace

TEST_CASE("helical faults: a crack of depth 0 is the healthy pair, its run bit for bit") {
  const GearPair h = h501_pair();
  const MeshTables tables = helical_tables(h, pinion_tooth0(h501_crack(0.0)));
  for (const Region line : {Region::n1, Region::n2}) {
    CHECK(&tooth0_table(tables, line) == &tables.healthy());
  }
  SimulationCase healthy = helical_run(h, 5.0, 200.0, 2.0 * 2.0 * pi_ / (20 * 200.0));
  healthy.initial.w1_rad_per_s *= 1.0 + 1e-2;
  SimulationCase cracked = healthy;
  cracked.faults = pinion_tooth0(h501_crack(0.0));
  RunControl control;
  control.keep_series = true;
  const SimulationResult a = simulate(healthy, control);
  const SimulationResult b = simulate(cracked, control);
  REQUIRE(a.series.size() == b.series.size());
  bool same = true;
  for (std::size_t i = 0; i < a.series.size(); ++i) {
    same = same && a.series[i].delta_m == b.series[i].delta_m &&
           a.series[i].w1_rad_per_s == b.series[i].w1_rad_per_s &&
           a.series[i].normal_force_n == b.series[i].normal_force_n;
  }
  CHECK(same);
  CHECK(a.summary.impacts_n1 == b.summary.impacts_n1);
}

TEST_CASE("helical faults: the losses of two half-face bands add up to the whole face's") {
  // Uncoupled slices are parallel springs: a band's loss is the integral of
  // kappa_t - kappa_fault over its slices on the path, so that the bands
  // [0, b/2) and [b/2, b) lose what the whole face does, at every position.
  const GearPair h = h501_pair();
  const double b = h.face_width_m;
  const MeshTables whole = helical_tables(h, pinion_tooth0(h501_spall(0.0, b)));
  const MeshTables first = helical_tables(h, pinion_tooth0(h501_spall(0.0, 0.5 * b)));
  const MeshTables second = helical_tables(h, pinion_tooth0(h501_spall(0.5 * b, 0.5 * b)));
  TipChip chip;
  chip.radius_m = h501_pinion_radius(0.8);
  ToothState chipped;
  chipped.kind = ToothKind::tip_chip;
  chipped.chip = chip;
  chipped.chip.width_m = b;
  const MeshTables chip_whole = helical_tables(h, pinion_tooth0(chipped));
  chipped.chip.width_m = 0.3 * b;
  const MeshTables chip_first = helical_tables(h, pinion_tooth0(chipped));
  chipped.face_start_m = 0.3 * b;
  chipped.chip.width_m = 0.7 * b;
  const MeshTables chip_second = helical_tables(h, pinion_tooth0(chipped));
  const StiffnessTable& healthy = whole.healthy();
  const double lo = healthy.domain_start_m();
  const double hi = healthy.domain_end_m();
  double k_most = 0.0;
  for (int i = 0; i <= 400; ++i)
    k_most = std::max(k_most, healthy.stiffness(lo + (hi - lo) * i / 400.0));
  double worst = 0.0;
  double largest_loss = 0.0;
  for (const Region line : {Region::n1, Region::n2}) {
    const std::array<const MeshTables*, 3> spall{&whole, &first, &second};
    const std::array<const MeshTables*, 3> chips{&chip_whole, &chip_first, &chip_second};
    for (const auto& set : {spall, chips}) {
      for (int i = 1; i < 1000; ++i) {
        const double x = lo + (hi - lo) * (i + 0.37) / 1000.0;
        const double k = healthy.stiffness(x);
        const double loss_whole = k - tooth0_table(*set[0], line).stiffness(x);
        const double loss_parts = (k - tooth0_table(*set[1], line).stiffness(x)) +
                                  (k - tooth0_table(*set[2], line).stiffness(x));
        worst = std::max(worst, std::abs(loss_whole - loss_parts) / k_most);
        largest_loss = std::max(largest_loss, loss_whole / k_most);
      }
    }
  }
  MESSAGE("helical faults: bands add up to " << worst << " of the largest K, loss up to "
                                             << largest_loss);
  // Tolerance: each of the four tables fits its function to about 1e-12 of
  // the largest Ke (the spur table's bound, docs/verification.md); 1e-10 leaves room
  // for the section tables they integrate.
  CHECK(worst < 1e-10);
  // The faults take a visible share of the pair (the check above could fail).
  CHECK(largest_loss > 0.05);
}

TEST_CASE("helical faults: a fault across the whole face against a by-hand slice sum") {
  // Route A by hand: N slices of width b/N, slice j at X + sigma (y_j - b/2)
  // tan(beta_b) on N1 (its mirror on N2), each with the per-width stiffness of
  // the transverse spur pair with the same fault across its face (its table
  // from MeshTables of that spur pair, Hertz projected by cos(beta_b)).
  const GearPair h = h501_pair();
  const GearPair t = transverse_pair(h);
  const HelicalGeometry g = helical_geometry(h);
  const double b = h.face_width_m;
  const double tan_bb = std::tan(g.base_helix_angle_rad);
  const double cos_bb = std::cos(g.base_helix_angle_rad);
  const ContactSegment path = contact_segment(t);
  const int n = 4096;
  const double db = b / n;
  for (const ToothState& state : {h501_crack(0.6e-3), h501_spall(0.0, b)}) {
    const MeshTables helical = helical_tables(h, pinion_tooth0(state));
    const MeshTables spur(t, StiffnessModel{}, pinion_tooth0(state));
    double worst = 0.0;
    double bound = 0.0;
    for (const Region line : {Region::n1, Region::n2}) {
      const StiffnessTable& section = tooth0_table(spur, line);
      const auto kappa = [&](double x) {
        const Compliances c = section.compliance(x);
        if (!(c.total_m_per_n() > 0.0)) return 0.0;
        const double hertz = c.of(Term::hertz);
        return 1.0 / (b * (c.total_m_per_n() - hertz + hertz / cos_bb));
      };
      double kappa_most = 0.0;
      for (int i = 0; i <= 1000; ++i) {
        kappa_most =
            std::max(kappa_most, kappa(path.start_m + (path.end_m - path.start_m) * i / 1000.0));
      }
      const double sign = line == Region::n1 ? 1.0 : -1.0;
      // Positions where the whole line lies on the path: the slices' midpoint
      // rule is second order there but for the spall's two edges, where one
      // slice at most is on the wrong side of each (kappa_most db apiece).
      for (int i = 0; i <= 50; ++i) {
        const double x =
            path.start_m + 0.5 * b * tan_bb + (path.end_m - path.start_m - b * tan_bb) * i / 50.0;
        double sum = 0.0;
        for (int j = 0; j < n; ++j) {
          const double at = x + sign * ((j + 0.5) * db - 0.5 * b) * tan_bb;
          if (at >= path.start_m && at <= path.end_m) sum += kappa(at) * db;
        }
        const double k = tooth0_table(helical, line).stiffness(x);
        worst = std::max(worst, std::abs(k - sum) / sum);
        const double edges = state.kind == ToothKind::spall ? 2.0 * kappa_most * db : 0.0;
        bound = std::max(bound, (edges + 1e-7 * sum) / sum);
      }
    }
    MESSAGE("helical faults: " << to_string(state.kind) << " against the slice sum: " << worst
                               << " (bound " << bound << ")");
    // Tolerance: for the crack (smooth kappa) the midpoint rule's (db / L)^2
    // ~ 1e-7 of the sum; for the spall one slice per edge, about 2 / N of the
    // band's share (bound above).
    CHECK(worst < bound);
  }
}

TEST_CASE("helical faults: a run with a cracked and a spalled tooth closes its ledger") {
  // A light load from the backlash, the pinion gaining: the teeth strike with
  // pinion tooth 0 cracked across the face and tooth 1 spalled over part of
  // it. The faulted pairs' Ke is a face integral, continuous: no stored-energy
  // jump, as for the healthy pair (Lagrangian force).
  const GearPair h = h501_pair();
  SimulationCase c = helical_run(h, 5.0, 200.0, 3.0 * 2.0 * pi_ / (20 * 200.0));
  c.model.mesh_force = MeshForce::lagrangian;
  c.initial.w1_rad_per_s = 200.0 * (1.0 + 1e-2);
  c.initial.w2_rad_per_s = 200.0 * c.gears.teeth1 / c.gears.teeth2;
  SimulationCase faulted = c;
  faulted.faults = pinion_tooth0(h501_crack(0.6e-3));
  ToothFault spalled;
  spalled.tooth = 1;
  spalled.state = h501_spall(0.3 * h.face_width_m, 0.5 * h.face_width_m);
  faulted.faults.push_back(spalled);
  const SimulationSummary healthy = simulate(c).summary;
  const SimulationSummary s = simulate(faulted).summary;
  CHECK(s.impacts_n1 >= 1);
  REQUIRE(s.stored_energy_jumps_j);
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  MESSAGE("helical faulted: residual " << s.ledger_residual_max_j << " J of " << throughput
                                       << " J, jumps " << *s.stored_energy_jumps_j);
  CHECK(*s.stored_energy_jumps_j < 1e-12 * throughput);
  // As the healthy helical run above: RK4 at h w ~ 0.01 closes to ~1e-8.
  CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
  // The faults reach the run (the checks above could pass without them).
  CHECK(s.max_penetration_m != healthy.max_penetration_m);
}

TEST_CASE("helical faults: what a faulted helical case refuses, naming the key") {
  SimulationCase c = helical_run(h501_pair(), 50.0, 100.0, 1e-3);
  SimulationCase beyond = c;
  beyond.faults = pinion_tooth0(h501_spall(0.02, 0.005));
  check_refused([&] { check_run(beyond); }, "faults[0].face_start", "within the face");
  SimulationCase spur;
  spur.faults = pinion_tooth0(h501_spall(0.001, 0.002));
  spur.faults[0].state.spall.start_radius_m = 0.0;
  check_refused([&] { check_tooth_faults(spur.gears, StiffnessModel{}, spur.faults); },
                "faults[0].face_start", "spur");
}

// A crack whose depth varies across a helical tooth's face (docs/helical.md,
// Faults): sub-bands of uniform depth by the midpoint rule in y.
namespace {

// H501's pinion tooth 0 with a partial-width crack of depth q0 over [0, W_c).
ToothState h501_partial_crack(double q0_m, double width_m) {
  ToothState s = h501_crack(q0_m);
  s.crack.profile = CrackProfile::partial_width;
  s.crack.width_m = width_m;
  return s;
}

// The per-width stiffness of a slice of the transverse spur pair t at X1 = x
// with the pinion tooth in `state` across its face, by mesh_stiffness (the
// cracked tooth integrated whole: a route independent of the tables), Hertz
// projected by cos(beta_b) as for a helical slice.
double slice_kappa(const GearPair& t, double x, const ToothState& state, double cos_bb) {
  const Compliances c =
      mesh_stiffness(t, x, StiffnessModel{}, state, ToothState{}, CrackFlank::loaded).included;
  const double hertz = c.of(Term::hertz);
  return 1.0 / (t.face_width_m * (c.total_m_per_n() - hertz + hertz / cos_bb));
}

}  // namespace

TEST_CASE("helical crack across the face: a partial-width crack against a by-hand slice sum") {
  // The table cuts [0, W_c) into n = model.face_slices = 8 sub-bands, each a
  // uniform crack of q at its middle. By hand: m = 8 slices per sub-band,
  // slice j at depth q(y_j) = q0 sqrt((W_c - y_j) / W_c), its per-width
  // stiffness from the spur section by mesh_stiffness (the cracked tooth
  // integrated whole); the loss against the healthy face is
  // sum_j db (kappa_t - kappa_q(y_j)) at the slice's place on the line. The
  // loss of the code's table is K_healthy - K_cracked.
  // Bound: kappa falls with q (the next tests) and q with y, so on sub-band i,
  // whose depths run from q_i at its start down to q_i+1 at its end, both
  // the sub-band's uniform depth and every hand slice's lie in [q_i+1, q_i]:
  // code and hand sum both lie between the sums at the sub-bands' end depths
  // (the stiffest) and at their start depths (the softest). Their distance,
  // sum_j db (kappa(q_i+1) - kappa(q_i)) at each slice's place, bounds the
  // difference at every position; 5 % more covers that bracket's own
  // midpoint sum at db, and 1e-10 K the tables' fit.
  const GearPair h = h501_pair();
  const GearPair t = transverse_pair(h);
  const HelicalGeometry g = helical_geometry(h);
  const double b = h.face_width_m;
  const double tan_bb = std::tan(g.base_helix_angle_rad);
  const double cos_bb = std::cos(g.base_helix_angle_rad);
  const ContactSegment path = contact_segment(t);
  const double q0 = 0.6e-3;
  const double wc = 0.6 * b;
  const ToothState crack = h501_partial_crack(q0, wc);
  StiffnessModel model;
  model.face_slices = 8;
  const int n = model.face_slices;
  const int m = 8;
  const double h_sub = wc / n;
  const double db = h_sub / m;
  const MeshTables helical = helical_tables(h, pinion_tooth0(crack), model);
  const StiffnessTable& healthy = helical.healthy();
  const auto depth = [&](double y) { return q0 * std::sqrt((wc - y) / wc); };
  const auto at_depth = [&](double q) { return q > 0.0 ? h501_crack(q) : ToothState{}; };
  double worst = 0.0;
  double worst_share = 0.0;
  double most_loss = 0.0;
  for (const Region line : {Region::n1, Region::n2}) {
    const double sign = line == Region::n1 ? 1.0 : -1.0;
    for (int i = 0; i <= 3; ++i) {
      const double x =
          path.start_m + 0.5 * b * tan_bb + (path.end_m - path.start_m - b * tan_bb) * i / 3.0;
      double loss = 0.0;
      double bracket = 0.0;
      for (int j = 0; j < n * m; ++j) {
        const double y = (j + 0.5) * db;
        const double at = x + sign * (y - 0.5 * b) * tan_bb;
        if (!(at >= path.start_m && at <= path.end_m)) continue;
        const int sub = j / m;
        const double stiff = slice_kappa(t, at, at_depth(depth((sub + 1) * h_sub)), cos_bb);
        const double soft = slice_kappa(t, at, at_depth(depth(sub * h_sub)), cos_bb);
        loss += (slice_kappa(t, at, ToothState{}, cos_bb) -
                 slice_kappa(t, at, at_depth(depth(y)), cos_bb)) *
                db;
        bracket += (stiff - soft) * db;
      }
      const double k = healthy.stiffness(x);
      const double code_loss = k - tooth0_table(helical, line).stiffness(x);
      const double bound = 1.05 * bracket + 1e-10 * k;
      worst = std::max(worst, std::abs(code_loss - loss) / bound);
      worst_share = std::max(worst_share, std::abs(code_loss - loss) / loss);
      most_loss = std::max(most_loss, loss / k);
    }
  }
  MESSAGE("helical partial-width crack (8 sub-bands): |loss - slice sum| up to "
          << worst << " of the bound, " << worst_share << " of the loss; loss up to " << most_loss
          << " of K");
  CHECK(worst < 1.0);
  // The crack takes a visible share of K (the check above could fail).
  CHECK(most_loss > 1e-3);
}

TEST_CASE("helical crack across the face: full-width with q2 = q0 is the uniform crack") {
  // q(z) = sqrt((q2^2 - q0^2) z / b + q0^2) = q0 at every z: every sub-band
  // has depth q0, they are one band, the uniform crack's; both tables to the
  // bit (compared to rounding of the largest K).
  const GearPair h = h501_pair();
  const double q0 = 0.6e-3;
  ToothState full = h501_crack(q0);
  full.crack.profile = CrackProfile::full_width;
  full.crack.end_depth_m = q0;
  const MeshTables uniform = helical_tables(h, pinion_tooth0(h501_crack(q0)));
  const MeshTables graded = helical_tables(h, pinion_tooth0(full));
  const StiffnessTable& healthy = uniform.healthy();
  const double lo = healthy.domain_start_m();
  const double hi = healthy.domain_end_m();
  double worst = 0.0;
  double k_most = 0.0;
  for (const Region line : {Region::n1, Region::n2}) {
    for (int i = 0; i <= 1000; ++i) {
      const double x = lo + (hi - lo) * i / 1000.0;
      const double k = tooth0_table(uniform, line).stiffness(x);
      k_most = std::max(k_most, k);
      worst = std::max(worst, std::abs(tooth0_table(graded, line).stiffness(x) - k));
    }
  }
  MESSAGE("helical full-width crack at q2 = q0 against the uniform one: " << worst << " N/m");
  CHECK(worst <= 1e-14 * k_most);
}

TEST_CASE("helical crack across the face: a graded crack loses less than the uniform q0") {
  // Every slice of a partial-width (W_c = b) or a full-width crack (q2 =
  // 0.3 q0) is cracked at most q0 deep, and a deeper crack is softer at every
  // contact, so each loses less than the uniform crack of depth q0 and more
  // than nothing, at every position, on both lines. Tolerance: the tables'
  // fit, 1e-10 of the largest K.
  const GearPair h = h501_pair();
  const double b = h.face_width_m;
  const double q0 = 0.6e-3;
  StiffnessModel model;
  model.face_slices = 4;
  ToothState full = h501_crack(q0);
  full.crack.profile = CrackProfile::full_width;
  full.crack.end_depth_m = 0.3 * q0;
  const MeshTables uniform = helical_tables(h, pinion_tooth0(h501_crack(q0)));
  const MeshTables partial = helical_tables(h, pinion_tooth0(h501_partial_crack(q0, b)), model);
  const MeshTables graded = helical_tables(h, pinion_tooth0(full), model);
  const StiffnessTable& healthy = uniform.healthy();
  const double lo = healthy.domain_start_m();
  const double hi = healthy.domain_end_m();
  double k_most = 0.0;
  for (int i = 0; i <= 400; ++i)
    k_most = std::max(k_most, healthy.stiffness(lo + (hi - lo) * i / 400.0));
  double above = -1e300;  // the most a graded loss exceeds the uniform one
  double below = 1e300;   // the least graded loss
  double partial_share = 0.0;
  for (const Region line : {Region::n1, Region::n2}) {
    for (int i = 1; i < 1000; ++i) {
      const double x = lo + (hi - lo) * (i + 0.37) / 1000.0;
      const double k = healthy.stiffness(x);
      const double lu = k - tooth0_table(uniform, line).stiffness(x);
      for (const MeshTables* set : {&partial, &graded}) {
        const double loss = k - tooth0_table(*set, line).stiffness(x);
        above = std::max(above, (loss - lu) / k_most);
        below = std::min(below, loss / k_most);
      }
      partial_share =
          std::max(partial_share, (k - tooth0_table(partial, line).stiffness(x)) / k_most);
    }
  }
  MESSAGE("helical graded cracks: loss above the uniform one by at most "
          << above << " of K, least loss " << below << ", partial-width loss up to "
          << partial_share);
  CHECK(above < 1e-10);
  CHECK(below > -1e-10);
  CHECK(partial_share > 1e-3);
}

TEST_CASE("helical crack across the face: a run with a partial-width crack closes its ledger") {
  // As the run with a uniform crack above: a light load from the backlash, the
  // pinion gaining, Lagrangian force; the sub-bands' face integral is
  // continuous, so no stored-energy jump.
  const GearPair h = h501_pair();
  SimulationCase c = helical_run(h, 5.0, 200.0, 3.0 * 2.0 * pi_ / (20 * 200.0));
  c.model.mesh_force = MeshForce::lagrangian;
  // Two sub-bands: the ledger is checked here, not the depth rule (a short sanitized pass).
  c.model.stiffness.face_slices = 2;
  c.initial.w1_rad_per_s = 200.0 * (1.0 + 1e-2);
  c.initial.w2_rad_per_s = 200.0 * c.gears.teeth1 / c.gears.teeth2;
  SimulationCase faulted = c;
  faulted.faults = pinion_tooth0(h501_partial_crack(0.6e-3, 0.7 * h.face_width_m));
  check_run(faulted);
  const SimulationSummary healthy = simulate(c).summary;
  const SimulationSummary s = simulate(faulted).summary;
  CHECK(s.impacts_n1 >= 1);
  REQUIRE(s.stored_energy_jumps_j);
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  MESSAGE("helical partial-width crack run: residual " << s.ledger_residual_max_j << " J of "
                                                       << throughput << " J, jumps "
                                                       << *s.stored_energy_jumps_j);
  CHECK(*s.stored_energy_jumps_j < 1e-12 * throughput);
  // RK4 at h w ~ 0.01 closes to ~1e-8, as the healthy and uniform-crack runs.
  CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
  CHECK(s.max_penetration_m != healthy.max_penetration_m);
}

TEST_CASE("helical faults on elastic bearings: stiff bearings approach the torsional run") {
  // The planar run reads the same faulted tables as the torsional one (one mesh
  // of the transverse section). As the healthy case above: H501 under
  // balanced torques from the mean stiffness's static deflection, with pinion
  // tooth 0 cracked over 70 % of the face (partial-width) and tooth 1 spalled
  // over part of it; the bearings' springs in series with the mesh's open the
  // deflection by eps F / k, eps = k (1/kb1 + 1/kb2), k the healthy mean, and
  // the pair oscillates about that by as much again: between 1 and 4 times
  // eps F / k at kb = 1e12 N/m.
  const GearPair h = h501_pair();
  const FaceStiffness face(h, StiffnessModel{}, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const double k = h.face_width_m * face.cumulative(face.end_m()) / mesh.base_pitch_m();
  const double rb1 = mesh.base_radius1_m();
  const double rb2 = rb1 * h.teeth2 / h.teeth1;
  const double t1 = 200.0;
  const double f = t1 / rb1;
  std::vector<ToothFault> faults = pinion_tooth0(h501_partial_crack(0.6e-3, 0.7 * h.face_width_m));
  ToothFault spalled;
  spalled.tooth = 1;
  spalled.state = h501_spall(0.3 * h.face_width_m, 0.5 * h.face_width_m);
  faults.push_back(spalled);
  const auto start = [&](SimulationCase& c) {
    c.integrator.step_s = 2e-8;
    c.initial.theta2_rad = -(c.gears.backlash_m + f / k) / rb2;
    c.model.stiffness.face_slices = 4;
  };
  const double end = 2e-4;
  SimulationCase healthy = helical_run(h, t1, 1000.0, end);
  healthy.model.damping_update = DampingUpdate::off;
  start(healthy);
  SimulationCase torsional = healthy;
  torsional.faults = faults;
  SimulationCase planar = planar_helical(h, 1e12, t1, 1000.0, end);
  start(planar);
  planar.faults = faults;
  RunControl control;
  control.keep_series = true;
  const SimulationResult t = simulate(torsional, control);
  const SimulationResult u = simulate(healthy, control);
  const SimulationResult p = simulate(planar, control);
  REQUIRE(p.series.size() == t.series.size());
  REQUIRE(u.series.size() == t.series.size());
  REQUIRE(p.summary.impacts_n1 == 1);  // the contact it starts in, never left
  const auto deflection = [&](const SeriesRow& r) {
    return rb1 * r.theta1_rad - rb2 * r.theta2_rad;
  };
  double most = 0.0;
  double fault_most = 0.0;
  for (std::size_t i = 0; i < t.series.size(); ++i) {
    most = std::max(most, std::fabs(deflection(p.series[i]) - deflection(t.series[i])));
    fault_most = std::max(fault_most, std::fabs(deflection(t.series[i]) - deflection(u.series[i])));
  }
  const double eps = k * 2.0 / 1e12;
  const double scaled = most / (eps * f / k);
  MESSAGE("faulted helical planar run: largest deflection difference "
          << scaled
          << " of eps F / k; the "
             "faults move it by "
          << fault_most / (eps * f / k));
  CHECK(scaled > 1.0);
  CHECK(scaled < 4.0);
  // The faults move the run by more than the bearings do (the check could pass without them).
  CHECK(fault_most > most);
}

// --- Friction on a helical pair: route B's face sums ----------------------------------------

TEST_CASE("helical friction: the tabled face sums against a by-hand slice sum of spur frictions") {
  // Each slice j of a pair whose mid-face contact is at X is the spur pair at X_j = X + (y_j -
  // b/2) tan(beta_b): its load kappa_t(X_j) db delta, its sliding sign that of Vs(X_j) and its
  // arm X_j (docs/model.md (35)-(38)). The by-hand sum (midpoint rule, N slices, kappa_t from
  // FaceStiffness of the helical pair, not the section's table FaceFriction reads) against the
  // tabled primitives split at the sign change. The midpoint rule's error is first order here:
  // the line ends at the path's ends and the sign jumps inside a slice, each a step of one
  // slice's load, 1/N of the line's; bound 2/N.
  const GearPair h = h501_pair();
  const StiffnessModel model;
  const FaceStiffness face(h, model, HelicalHertz::projected);
  const HelicalMesh mesh(h, face);
  const GearPair swept = swept_transverse_pair(h);
  const FaceFriction friction(swept, model);
  const double lp = line_of_action_length(swept);
  const double tan_bb = std::tan(mesh.base_helix_angle_rad());
  const double b = h.face_width_m;
  const double w = b * tan_bb;
  const double xs = face.start_m();
  const double xe = face.end_m();
  CHECK(relative_difference(friction.start_m(), xs) < 1e-14);
  CHECK(relative_difference(friction.end_m(), xe) < 1e-14);
  const double x_pitch = pitch_point_position(swept);
  const int n = 20000;
  // (w1, w2, the centres' slide): rolling (Vs = 0 at the pitch point), the wheel lagging, a
  // slide of the centres, and turning backwards.
  const std::array<std::array<double, 3>, 4> speeds{{{100.0, 100.0 * 20.0 / 30.0, 0.0},
                                                     {100.0, 60.0, 0.0},
                                                     {100.0, 100.0 * 20.0 / 30.0, 0.4},
                                                     {-50.0, -50.0 * 20.0 / 30.0, 0.0}}};
  const std::array<double, 7> mids{xs - 0.4 * w,      xs + 0.1 * w, x_pitch - 0.3 * w, x_pitch,
                                   x_pitch + 0.2 * w, xe - 0.2 * w, xe + 0.45 * w};
  double worst = 0.0;
  for (const auto& v : speeds) {
    const double rate = v[0] + v[1];
    const double offset = sliding_speed(v[0], v[1], 0.0, lp) + v[2];
    for (const double x : mids) {
      double load = 0.0;
      double slip = 0.0;
      double arm = 0.0;
      for (int j = 0; j < n; ++j) {
        const double xj = x + ((j + 0.5) / n - 0.5) * b * tan_bb;
        if (xj < xs || xj > xe) continue;
        const double wj = face.kappa(xj) * b / n;
        const double sign = sliding_speed(v[0], v[1], xj, lp) + v[2] >= 0.0 ? 1.0 : -1.0;
        load += wj;
        slip += wj * sign;
        arm += wj * sign * xj;
      }
      const FaceSlip f = friction.slip(x, rate, offset);
      CAPTURE(x);
      CAPTURE(rate);
      CAPTURE(offset);
      // The face integral of kappa_t dy is that of kappa_t dX' over tan(beta_b): route B's K_pair.
      CHECK(relative_difference(f.weight_n_per_m / tan_bb, load) < 2.0 / n);
      CHECK(relative_difference(f.weight_n_per_m / tan_bb, mesh.pair_stiffness_face(x)) < 1e-9);
      CHECK(std::abs(f.slip - slip / load) < 2.0 / n);
      CHECK(std::abs(f.arm_m - arm / load) < 2.0 / n * xe);
      worst =
          std::max({worst, std::abs(f.slip - slip / load), std::abs(f.arm_m - arm / load) / xe});
    }
  }
  MESSAGE("helical friction: face sums against " << n << " slices, worst " << worst);
  // A line whose extent lies off the path: the spur pair's sign and arm at the path's end.
  const FaceSlip off = friction.slip(xe + 0.6 * w, 1.0, -x_pitch);
  CHECK(off.weight_n_per_m == 0.0);
  CHECK(off.slip == 1.0);
  CHECK(off.arm_m == xe);
}

namespace {

// A helical pair rolling under load from its static deflection (balanced torques, no Hertzian
// damping), with friction f, and the spur run of its transverse section: the same discs, the
// section's Ke. With helical_hertz = "face-width" kappa_t b is that Ke, so as W -> 0 route B's
// K_pair(X) tends to it and the face sums of friction to the spur pair's terms.
struct NarrowFace {
  double helical_friction_loss_j;
  double spur_friction_loss_j;
  double helical_w1;
  double spur_w1;
};
NarrowFace narrow_face_runs(double beta_rad, double f) {
  GearPair h = h501_pair();
  h.helix_angle_rad = beta_rad;
  const double t1 = 100.0;
  SimulationCase c = helical_run(h, t1, 200.0, 2.0 * pi_ / (20.0 * 200.0));
  c.model.stiffness.helical_hertz = HelicalHertz::face_width;
  c.model.damping_update = DampingUpdate::off;
  c.model.friction_coefficient = f;
  // Both torques unbalanced by friction alone: start at the static deflection of the mean K.
  const GearPair t = transverse_pair(h);
  SimulationCase spur = c;
  spur.gears = t;
  const double k = mean_mesh_stiffness_n_per_m(spur, StiffnessTable(t));
  c.initial.theta2_rad =
      -(h.backlash_m + t1 / (base_radius(t, Gear::one) * k)) / base_radius(t, Gear::two);
  spur.initial = c.initial;
  const SimulationSummary a = simulate(c).summary;
  const SimulationSummary s = simulate(spur).summary;
  return {a.friction_loss_j, s.friction_loss_j, a.final_w1_rad_per_s, s.final_w1_rad_per_s};
}

}  // namespace

TEST_CASE("helical friction: a narrow face (eps_beta -> 0) tends to the spur run of its section") {
  // W = b tan(beta_b) shrinks with beta: the helical run's friction loss and final speed tend
  // to the spur section's at first order in W (a contact line of length W averages the spur
  // terms over W). Measured: the friction losses 5.1e-3 apart at 2 deg, 5.2e-4 at 0.5 deg; the
  // final w1 0.39 and 0.13 rad/s apart (of 200 rad/s; an undamped ringing's phase). The check:
  // for 4 times smaller W the loss's difference falls at least 3 times and the speed's twice.
  const NarrowFace wide = narrow_face_runs(2.0 * degree, 0.08);
  const NarrowFace narrow = narrow_face_runs(0.5 * degree, 0.08);
  const double d_wide =
      relative_difference(wide.helical_friction_loss_j, wide.spur_friction_loss_j);
  const double d_narrow =
      relative_difference(narrow.helical_friction_loss_j, narrow.spur_friction_loss_j);
  const double v_wide = std::abs(wide.helical_w1 - wide.spur_w1);
  const double v_narrow = std::abs(narrow.helical_w1 - narrow.spur_w1);
  MESSAGE("narrow face: friction loss "
          << wide.helical_friction_loss_j << " / " << wide.spur_friction_loss_j << " J (2 deg), "
          << narrow.helical_friction_loss_j << " / " << narrow.spur_friction_loss_j
          << " J (0.5 deg); w1 " << v_wide << ", " << v_narrow << " rad/s apart");
  CHECK(wide.spur_friction_loss_j > 0.0);
  CHECK(d_narrow < d_wide / 3.0);
  CHECK(d_narrow < 1e-2);
  CHECK(v_narrow < v_wide / 2.0);
}

TEST_CASE("helical friction: the ledger closes with the friction loss, impacts included") {
  // H501 struck from the backlash as the ledger test above, now with f = 0.1: the friction
  // loss is the power f N times the load-weighted mean |Vs| along each line, which the
  // moments' arms must match for the ledger to close; without it the residual would be the
  // whole loss.
  SimulationCase c = helical_run(h501_pair(), 5.0, 200.0, 3.0 * 2.0 * pi_ / (20 * 200.0));
  c.model.mesh_force = MeshForce::lagrangian;
  c.model.friction_coefficient = 0.1;
  c.initial.w1_rad_per_s = 200.0 * (1.0 + 1e-2);
  c.initial.w2_rad_per_s = 200.0 * c.gears.teeth1 / c.gears.teeth2;
  const SimulationSummary s = simulate(c).summary;
  CHECK(s.impacts_n1 >= 1);
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  SimulationCase fine = c;
  fine.integrator.step_s = 0.5 * c.integrator.step_s;
  const SimulationSummary h2 = simulate(fine).summary;
  MESSAGE("helical friction: friction loss "
          << s.friction_loss_j << " J, residual " << s.ledger_residual_max_j << " J (h), "
          << h2.ledger_residual_max_j << " J (h/2) of " << throughput << " J");
  CHECK(s.friction_loss_j > 1e3 * s.ledger_residual_max_j);
  // As the frictionless run above: RK4 at h w ~ 0.01 closes to ~1e-8 of the throughput.
  CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
  // The same loss at half the step, to the integrator's order.
  CHECK(relative_difference(h2.friction_loss_j, s.friction_loss_j) < 1e-6);
}

TEST_CASE("helical friction: refused with faults, a smoothed sign and in a train, by key") {
  SimulationCase c = helical_run(h501_pair(), 50.0, 100.0, 1e-3);
  c.model.friction_coefficient = 0.05;
  SimulationCase faulted = c;
  faulted.faults = pinion_tooth0(h501_crack(0.5e-3));
  check_refused([&] { check_run(faulted); }, "model.friction_coefficient", "[[faults]]");
  SimulationCase smooth = c;
  smooth.model.friction_smoothing_speed_m_s = 1e-3;
  check_refused([&] { check_run(smooth); }, "model.friction_smoothing_speed", "continuously");
  // The run itself goes through.
  CHECK_NOTHROW(check_run(c));
}

TEST_CASE("helical friction: on elastic bearings the planar ledger closes with the friction loss") {
  // The planar model adds the centres' slide to each point's Vs and the friction force to the
  // centres; its ledger (bearings' energies included) closes only if the loss is the power of
  // the moments and the centres' forces together.
  SimulationCase c = planar_helical(h501_pair(), 1e9, 200.0, 100.0, 1e-3);
  c.model.friction_coefficient = 0.1;
  const SimulationSummary s = simulate(c).summary;
  const double throughput =
      s.kinetic_energy_initial_j + s.stored_energy_initial_j + std::fabs(s.torque_work_j);
  MESSAGE("helical planar friction: loss " << s.friction_loss_j << " J, residual "
                                           << s.ledger_residual_max_j << " J of " << throughput
                                           << " J");
  CHECK(s.friction_loss_j > 1e3 * s.ledger_residual_max_j);
  CHECK(s.ledger_residual_max_j < 1e-7 * throughput);
}

// The static commands on a faulted helical pair (docs/helical.md, Faults):
// mesh-stiffness and ste read the tables a run reads.
namespace {

// X of the pair with pinion tooth `tooth` on N1 at theta1 on the widened
// segment of `tables`, or NaN: X_k = X_pitch + Rb1 theta1 + k p_bt.
double pinion_tooth_position(const GearPair& h, const MeshTables& tables, double theta1,
                             int tooth) {
  const GearPair swept = swept_transverse_pair(h);
  const MeshLayout layout(swept, CoastPhase::half_base_pitch);
  const double reference = layout.reference_m(Region::n1, theta1);
  for (int k = -swept.teeth1; k <= swept.teeth1; ++k) {
    const double x = layout.position_m(reference, k);
    if (x >= tables.healthy().domain_start_m() && x <= tables.healthy().domain_end_m() &&
        teeth_of_pair(swept, Region::n1, k).pinion_tooth == tooth) {
      return x;
    }
  }
  return std::nan("");
}

}  // namespace

TEST_CASE("helical static commands: a crack of depth 0 gives the healthy stiffness and STE") {
  // Bit for bit against the healthy pair by the same tables; and those
  // tables' route against the closed-form route B (helical_mesh_stiffness,
  // the face integral through C(X)) and its exact mean b C(X_EAP) / p_bt.
  const GearPair h = h501_pair();
  const StiffnessModel model;
  const TruePeriodMeshStiffness cracked =
      helical_true_period_mesh_stiffness(h, model, pinion_tooth0(h501_crack(0.0)), 10);
  REQUIRE(cracked.mesh_periods == 20);
  REQUIRE(cracked.samples.size() == 200);
  bool same = true;
  for (const TruePeriodSample& s : cracked.samples)
    same = same && s.ke_n_per_m == s.healthy_ke_n_per_m;
  CHECK(same);
  // The faulted mean adds the healthy integral N times before dividing by N p_bt: to rounding.
  CHECK(relative_difference(cracked.mean_n_per_m, cracked.healthy_mean_n_per_m) < 1e-14);
  const HelicalMeshStiffnessCurve curve = helical_mesh_stiffness(h, model, 10);
  double worst = 0.0;
  for (std::size_t i = 0; i < curve.samples.size(); ++i) {
    CHECK(cracked.samples[i].theta1_rad == doctest::Approx(curve.samples[i].theta1_rad));
    worst = std::max(
        worst, relative_difference(cracked.samples[i].ke_n_per_m, curve.samples[i].face_n_per_m));
  }
  MESSAGE("helical static: tables against route B "
          << worst << ", mean " << relative_difference(cracked.mean_n_per_m, curve.mean_n_per_m));
  // Tolerance: the pair table fits route B to about 1e-12 of the largest Ke
  // (docs/verification.md); 1e-9 leaves room, far below any fault's share.
  CHECK(worst < 1e-9);
  CHECK(relative_difference(cracked.mean_n_per_m, curve.mean_n_per_m) < 1e-9);

  const MeshTables zero = helical_mesh_tables(h, model, pinion_tooth0(h501_crack(0.0)));
  const MeshTables healthy = helical_mesh_tables(h, model, {});
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 10;
  options.mesh_periods = 20;
  const HelicalStaticTransmissionError a =
      helical_static_transmission_error(h, 200.0, model, zero, options);
  const HelicalStaticTransmissionError b =
      helical_static_transmission_error(h, 200.0, model, healthy, options);
  const HelicalStaticTransmissionError route_b =
      helical_static_transmission_error(h, Modifications{}, 200.0, model, options);
  REQUIRE(a.points.size() == 200);
  REQUIRE(route_b.points.size() == 200);
  bool same_ste = true;
  double worst_ste = 0.0;
  double worst_load = 0.0;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    same_ste = same_ste && a.points[i].ste_m == b.points[i].ste_m &&
               a.points[i].load_per_width_n_per_m == b.points[i].load_per_width_n_per_m;
    worst_ste =
        std::max(worst_ste, relative_difference(a.points[i].ste_m, route_b.points[i].ste_m));
    for (std::size_t j = 0; j < a.slice_y_m.size(); ++j) {
      worst_load =
          std::max(worst_load, relative_difference(a.points[i].load_per_width_n_per_m[j],
                                                   route_b.points[i].load_per_width_n_per_m[j]));
    }
  }
  CHECK(same_ste);
  MESSAGE("helical static STE: tables against route B " << worst_ste << ", load across the face "
                                                        << worst_load);
  // The same fit bound as the stiffness above; the load across the face reads
  // the section's table where route B reads the transverse pair's, the same
  // pair and model: to rounding.
  CHECK(worst_ste < 1e-9);
  CHECK(worst_load < 1e-9);
}

TEST_CASE("helical static commands: a spall band's loss in mesh-stiffness is a by-hand slice sum") {
  // Pinion tooth 0 spalled over the middle half of the face [b/4, 3b/4). By
  // hand: N = 4096 slices, those of the band at X + (y_j - b/2) tan(beta_b),
  // each losing kappa_t - kappa_spall of the transverse spur pair spalled
  // across its face (its table from MeshTables of that pair, Hertz projected
  // by cos(beta_b)), times db. The code's loss is Ke - healthy Ke of the
  // sample, where only pinion tooth 0's pair differs.
  const GearPair h = h501_pair();
  const GearPair t = transverse_pair(h);
  const HelicalGeometry g = helical_geometry(h);
  const double b = h.face_width_m;
  const double tan_bb = std::tan(g.base_helix_angle_rad);
  const double cos_bb = std::cos(g.base_helix_angle_rad);
  const ContactSegment path = contact_segment(t);
  const std::vector<ToothFault> faults = pinion_tooth0(h501_spall(0.25 * b, 0.5 * b));
  const StiffnessModel model;
  const TruePeriodMeshStiffness tvms = helical_true_period_mesh_stiffness(h, model, faults, 16);
  const MeshTables tables = helical_mesh_tables(h, model, faults);
  const MeshTables spur(t, model, pinion_tooth0(h501_spall(0.0, b)));
  const StiffnessTable& section = tooth0_table(spur, Region::n1);
  const auto kappa = [&](const StiffnessTable& table, double x) {
    const Compliances c = table.compliance(x);
    if (!(c.total_m_per_n() > 0.0)) return 0.0;
    const double hertz = c.of(Term::hertz);
    return 1.0 / (b * (c.total_m_per_n() - hertz + hertz / cos_bb));
  };
  double kappa_most = 0.0;
  for (int i = 0; i <= 1000; ++i) {
    kappa_most = std::max(
        kappa_most, kappa(spur.healthy(), path.start_m + (path.end_m - path.start_m) * i / 1000.0));
  }
  const int n = 4096;
  const double db = b / n;
  double worst = 0.0;
  double worst_table = 0.0;
  double most_loss = 0.0;
  int faulted_samples = 0;
  for (const TruePeriodSample& s : tvms.samples) {
    const double x = pinion_tooth_position(h, tables, s.theta1_rad, 0);
    const double code_loss = s.healthy_ke_n_per_m - s.ke_n_per_m;
    if (std::isnan(x)) {
      CHECK(code_loss == 0.0);
      continue;
    }
    ++faulted_samples;
    double loss = 0.0;
    for (int j = n / 4; j < 3 * n / 4; ++j) {
      const double at = x + ((j + 0.5) * db - 0.5 * b) * tan_bb;
      if (at >= path.start_m && at <= path.end_m) {
        loss += (kappa(spur.healthy(), at) - kappa(section, at)) * db;
      }
    }
    // The dynamics' table of tooth 0's pair at the same X.
    const double table_loss =
        tables.healthy().stiffness(x) - tooth0_table(tables, Region::n1).stiffness(x);
    // Tolerance: one slice at most on the wrong side of each of the spall's
    // two radial edges (kappa_most db apiece), and 1e-10 of K for the tables' fit.
    worst = std::max(worst,
                     std::abs(code_loss - loss) / (2.0 * kappa_most * db + 1e-10 * s.ke_n_per_m));
    worst_table = std::max(worst_table, std::abs(code_loss - table_loss) / s.healthy_ke_n_per_m);
    most_loss = std::max(most_loss, loss / s.healthy_ke_n_per_m);
  }
  MESSAGE("helical static spall: |loss - slice sum| up to " << worst << " of the bound; against "
                                                            << "the run's table " << worst_table
                                                            << "; loss up to " << most_loss);
  CHECK(faulted_samples > 0);
  CHECK(worst < 1.0);
  // The other pairs read the healthy table in both sums: to rounding of K.
  CHECK(worst_table < 1e-14);
  // The spall takes a visible share of K (the checks above could fail).
  CHECK(most_loss > 0.02);
}

TEST_CASE("helical static commands: the STE rises only while the spalled tooth is in contact") {
  // Pinion tooth 0 spalled over part of the face: where no pair of tooth 0
  // is on the widened segment, every pair reads the healthy table and the
  // STE is the healthy one to the bit; while it is, the pair is softer and
  // the STE higher (never lower, to rounding).
  const GearPair h = h501_pair();
  const double b = h.face_width_m;
  const StiffnessModel model;
  const MeshTables faulted =
      helical_mesh_tables(h, model, pinion_tooth0(h501_spall(0.2 * b, 0.5 * b)));
  const MeshTables healthy = helical_mesh_tables(h, model, {});
  StaticTransmissionErrorOptions options;
  options.points_per_mesh_period = 16;
  const HelicalStaticTransmissionError f =
      helical_static_transmission_error(h, 200.0, model, faulted, options);
  options.mesh_periods = f.mesh_periods;
  const HelicalStaticTransmissionError s =
      helical_static_transmission_error(h, 200.0, model, healthy, options);
  REQUIRE(f.mesh_periods == 20);
  REQUIRE(f.points.size() == s.points.size());
  int outside_differs = 0;
  int inside = 0;
  double lowest = 0.0;
  double rise = 0.0;
  for (std::size_t i = 0; i < f.points.size(); ++i) {
    const bool touching = !std::isnan(pinion_tooth_position(h, faulted, f.points[i].theta1_rad, 0));
    const double ratio = f.points[i].ste_m / s.points[i].ste_m - 1.0;
    if (!touching) {
      if (f.points[i].ste_m != s.points[i].ste_m) ++outside_differs;
      continue;
    }
    ++inside;
    lowest = std::min(lowest, ratio);
    rise = std::max(rise, ratio);
  }
  MESSAGE("helical static STE: " << inside << " points with tooth 0 in contact, rise up to " << rise
                                 << ", lowest " << lowest);
  CHECK(outside_differs == 0);
  CHECK(inside > 0);
  CHECK(lowest > -1e-12);
  CHECK(rise > 0.05);
}
