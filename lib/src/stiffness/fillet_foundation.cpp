#include "gearimpact/stiffness/fillet_foundation.hpp"

#include <cmath>
#include <cstdio>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// One row A..F of the table of Sainsot et al. (2004), as printed in
// docs/stiffness-models.md.
struct FitRow {
  double a, b, c, d, e, f;
};

constexpr FitRow l_row{-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045};
constexpr FitRow m_row{60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086};
constexpr FitRow p_row{-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236};
constexpr FitRow q_row{-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904};

double evaluate(const FitRow& r, double h, double theta) {
  return r.a / (theta * theta) + r.b * h * h + r.c * h / theta + r.d / theta + r.e * h + r.f;
}

}  // namespace

FoundationFit sainsot_coefficients(double h_f, double theta_f_rad) {
  if (!std::isfinite(h_f) || h_f <= 1.0) {
    throw InputError("h_f = r_f / r_int", h_f, "(1, inf): the bore inside the root circle");
  }
  if (!std::isfinite(theta_f_rad) || theta_f_rad <= 0.0 || theta_f_rad >= 0.5 * pi) {
    throw InputError("theta_f", theta_f_rad, "(0, pi/2) rad");
  }
  FoundationFit fit{};
  fit.coefficients = {evaluate(l_row, h_f, theta_f_rad), evaluate(m_row, h_f, theta_f_rad),
                      evaluate(p_row, h_f, theta_f_rad), evaluate(q_row, h_f, theta_f_rad)};
  fit.extrapolated = h_f < sainsot_fit_min_h_f || h_f > sainsot_fit_max_h_f ||
                     theta_f_rad < sainsot_fit_min_theta_f_rad ||
                     theta_f_rad > sainsot_fit_max_theta_f_rad;
  return fit;
}

bool FoundationExtrapolation::h_f_outside() const {
  return h_f < sainsot_fit_min_h_f || h_f > sainsot_fit_max_h_f;
}

bool FoundationExtrapolation::theta_f_outside() const {
  return theta_f_rad < sainsot_fit_min_theta_f_rad || theta_f_rad > sainsot_fit_max_theta_f_rad;
}

std::vector<FoundationExtrapolation> foundation_extrapolation(Gear gear, double h_f,
                                                              double theta_f_rad) {
  const FoundationExtrapolation e{gear, h_f, theta_f_rad};
  if (!e.h_f_outside() && !e.theta_f_outside()) return {};
  return {e};
}

std::string describe(const FoundationExtrapolation& e) {
  // Three digits tell a value from a bound of two; the bounds print as the fit states them.
  char text[256];
  std::string out = e.gear == Gear::one ? "pinion (gear 1): " : "wheel (gear 2): ";
  if (e.theta_f_outside()) {
    std::snprintf(text, sizeof text, "theta_f = %.3g rad, outside the fit's [%g, %g] rad",
                  e.theta_f_rad, sainsot_fit_min_theta_f_rad, sainsot_fit_max_theta_f_rad);
    out += text;
  }
  if (e.h_f_outside()) {
    std::snprintf(text, sizeof text, "%sh_f = r_f / r_int = %.3g, outside the fit's [%g, %g]",
                  e.theta_f_outside() ? "; " : "", e.h_f, sainsot_fit_min_h_f, sainsot_fit_max_h_f);
    out += text;
  }
  return out;
}

std::string foundation_extrapolation_warning(const std::vector<FoundationExtrapolation>& gears) {
  if (gears.empty()) return "";
  std::string list;
  for (const FoundationExtrapolation& e : gears) list += (list.empty() ? "" : "; ") + describe(e);
  return "the fillet-foundation fit of Sainsot et al. (2004) is used outside its range (" + list +
         "): the foundation term is an extrapolation";
}

double fillet_foundation_compliance(const FoundationCoefficients& k, double youngs_modulus_pa,
                                    double width_m, double u_f_m, double s_f_m, double tau_rad) {
  const double ratio = u_f_m / s_f_m;
  const double cos_tau = std::cos(tau_rad);
  const double tan_tau = std::tan(tau_rad);
  // Sainsot et al. (2004), docs/stiffness-models.md section 2.
  return cos_tau * cos_tau / (youngs_modulus_pa * width_m) *
         (k.l * ratio * ratio + k.m * ratio + k.p * (1.0 + k.q * tan_tau * tan_tau));
}

}  // namespace gearimpact
