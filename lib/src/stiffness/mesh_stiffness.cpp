#include "gearimpact/stiffness/mesh_stiffness.hpp"

#include <cmath>
#include "gearimpact/constants.hpp"

#include "gearimpact/error.hpp"
#include "gearimpact/numerics/quadrature.hpp"

namespace gearimpact {

namespace {

// sin tau + (theta_b - tau) cos tau: the half thickness of the section at
// tau over Rb, from the involute r(tau) of (23),(24).
double section_factor(double theta_b, double tau) {
  return std::sin(tau) + (theta_b - tau) * std::cos(tau);
}

QuadratureResult integrate(StiffnessMethod method, const Integrand& f, double a, double b,
                           double relative_tolerance) {
  const QuadratureTolerance tolerance{relative_tolerance, 0.0};
  switch (method) {
    case StiffnessMethod::gsl_qag:
      return integrate_gsl_qag(f, a, b, tolerance);
    case StiffnessMethod::gsl_cquad:
      return integrate_gsl_cquad(f, a, b, tolerance);
    case StiffnessMethod::boost_gauss_kronrod:
      return integrate_boost_gauss_kronrod(f, a, b, tolerance);
    case StiffnessMethod::boost_tanh_sinh:
      return integrate_boost_tanh_sinh(f, a, b, tolerance);
    case StiffnessMethod::xform:
      break;
  }
  throw std::logic_error("the x-form is a route, not a quadrature rule");
}

// (16)-(19): U = Int M^2/(2 E I) dx + Int Fa^2/(2 E A) dx over the centre line,
// x from the base-circle section (0) to the load (l), M = Fb (l - x) -/+ Fa h.
ToothCompliance xform_compliance(const InvoluteTooth& tooth, double contact_x_m, double e,
                                 double width, const StiffnessModel& model) {
  const PolarContact contact = polar_contact(tooth, contact_x_m);
  const double l = contact.arm.height_l_m;
  const double h = contact.arm.offset_h_m;
  // (6),(7) per unit force.
  const double fb = std::cos(contact.phi_rad);
  const double fa = std::sin(contact.phi_rad);
  const double axial_arm = model.moment_sign == AxialMomentSign::physical ? -fa * h : fa * h;
  // x = l s^2 smooths the square-root behaviour of the sections at the base
  // circle (x ~ (theta_b - tau)^2 there), so that every rule converges fast.
  const auto bending = [&](double s) {
    const double x = l * s * s;
    const double y = section_half_thickness(tooth, x);
    const double moment = fb * (l - x) + axial_arm;
    const double second_moment = 2.0 / 3.0 * width * y * y * y;
    return moment * moment / (e * second_moment) * 2.0 * l * s;
  };
  const auto axial = [&](double s) {
    const double x = l * s * s;
    const double area = 2.0 * width * section_half_thickness(tooth, x);
    return fa * fa / (e * area) * 2.0 * l * s;
  };
  const StiffnessMethod rule = model.xform_rule;
  return {integrate(rule, bending, 0.0, 1.0, model.relative_tolerance).value,
          integrate(rule, axial, 0.0, 1.0, model.relative_tolerance).value};
}

}  // namespace

StiffnessMethod parse_stiffness_method(std::string_view name) {
  if (name == "gsl") return StiffnessMethod::gsl_qag;
  if (name == "gsl-cquad") return StiffnessMethod::gsl_cquad;
  if (name == "boost-gk") return StiffnessMethod::boost_gauss_kronrod;
  if (name == "boost-ts") return StiffnessMethod::boost_tanh_sinh;
  if (name == "xform") return StiffnessMethod::xform;
  throw InputError("method", std::string(name), "one of gsl, gsl-cquad, boost-gk, boost-ts, xform");
}

std::string to_string(StiffnessMethod method) {
  switch (method) {
    case StiffnessMethod::gsl_qag:
      return "gsl";
    case StiffnessMethod::gsl_cquad:
      return "gsl-cquad";
    case StiffnessMethod::boost_gauss_kronrod:
      return "boost-gk";
    case StiffnessMethod::boost_tanh_sinh:
      return "boost-ts";
    case StiffnessMethod::xform:
      return "xform";
  }
  throw std::logic_error("unknown StiffnessMethod");
}

InvoluteTooth tooth_of(const GearPair& pair, Gear gear) {
  return {base_radius(pair, gear), half_tooth_angle(pair, gear)};
}

double hertz_stiffness(const GearPair& pair) {
  // (4)
  const double nu = pair.poisson_ratio;
  return pi * pair.youngs_modulus_pa * pair.face_width_m / (4.0 * (1.0 - nu * nu));
}

double bending_integrand(double theta_b, double phi, double tau, AxialMomentSign sign) {
  const double cos_phi = std::cos(phi);
  // (22) over Rb: [(l - x) cos phi -/+ h sin phi] / Rb with l, h from (10),(11)
  // and x(tau) from the involute. The printed sign simplifies to
  // 1 + cos phi [(theta_b - tau) sin tau - cos tau]; the flipped one keeps
  // 2 h sin phi / Rb more.
  double arm = 1.0 + cos_phi * ((theta_b - tau) * std::sin(tau) - std::cos(tau));
  if (sign == AxialMomentSign::flipped) {
    arm += 2.0 * std::sin(phi) * ((theta_b + phi) * cos_phi - std::sin(phi));
  }
  const double s = section_factor(theta_b, tau);
  // (20) with (23)
  return 3.0 * arm * arm * (theta_b - tau) * std::cos(tau) / (2.0 * s * s * s);
}

double axial_integrand(double theta_b, double phi, double tau) {
  const double sin_phi = std::sin(phi);
  // (21) with (24)
  return (theta_b - tau) * std::cos(tau) * sin_phi * sin_phi / (2.0 * section_factor(theta_b, tau));
}

ToothCompliance tooth_compliance(const InvoluteTooth& tooth, double contact_x_m,
                                 double youngs_modulus_pa, double face_width_m,
                                 const StiffnessModel& model) {
  if (!std::isfinite(contact_x_m) || contact_x_m <= 0.0) {
    throw InputError("contact position from the base-circle tangent point", contact_x_m,
                     "(0, tip] m: the contact must lie above the base circle");
  }
  if (model.method == StiffnessMethod::xform) {
    return xform_compliance(tooth, contact_x_m, youngs_modulus_pa, face_width_m, model);
  }
  const double theta_b = tooth.half_tooth_angle_rad;
  // (12) phi = X / Rb - theta_b; the section angle tau runs from the load
  // (tau = -phi) down to the base circle (tau = theta_b).
  const double phi = contact_x_m / tooth.base_radius_m - theta_b;
  const double scale = 1.0 / (youngs_modulus_pa * face_width_m);
  const auto bending = [&](double tau) {
    return bending_integrand(theta_b, phi, tau, model.moment_sign);
  };
  const auto axial = [&](double tau) { return axial_integrand(theta_b, phi, tau); };
  return {scale * integrate(model.method, bending, -phi, theta_b, model.relative_tolerance).value,
          scale * integrate(model.method, axial, -phi, theta_b, model.relative_tolerance).value};
}

void validate(const StiffnessModel& model) {
  if (!model.hertz_term && !model.bending_term && !model.axial_term) {
    throw InputError("stiffness terms", "none",
                     "at least one of the Hertzian, bending and axial terms of (29)");
  }
  if (!std::isfinite(model.relative_tolerance) || model.relative_tolerance < 1e-14 ||
      model.relative_tolerance > 1e-2) {
    throw InputError("stiffness tolerance", model.relative_tolerance, "[1e-14, 1e-2]");
  }
}

PairCompliance included_compliance(const StiffnessModel& model, double hertz_m_per_n,
                                   double bending_m_per_n, double axial_m_per_n) {
  return {model.hertz_term ? hertz_m_per_n : 0.0, model.bending_term ? bending_m_per_n : 0.0,
          model.axial_term ? axial_m_per_n : 0.0};
}

double series_stiffness(double kh, double kb1, double ka1, double kb2, double ka2) {
  // (29)
  return 1.0 / (1.0 / kh + 1.0 / kb1 + 1.0 / ka1 + 1.0 / kb2 + 1.0 / ka2);
}

MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model) {
  validate(model);
  const double lp = line_of_action_length(pair);
  if (!std::isfinite(x1_m) || x1_m <= 0.0 || x1_m >= lp) {
    throw InputError(
        "contact position X1", x1_m,
        "(0, lp) with lp = " + format_number(lp) + " m: between the tangent points C1 and C2");
  }
  const double e = pair.youngs_modulus_pa;
  const double width = pair.face_width_m;
  const ToothCompliance c1 = tooth_compliance(tooth_of(pair, Gear::one), x1_m, e, width, model);
  // (25),(26): gear 2 sees the contact at lp - X1 from C2.
  const ToothCompliance c2 =
      tooth_compliance(tooth_of(pair, Gear::two), lp - x1_m, e, width, model);
  MeshStiffness k{};
  k.kh = hertz_stiffness(pair);
  k.kb1 = 1.0 / c1.bending_m_per_n;
  k.ka1 = 1.0 / c1.axial_m_per_n;
  k.kb2 = 1.0 / c2.bending_m_per_n;
  k.ka2 = 1.0 / c2.axial_m_per_n;
  // (29) over the terms switched on.
  k.ke = 1.0 / included_compliance(model, 1.0 / k.kh, c1.bending_m_per_n + c2.bending_m_per_n,
                                   c1.axial_m_per_n + c2.axial_m_per_n)
                   .total_m_per_n();
  return k;
}

}  // namespace gearimpact
