// The compliance of the gear body under a tooth (the fillet foundation), by
// the analytical fit of P. Sainsot, P. Velex and O. Duverger, "Contribution of
// gear body to tooth deflections - a new bidimensional analytical formula",
// J. Mech. Des. 126(4) (2004) 748-752, doi 10.1115/1.1758252.
// docs/stiffness-models.md, section 2.
#pragma once

#include <string>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"

namespace gearimpact {

// L*, M*, P*, Q* of the fit at one (h_f, theta_f).
struct FoundationCoefficients {
  double l;
  double m;
  double p;
  double q;
};

// The fit was made over finite element results for a range of gear bodies;
// outside h_f in [1.4, 7] and theta_f in [0.01, 0.12] rad it is an
// extrapolation. That range is the one carried (as a disabled check) in the
// development code of the ROSS gear element (petrobras/ross, GearElementTVMS,
// "not 1.4 <= h <= 7 or not 0.01 <= theta_f <= 0.12"), which cites Sainsot et
// al.; the paper itself was not at hand to confirm it.
inline constexpr double sainsot_fit_min_h_f = 1.4;
inline constexpr double sainsot_fit_max_h_f = 7.0;
inline constexpr double sainsot_fit_min_theta_f_rad = 0.01;
inline constexpr double sainsot_fit_max_theta_f_rad = 0.12;

// One gear whose fit inputs lie outside the range above: which gear, both inputs, and which of
// them are outside. A model carries these (TimeVaryingMeshStiffness, the run's summary) so that
// every warning can name the gear, the parameter, its value and the range.
struct FoundationExtrapolation {
  Gear gear = Gear::one;
  double h_f = 0.0;          // r_f / r_int
  double theta_f_rad = 0.0;  // the half angle of the tooth at the root circle
  bool h_f_outside() const;
  bool theta_f_outside() const;
};

// The gear's extrapolation, or nothing when (h_f, theta_f) lies inside the fit's range.
std::vector<FoundationExtrapolation> foundation_extrapolation(Gear gear, double h_f,
                                                              double theta_f_rad);

// "pinion (gear 1): theta_f = 0.131 rad, outside the fit's [0.01, 0.12] rad", each input outside
// named with its value and range.
std::string describe(const FoundationExtrapolation& extrapolation);

// The one warning for every extrapolated gear: "the fillet-foundation fit of Sainsot et al.
// (2004) is used outside its range (pinion (gear 1): theta_f = 0.131 rad, outside ...): the
// foundation term is an extrapolation". Empty for an empty list.
std::string foundation_extrapolation_warning(const std::vector<FoundationExtrapolation>& gears);

struct FoundationFit {
  FoundationCoefficients coefficients;
  // (h_f, theta_f) outside the fit's range above: the result is an extrapolation.
  bool extrapolated;
};

// X*(h_f, theta_f) = A / theta_f^2 + B h_f^2 + C h_f / theta_f + D / theta_f + E h_f + F
// with the table of docs/stiffness-models.md (Sainsot et al. 2004); h_f = r_f / r_int,
// theta_f the half angle of the tooth at the root circle. Throws InputError
// unless h_f > 1 (the bore inside the root circle) and theta_f is in (0, pi/2).
FoundationFit sainsot_coefficients(double h_f, double theta_f_rad);

// 1/kf = cos^2 tau / (E b) [L* (u_f/S_f)^2 + M* (u_f/S_f) + P* (1 + Q* tan^2 tau)]
// (Sainsot et al. 2004): u_f the distance from the root circle to where the
// load acts on the centre line, S_f = 2 r_f theta_f the root arc thickness.
double fillet_foundation_compliance(const FoundationCoefficients& coefficients,
                                    double youngs_modulus_pa, double width_m, double u_f_m,
                                    double s_f_m, double tau_rad);

}  // namespace gearimpact
