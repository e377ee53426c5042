// Mesh stiffness of one tooth pair by the potential energy method: MODEL.md,
// section Stiffness. Compliances in m/N, stiffnesses in N/m.
#pragma once

#include <string>
#include <string_view>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"

namespace gearimpact {

// How the bending and axial compliances are integrated. The first four
// integrate the tau-form (20)-(24); `xform` integrates (16)-(19) over the tooth
// centre line with every section built from the polar involute.
enum class StiffnessMethod { gsl_qag, gsl_cquad, boost_gauss_kronrod, boost_tanh_sinh, xform };

// The sign of the axial-force moment in M = Fb (l - x) -/+ Fa h. `physical` is
// the printed (14): the axial component, offset h towards the loaded flank,
// unbends the tooth. `flipped` adds it instead, as a possible slip in the
// authors' program (see the reproduction report).
enum class AxialMomentSign { physical, flipped };

struct StiffnessModel {
  StiffnessMethod method = StiffnessMethod::gsl_qag;
  AxialMomentSign moment_sign = AxialMomentSign::physical;
  // Requested of every rule. 1e-12 is within reach of all of them at every
  // contact position (tanh-sinh's level-difference estimate stalls near
  // 1e-13 on these integrands although its result is better).
  double relative_tolerance = 1e-12;
  // The quadrature rule the x-form route integrates with.
  StiffnessMethod xform_rule = StiffnessMethod::gsl_qag;
  // Which terms of (29) enter Ke. All by default; switching one off shows
  // what it contributes (the paper's section 8 compares them). At least one.
  bool hertz_term = true;
  bool bending_term = true;
  bool axial_term = true;
};

// Throws InputError unless at least one term of (29) is on and the tolerance
// is in [1e-14, 1e-2].
void validate(const StiffnessModel& model);

// Names used on the command line: gsl, gsl-cquad, boost-gk, boost-ts, xform.
StiffnessMethod parse_stiffness_method(std::string_view name);
std::string to_string(StiffnessMethod method);

InvoluteTooth tooth_of(const GearPair& pair, Gear gear);

// (4) Kh = pi E L / (4 (1 - nu^2)).
double hertz_stiffness(const GearPair& pair);

// The tau-form integrands, without the 1/(E L) factor, at section angle tau for
// a tooth of half angle theta_b loaded at contact angle phi.
// (20),(22),(23): 3 C(tau) (theta_b - tau) cos tau / (2 [sin tau + (theta_b - tau) cos tau]^3).
double bending_integrand(double theta_b, double phi, double tau, AxialMomentSign sign);
// (21),(24): (theta_b - tau) cos tau sin^2 phi / (2 [sin tau + (theta_b - tau) cos tau]).
double axial_integrand(double theta_b, double phi, double tau);

// 1/Kb and 1/Ka of one tooth, loaded at distance `contact_x_m` from the tangent
// point of its own base circle along the line of action (X1 for gear 1,
// lp - X1 for gear 2). The contact must lie above the base circle: X > 0.
struct ToothCompliance {
  double bending_m_per_n;
  double axial_m_per_n;
};
ToothCompliance tooth_compliance(const InvoluteTooth& tooth, double contact_x_m,
                                 double youngs_modulus_pa, double face_width_m,
                                 const StiffnessModel& model = {});

// Every stiffness of one pair in contact at X1 (from C1), and Ke by (29)
// over the terms the model switches on (kh, kb, ka are reported either way).
struct MeshStiffness {
  double kh;
  double kb1;
  double ka1;
  double kb2;
  double ka2;
  double ke;
};
MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model = {});

// (29) 1/Ke = 1/Kh + 1/Kb1 + 1/Ka1 + 1/Kb2 + 1/Ka2.
double series_stiffness(double kh, double kb1, double ka1, double kb2, double ka2);

// The series compliances of one pair as they enter (29), m/N. A term the
// model switches off is 0.
struct PairCompliance {
  double hertz_m_per_n;    // 1/Kh
  double bending_m_per_n;  // 1/Kb1 + 1/Kb2
  double axial_m_per_n;    // 1/Ka1 + 1/Ka2
  double total_m_per_n() const { return hertz_m_per_n + bending_m_per_n + axial_m_per_n; }
};
PairCompliance included_compliance(const StiffnessModel& model, double hertz_m_per_n,
                                   double bending_m_per_n, double axial_m_per_n);

}  // namespace gearimpact
