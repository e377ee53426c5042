// The dimensionless form and the closed forms of docs/steady-state.md sections 2, 3.1 and 3.2,
// against independent routes: the two-disc SI system solved by linear algebra, the fixed point
// of the reference integrator's period map found by shooting, and slow sweeps of that
// integrator.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/steady/closed_forms.hpp"
#include "gearimpact/steady/shooting.hpp"
#include "reference_oscillator.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

constexpr double pressure_angle = 20.0 * std::numbers::pi / 180.0;

// The paper's pair (docs/model.md): pitch radii 20 and 80 mm, solid discs of face width 10 mm on
// the pitch radius, steel; the mesh stiffness of ISO's c_gamma_alpha = 20 N/(mm um) times the face
// width; Table 1's case 2 torque, 50 kgf-mm.
LoadedPair paper_loaded_pair(double excitation_rad_per_s) {
  const double density = 7800.0;
  const double width = 10e-3;
  const auto disc = [&](double radius) {
    return density * std::numbers::pi * std::pow(radius, 4) * width / 2.0;
  };
  LoadedPair p;
  p.inertia1_kg_m2 = disc(20e-3);
  p.inertia2_kg_m2 = disc(80e-3);
  p.base_radius1_m = 20e-3 * std::cos(pressure_angle);
  p.base_radius2_m = 80e-3 * std::cos(pressure_angle);
  p.mesh_stiffness_n_per_m = 20e9 * width;
  p.backlash_m = 0.05e-3;
  p.mean_torque1_n_m = 50.0 * 9.80665e-3;
  p.torque_fluctuation1_n_m = 0.2;
  p.excitation_frequency_rad_per_s = excitation_rad_per_s;
  return p;
}

}  // namespace

TEST_CASE("dimensionless form against the two-disc SI system") {
  for (const double w : {5000.0, 40000.0, 90000.0}) {
    CAPTURE(w);
    const LoadedPair pair = paper_loaded_pair(w);
    const DimensionlessPair d = dimensionless_form(pair);
    const double rb1 = pair.base_radius1_m;
    const double rb2 = pair.base_radius2_m;
    const double k = pair.mesh_stiffness_n_per_m;

    // Two discs coupled along the line of action by the mesh spring on s = Rb1 th1 - Rb2 th2:
    // M th'' + K th = T with K = k [Rb1, -Rb2]^T [Rb1, -Rb2].
    Eigen::Matrix2d m = Eigen::Matrix2d::Zero();
    m(0, 0) = pair.inertia1_kg_m2;
    m(1, 1) = pair.inertia2_kg_m2;
    const Eigen::Vector2d line(rb1, -rb2);
    const Eigen::Matrix2d stiffness = k * line * line.transpose();

    // The elastic mode's natural frequency: the non-zero generalised eigenvalue of (K, M).
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> modes(stiffness, m);
    const double w_n = std::sqrt(modes.eigenvalues().maxCoeff());
    // Rounding of a 2x2 eigenproblem: a few ulps, times the ratio of the two inertias' scales.
    CHECK(relative_difference(d.natural_frequency_rad_per_s, w_n) <= 1e-12);
    CHECK(relative_difference(d.frequency_ratio, w / w_n) <= 1e-12);

    // Forced response to dT1 cos(w t) on gear 1 with the contact held (no damping): the
    // amplitude of s is B times the linear closed form with F_a and Omega.
    const Eigen::Vector2d torque(pair.torque_fluctuation1_n_m, 0.0);
    const Eigen::Vector2d theta = (stiffness - w * w * m).partialPivLu().solve(torque);
    const double s_amplitude = std::fabs(line.dot(theta));
    const ClearanceOscillator oscillator{0.0, d.mean_force, d.alternating_force,
                                         ExcitationForm::torque_fluctuation};
    const double closed_form =
        linear_steady_response(oscillator, d.frequency_ratio).amplitude * pair.backlash_m;
    // A 2x2 solve whose conditioning is 1 / |1 - Omega^2| <= 10 here: 1e-12 covers it.
    CHECK(relative_difference(s_amplitude, closed_form) <= 1e-12);

    // The viscous mesh damper c = 2 zeta sqrt(k m_e) on s gives the elastic mode the damping
    // ratio zeta: in the time w_n t its eigenvalues in the 4-state system (th, th' / w_n) are
    // -zeta +- i sqrt(1 - zeta^2); the rigid-body pair sits at 0.
    const double zeta = 0.07;
    const double c = viscous_mesh_damping_n_s_per_m(zeta, k, d.effective_mass_kg);
    Eigen::Matrix4d state = Eigen::Matrix4d::Zero();
    state.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
    state.bottomLeftCorner<2, 2>() = -m.inverse() * stiffness / (w_n * w_n);
    state.bottomRightCorner<2, 2>() = -m.inverse() * (c * line * line.transpose()) / w_n;
    const Eigen::Vector4cd lambda = Eigen::EigenSolver<Eigen::Matrix4d>(state).eigenvalues();
    double real_part = 0.0;
    for (Eigen::Index i = 0; i < 4; ++i) real_part = std::min(real_part, lambda[i].real());
    // Eigenvalues of a 4x4 with entries of order 1 (the two inertias differ by 256): 1e-12.
    CHECK(relative_difference(-real_part, zeta) <= 1e-12);

    // The static load: the mesh force that holds gear 1 against T_m is k (s - B) = T_m / Rb1,
    // so x - 1 = (s - B) / B is F_m.
    const double mesh_deflection = (pair.mean_torque1_n_m / rb1) / k;
    CHECK(relative_difference(d.mean_force, mesh_deflection / pair.backlash_m) <= 1e-14);
  }
}

TEST_CASE("the mean torques of a steady state must balance") {
  const LoadedPair pair = paper_loaded_pair(1000.0);
  const double t1 = pair.mean_torque1_n_m;
  const double t2 = -t1 * pair.base_radius2_m / pair.base_radius1_m;
  CHECK_NOTHROW(require_balanced_mean_torques(t1, t2, pair.base_radius1_m, pair.base_radius2_m));
  try {
    require_balanced_mean_torques(t1, 0.9 * t2, pair.base_radius1_m, pair.base_radius2_m);
    FAIL("an unbalanced pair was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "mean torques");
    CHECK(std::string(e.what()).find("T1/Rb1 + T2/Rb2") != std::string::npos);
  }
}

TEST_CASE("bad inputs name their field") {
  LoadedPair pair = paper_loaded_pair(1000.0);
  pair.backlash_m = 0.0;
  try {
    (void)dimensionless_form(pair);
    FAIL("a zero backlash was accepted");
  } catch (const InputError& e) {
    CHECK(e.field() == "backlash");
  }
  const ClearanceOscillator undamped{0.0, 0.1, 0.01, ExcitationForm::torque_fluctuation};
  CHECK_THROWS_AS((void)linear_steady_response(undamped, 1.0), InputError);
  const ClearanceOscillator unloaded{0.1, 0.0, 0.01, ExcitationForm::torque_fluctuation};
  CHECK_THROWS_AS((void)contact_loss_band(unloaded), InputError);
  const ClearanceOscillator nan_damping{std::nan(""), 0.1, 0.01,
                                        ExcitationForm::torque_fluctuation};
  CHECK_THROWS_AS((void)linear_steady_response(nan_damping, 0.5), InputError);
}

TEST_CASE("linear limit: closed form against the shooting fixed point of the oscillator") {
  struct Case {
    ExcitationForm form;
    double omega;
  };
  const std::vector<Case> cases{{ExcitationForm::torque_fluctuation, 0.5},
                                {ExcitationForm::torque_fluctuation, 1.0},
                                {ExcitationForm::torque_fluctuation, 1.6},
                                {ExcitationForm::transmission_error, 0.7},
                                {ExcitationForm::transmission_error, 2.5}};
  for (const Case& c : cases) {
    CAPTURE(c.omega);
    CAPTURE(static_cast<int>(c.form));
    verify::OscillatorParameters p;
    p.damping_ratio = 0.1;
    p.mean_force = 0.1;
    p.alternating_force = 0.01;
    p.form = c.form;
    p.frequency_ratio = c.omega;
    const verify::ReferenceOscillator oscillator(p);
    const PeriodMap map = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
      return oscillator.period_map(Eigen::Vector2d(y[0], y[1]), 2000);
    };
    ShootingSettings settings;
    settings.tolerance = 1e-13;
    const PeriodicOrbit orbit =
        find_periodic_orbit(map, Eigen::Vector2d(1.0 + p.mean_force, 0.0), settings);

    const ClearanceOscillator closed{p.damping_ratio, p.mean_force, p.alternating_force, c.form};
    const LinearSteadyResponse r = linear_steady_response(closed, c.omega);
    REQUIRE(r.keeps_contact);
    // x = 1 + F_m + A cos(Omega tau - phi) at tau = 0, and its derivative.
    const double x0 = 1.0 + p.mean_force + r.amplitude * std::cos(r.phase_rad);
    const double v0 = r.amplitude * c.omega * std::sin(r.phase_rad);
    MESSAGE("Omega " << c.omega << ": x(0) differs by " << orbit.fixed_point[0] - x0
                     << ", x'(0) by " << orbit.fixed_point[1] - v0);
    // RK4 with 2000 steps a period: its global error is of order h^4 = (T / 2000)^4 <= 3e-9
    // relative to the motion, further multiplied by the method's small error constant; measured
    // 4e-13 on these cases. 1e-10 still fails a wrong phase sign or a
    // wrong W by orders of magnitude.
    CHECK(std::fabs(orbit.fixed_point[0] - x0) <= 1e-10);
    CHECK(std::fabs(orbit.fixed_point[1] - v0) <= 1e-10);

    // The orbit never separates, so its multipliers are those of y'' + 2 zeta y' + y = 0 over
    // T: the complex pair e^{(-zeta +- i sqrt(1 - zeta^2)) T}, of modulus e^{-zeta T}.
    const double period = 2.0 * std::numbers::pi / c.omega;
    const double modulus = std::exp(-p.damping_ratio * period);
    for (Eigen::Index i = 0; i < 2; ++i) {
      // Central differences on a linear map are exact up to rounding (~1e-10 relative, the
      // rounding of the map over its step); RK4's own error is ~1e-10.
      CHECK(std::fabs(std::abs(orbit.floquet_multipliers[i]) - modulus) <= 1e-8);
    }
  }
}

TEST_CASE("contact-loss band: the linear amplitude equals F_m at its edges") {
  struct Case {
    ExcitationForm form;
    double r;
  };
  const double zeta = 0.1;
  const double f_m = 0.1;
  for (const Case c : {Case{ExcitationForm::torque_fluctuation, 0.5},
                       Case{ExcitationForm::torque_fluctuation, 1.5},
                       Case{ExcitationForm::transmission_error, 0.5},
                       Case{ExcitationForm::transmission_error, 1.0},
                       Case{ExcitationForm::transmission_error, 1.5}}) {
    CAPTURE(c.r);
    CAPTURE(static_cast<int>(c.form));
    const ClearanceOscillator o{zeta, f_m, c.r * f_m, c.form};
    const std::optional<FrequencyBand> band = contact_loss_band(o);
    REQUIRE(band.has_value());

    // Section 3.2's roots, written out here from the spec.
    const double b0 = 1.0 - 2.0 * zeta * zeta;
    const double r2 = c.r * c.r;
    if (c.form == ExcitationForm::torque_fluctuation) {
      const double root = std::sqrt(b0 * b0 - 1.0 + r2);
      CHECK(relative_difference(band->upper, std::sqrt(b0 + root)) <= 1e-14);
      if (c.r < 1.0) {
        CHECK(relative_difference(band->lower, std::sqrt(b0 - root)) <= 1e-13);
      } else {
        CHECK(band->lower == 0.0);
      }
    } else if (c.r < 1.0) {
      const double root = std::sqrt(b0 * b0 - (1.0 - r2));
      CHECK(relative_difference(band->lower, std::sqrt((b0 - root) / (1.0 - r2))) <= 1e-13);
      CHECK(relative_difference(band->upper, std::sqrt((b0 + root) / (1.0 - r2))) <= 1e-13);
    } else {
      CHECK(band->upper == std::numeric_limits<double>::infinity());
    }

    // At a finite, non-zero edge A = F_m; just inside contact is lost, just outside it is kept.
    for (const double edge : {band->lower, band->upper}) {
      if (edge == 0.0 || !std::isfinite(edge)) continue;
      CAPTURE(edge);
      // The roots are computed without cancellation: A(edge) matches F_m to rounding.
      CHECK(relative_difference(linear_steady_response(o, edge).amplitude, f_m) <= 1e-12);
      const double into = edge == band->lower ? 1.0 + 1e-6 : 1.0 - 1e-6;
      CHECK_FALSE(linear_steady_response(o, edge * into).keeps_contact);
      CHECK(linear_steady_response(o, edge / into).keeps_contact);
    }
  }

  // Heavy damping and a small excitation: the peak F_a / (2 zeta sqrt(1 - zeta^2)) stays below
  // F_m, so no band, and every Omega keeps contact.
  const ClearanceOscillator calm{0.5, f_m, 0.1 * f_m, ExcitationForm::torque_fluctuation};
  CHECK_FALSE(contact_loss_band(calm).has_value());
  for (int i = 1; i <= 400; ++i) CHECK(linear_steady_response(calm, 0.01 * i).keeps_contact);
}

TEST_CASE("contact-loss onset: slow sweeps switch NI -> SS within one grid step of the edge") {
  struct Case {
    ExcitationForm form;
    double r;
  };
  const double zeta = 0.1;
  const double f_m = 0.1;
  // Grid step 0.02, offset so that no grid point lies within 1e-4 of an edge: closer than that
  // the decision rests on amplitude differences of the order of the integration error.
  std::vector<double> up;
  for (int i = 0; i <= 80; ++i) up.push_back(0.401 + 0.02 * i);
  const double grid_step = 0.02;
  std::vector<double> down(up.rbegin(), up.rend());

  for (const Case c : {Case{ExcitationForm::torque_fluctuation, 0.5},
                       Case{ExcitationForm::torque_fluctuation, 1.5},
                       Case{ExcitationForm::transmission_error, 0.5}}) {
    CAPTURE(c.r);
    CAPTURE(static_cast<int>(c.form));
    const ClearanceOscillator o{zeta, f_m, c.r * f_m, c.form};
    const FrequencyBand band = contact_loss_band(o).value();
    for (const double omega : up) {
      REQUIRE(std::fabs(omega - band.lower) > 1e-4);
      REQUIRE(std::fabs(omega - band.upper) > 1e-4);
    }
    verify::OscillatorParameters p;
    p.damping_ratio = zeta;
    p.mean_force = f_m;
    p.alternating_force = c.r * f_m;
    p.form = c.form;
    // 150 periods of transient: the free motion decays by e^{-zeta 2 pi / Omega} >= e^{-0.26}
    // a period over this grid, to below 1e-17 in 150.
    const auto sweep_up = verify::slow_sweep(p, up, {1.0 + f_m, 0.0}, 150, 400);
    const auto sweep_down = verify::slow_sweep(p, down, {1.0 + f_m, 0.0}, 150, 400);

    // Every switch from no impact to contact loss along a sweep brackets an edge of the band:
    // the NI branch ends exactly where its amplitude reaches F_m.
    std::vector<double> switches;
    for (const auto* sweep : {&sweep_up, &sweep_down}) {
      for (std::size_t i = 1; i < sweep->size(); ++i) {
        const auto& before = (*sweep)[i - 1];
        const auto& after = (*sweep)[i];
        if (before.last_period.lost_drive_contact || !after.last_period.lost_drive_contact) {
          continue;
        }
        const double a = before.frequency_ratio;
        const double b = after.frequency_ratio;
        const bool brackets_lower = (band.lower - a) * (band.lower - b) < 0.0;
        const bool brackets_upper = (band.upper - a) * (band.upper - b) < 0.0;
        MESSAGE("NI -> SS between Omega " << a << " and " << b << "; band [" << band.lower << ", "
                                          << band.upper << "]");
        CHECK(std::fabs(b - a) <= grid_step * (1.0 + 1e-12));
        CHECK((brackets_lower || brackets_upper));
        switches.push_back(brackets_lower ? band.lower : band.upper);
      }
    }
    // The sweeps do meet the edges inside the grid: the up sweep the lower edge (unless contact
    // is lost from Omega = 0), the down sweep the upper one.
    const auto met = [&](double edge) {
      for (double s : switches) {
        if (s == edge) return true;
      }
      return false;
    };
    if (band.lower > up.front()) CHECK(met(band.lower));
    if (band.upper < up.back()) CHECK(met(band.upper));
  }
}
