#include "gearimpact/stiffness/tooth_beam.hpp"

#include <algorithm>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <string>

#include "gearimpact/error.hpp"
#include "gearimpact/numerics/quadrature.hpp"

namespace gearimpact {

namespace {

// The three energy densities per unit height, as functions of the section's
// half thickness x at height y (docs/stiffness-models.md section 2).
struct Densities {
  double bending;
  double shear;
  double axial;
};

class EnergyDensity {
 public:
  EnergyDensity(const BeamLoad& load, const BeamMaterial& material, const BeamSections* sections,
                bool change = false)
      : load_(load),
        material_(material),
        sections_(sections),
        change_(change),
        cos_tau_(std::cos(load.tau_rad)),
        sin_tau_(std::sin(load.tau_rad)) {}

  // 1/kb integrand: M^2 / (E I) with M = F [cos tau (y_t - y) - x_t sin tau].
  double bending(double x, double y) const {
    const double arm = cos_tau_ * (load_.y_m - y) - load_.x_m * sin_tau_;
    const double second_moment = 2.0 / 3.0 * x * x * x * material_.width_m;
    if (change_) {
      return arm * arm / material_.youngs_modulus_pa *
             (1.0 / (*sections_)(x, y).second_moment_m4 - 1.0 / second_moment);
    }
    if (sections_) {
      return arm * arm / (material_.youngs_modulus_pa * (*sections_)(x, y).second_moment_m4);
    }
    return arm * arm / (material_.youngs_modulus_pa * second_moment);
  }
  // 1/ks integrand, Tian 2004: 1.2 (F cos tau)^2 / (G A).
  double shear(double x, double y) const {
    if (change_) {
      return 1.2 * cos_tau_ * cos_tau_ / material_.shear_modulus_pa *
             (1.0 / (*sections_)(x, y).area_m2 - 1.0 / (2.0 * x * material_.width_m));
    }
    if (sections_) {
      return 1.2 * cos_tau_ * cos_tau_ / (material_.shear_modulus_pa * (*sections_)(x, y).area_m2);
    }
    return 1.2 * cos_tau_ * cos_tau_ / (material_.shear_modulus_pa * 2.0 * x * material_.width_m);
  }
  // 1/ka integrand: (F sin tau)^2 / (E A).
  double axial(double x, double y) const {
    if (change_) {
      return sin_tau_ * sin_tau_ / material_.youngs_modulus_pa *
             (1.0 / (*sections_)(x, y).area_m2 - 1.0 / (2.0 * x * material_.width_m));
    }
    if (sections_) {
      return sin_tau_ * sin_tau_ / (material_.youngs_modulus_pa * (*sections_)(x, y).area_m2);
    }
    return sin_tau_ * sin_tau_ / (material_.youngs_modulus_pa * 2.0 * x * material_.width_m);
  }
  bool has_shear() const { return cos_tau_ != 0.0; }
  bool has_axial() const { return sin_tau_ != 0.0; }

 private:
  BeamLoad load_;
  BeamMaterial material_;
  const BeamSections* sections_;  // null: A = 2 x b, I = (2/3) x^3 b
  // The density with sections_ less the one with 2 x b, (2/3) x^3 b.
  bool change_;
  double cos_tau_;
  double sin_tau_;
};

// The beam's terms of terms.hpp; the Hertzian contact and the foundation are
// no part of the beam.
double density(const EnergyDensity& d, Term term, double x, double y) {
  switch (term) {
    case Term::bending:
      return d.bending(x, y);
    case Term::shear:
      return d.shear(x, y);
    case Term::axial:
      return d.axial(x, y);
    case Term::hertz:
    case Term::foundation:
      break;
  }
  return 0.0;
}

// Route 1: Int f(x(p), y(p)) y'(p) dp over the piece's parameter, with
// p = p_root + t (p_top - p_root), t in [0, 1]. The unit interval is for
// Boost 1.74, whose Gauss-Kronrod error estimate is taken on [-1, 1] before
// scaling to the interval: on a piece a fraction of a millimetre long it
// would read thousands of times the true error and never converge.
double integrate_over_parameter(const FlankPiece& piece, const EnergyDensity& d, Term term,
                                QuadratureTolerance tolerance) {
  const double span = piece.parameter_top - piece.parameter_root;
  const auto integrand = [&](double t) {
    const ProfilePoint point = piece.point(piece.parameter_root + t * span);
    return density(d, term, point.x_m, point.y_m) * point.dy_m * span;
  };
  return integrate_boost_gauss_kronrod(integrand, 0.0, 1.0, tolerance).value;
}

// The parameter at which the piece reaches height y: y(p) is monotonic on
// the piece, so the root is bracketed by its ends. Heights within rounding of
// an end return that end.
double parameter_at_height(const FlankPiece& piece, double y) {
  const auto excess = [&](double p) { return piece.point(p).y_m - y; };
  const double at_root = excess(piece.parameter_root);
  const double at_top = excess(piece.parameter_top);
  if (at_root >= 0.0) return piece.parameter_root;
  if (at_top <= 0.0) return piece.parameter_top;
  std::uintmax_t iterations = 200;
  const bool rising = piece.parameter_top > piece.parameter_root;
  const auto bracket = boost::math::tools::toms748_solve(
      excess, rising ? piece.parameter_root : piece.parameter_top,
      rising ? piece.parameter_top : piece.parameter_root, rising ? at_root : at_top,
      rising ? at_top : at_root, boost::math::tools::eps_tolerance<double>(), iterations);
  return 0.5 * (bracket.first + bracket.second);
}

// Route 2: Int f(x(y), y) dy over the piece's height, each section solved for.
double integrate_over_height(const FlankPiece& piece, const EnergyDensity& d, Term term,
                             QuadratureTolerance tolerance) {
  const double y_root = piece.point(piece.parameter_root).y_m;
  const double y_top = piece.point(piece.parameter_top).y_m;
  if (!(y_top > y_root)) {
    throw InputError("flank piece", y_top - y_root,
                     "a positive rise in height from the piece's root to its top");
  }
  const auto integrand = [&](double y) {
    const double x = piece.point(parameter_at_height(piece, y)).x_m;
    return density(d, term, x, y);
  };
  return integrate_gsl_qag(integrand, y_root, y_top, tolerance).value;
}

double integrate_flank(const std::vector<FlankPiece>& flank, const EnergyDensity& d, Term term,
                       StiffnessRoute route, QuadratureTolerance tolerance) {
  double sum = 0.0;
  for (const FlankPiece& piece : flank) {
    sum += route == StiffnessRoute::tau_form ? integrate_over_parameter(piece, d, term, tolerance)
                                             : integrate_over_height(piece, d, term, tolerance);
  }
  return sum;
}

BeamCompliance beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                               const BeamMaterial& material, StiffnessRoute route,
                               double relative_tolerance, const BeamSections* sections,
                               bool change = false) {
  if (flank.empty()) throw InputError("flank", "empty", "at least one piece");
  const EnergyDensity d(load, material, sections, change);
  const QuadratureTolerance tolerance{relative_tolerance, 0.0};
  BeamCompliance c{};
  c.bending_m_per_n = integrate_flank(flank, d, Term::bending, route, tolerance);
  // A load straight across (along) the tooth has no axial (shear) part; its
  // integrand is identically zero, which a relative tolerance cannot certify.
  c.shear_m_per_n = d.has_shear() ? integrate_flank(flank, d, Term::shear, route, tolerance) : 0.0;
  c.axial_m_per_n = d.has_axial() ? integrate_flank(flank, d, Term::axial, route, tolerance) : 0.0;
  return c;
}

}  // namespace

BeamCompliance tooth_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance) {
  return beam_compliance(flank, load, material, route, relative_tolerance, nullptr);
}

BeamCompliance tooth_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance, const BeamSections& sections) {
  return beam_compliance(flank, load, material, route, relative_tolerance, &sections);
}

BeamCompliance tooth_beam_compliance_change(const std::vector<FlankPiece>& flank,
                                            const BeamLoad& load, const BeamMaterial& material,
                                            StiffnessRoute route, double relative_tolerance,
                                            const BeamSections& sections) {
  if (flank.empty()) return {0.0, 0.0, 0.0};
  return beam_compliance(flank, load, material, route, relative_tolerance, &sections, true);
}

}  // namespace gearimpact
