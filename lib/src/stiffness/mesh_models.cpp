#include "gearimpact/stiffness/mesh_models.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"

namespace gearimpact {

namespace {

// The foundation term's h_f = r_f / r_int needs the bore.
void require_bore(const RackGearGeometry& geometry, Gear gear) {
  if (!geometry.bore_diameter_m) {
    throw InputError(gear == Gear::one ? "bore_diameter1" : "bore_diameter2", "absent",
                     "a diameter in (0, " + format_number(2.0 * geometry.root_radius_m) +
                         ") m: the fillet-foundation term needs the bore (or switch the term off)");
  }
}

double foundation_h_f(const RackGearGeometry& gear) {
  return gear.root_radius_m / (0.5 * *gear.bore_diameter_m);
}

}  // namespace

std::vector<FoundationExtrapolation> foundation_extrapolations(const RackGearPairGeometry& pair,
                                                               const StiffnessModel& model) {
  if (!model.terms.has(Term::foundation)) return {};
  std::vector<FoundationExtrapolation> found;
  for (const auto& [gear, which] : {std::pair{&pair.gear1, Gear::one}, {&pair.gear2, Gear::two}}) {
    require_bore(*gear, which);
    for (const FoundationExtrapolation& e : foundation_extrapolation(
             which, foundation_h_f(*gear), foundation_root_half_angle(*gear, model.kind))) {
      found.push_back(e);
    }
  }
  return found;
}

double hertz_stiffness_two_materials(double width_m, double youngs_modulus1_pa,
                                     double poisson_ratio1, double youngs_modulus2_pa,
                                     double poisson_ratio2) {
  // docs/stiffness-models.md section 2, Hertz for materials 1 and 2.
  const double compliance1 = (1.0 - poisson_ratio1 * poisson_ratio1) / youngs_modulus1_pa;
  const double compliance2 = (1.0 - poisson_ratio2 * poisson_ratio2) / youngs_modulus2_pa;
  return 0.5 * pi * width_m / (compliance1 + compliance2);
}

double foundation_root_half_angle(const RackGearGeometry& gear, StiffnessModelKind kind) {
  if (kind == StiffnessModelKind::ross_compatible) {
    // ROSS's theta_f (docs/stiffness-models.md section 3). Written as 2 b / (z m),
    // its b = pi m / 4 + ha m tan a0 + rho (1 - sin a0) / cos a0 is the
    // round centre's b1 without the clearance's run c m tan a0 along the
    // rack flank, so it falls 2 c tan a0 / z short of where its own trochoid
    // meets the root circle.
    const double a0 = gear.pressure_angle_rad;
    const double rho_star = gear.rack_tip_radius_m / gear.module_m;
    return (0.5 * pi + 2.0 * std::tan(a0) * (gear.addendum_coefficient - rho_star) +
            2.0 * rho_star / std::cos(a0)) /
           gear.teeth;
  }
  return gear.root_half_angle_rad;
}

double foundation_load_height(const RackGearGeometry& gear, const ToothContact& contact,
                              StiffnessModelKind kind) {
  if (kind == StiffnessModelKind::ross_compatible) return contact.y_m - gear.root_radius_m;
  // Where the load line through (x_t, y_t) at angle tau to the x axis crosses
  // the centre line x = 0, measured from the root circle.
  return contact.y_m - contact.x_m * std::tan(contact.tau_rad) - gear.root_radius_m;
}

std::vector<FlankPiece> flank_to_contact(const RackGearGeometry& gear, double contact_tau_rad) {
  const RackGearGeometry* g = &gear;
  return {
      {[g](double gamma) { return trochoid_point(*g, gamma); }, 0.5 * pi, gear.pressure_angle_rad},
      {[g](double tau) { return involute_point(*g, tau); }, gear.form_tau_rad, contact_tau_rad}};
}

ToothCompliances tooth_compliances(const RackGearGeometry& gear, Gear which,
                                   const ToothContact& contact, double contact_width_m,
                                   const StiffnessModel& model) {
  const std::string name = which == Gear::one ? "gear1" : "gear2";
  const TermSet& terms = model.terms;
  const bool bending = terms.has(Term::bending);
  const bool shear = terms.has(Term::shear);
  const bool axial = terms.has(Term::axial);
  const bool foundation = terms.has(Term::foundation);
  if (!(bending || shear || axial || foundation)) {
    throw InputError("stiffness terms", "none of bending, shear, axial, foundation",
                     "at least one tooth term");
  }
  // The path's ends put the contact on a tip or a form point up to the
  // rounding of T1T2 - s: a few ulps of tan alpha are let through.
  const double slack = 64.0 * std::numeric_limits<double>::epsilon() *
                       (gear.tip_tau_rad + gear.half_tooth_angle_base_rad);
  if (!(contact.tau_rad >= gear.form_tau_rad - slack &&
        contact.tau_rad <= gear.tip_tau_rad + slack)) {
    throw InputError(name + " contact tau", contact.tau_rad,
                     "[" + format_number(gear.form_tau_rad) + ", " +
                         format_number(gear.tip_tau_rad) + "] rad: on the involute");
  }
  ToothCompliances c{};
  const double e = gear.youngs_modulus_pa;
  if (bending || shear || axial) {
    const double shear_modulus = e / (2.0 * (1.0 + gear.poisson_ratio));
    const BeamCompliance beam = tooth_beam_compliance(
        flank_to_contact(gear, contact.tau_rad), {contact.x_m, contact.y_m, contact.tau_rad},
        {e, shear_modulus, contact_width_m}, model.route, model.relative_tolerance);
    if (bending) c.bending_m_per_n = beam.bending_m_per_n;
    if (shear) c.shear_m_per_n = beam.shear_m_per_n;
    if (axial) c.axial_m_per_n = beam.axial_m_per_n;
  }
  if (foundation) {
    require_bore(gear, which);
    const double theta_f = foundation_root_half_angle(gear, model.kind);
    const double h_f = foundation_h_f(gear);
    const FoundationFit fit = sainsot_coefficients(h_f, theta_f);
    c.foundation_m_per_n = fillet_foundation_compliance(
        fit.coefficients, e, contact_width_m, foundation_load_height(gear, contact, model.kind),
        2.0 * gear.root_radius_m * theta_f, contact.tau_rad);
    // Far outside its range the fit can turn negative; that is no compliance.
    if (!(c.foundation_m_per_n > 0.0)) {
      throw InputError(which == Gear::one ? "bore_diameter1" : "bore_diameter2",
                       *gear.bore_diameter_m,
                       "values for which the foundation fit of Sainsot et al. gives a positive "
                       "compliance (here h_f = " +
                           format_number(h_f) + ", theta_f = " + format_number(theta_f) +
                           " rad; the fit covers h_f in [1.4, 7], theta_f in [0.01, 0.12] rad)");
    }
    c.foundation_extrapolated = fit.extrapolated;
  }
  return c;
}

void validate(const StiffnessModel& model, const RackGearPairGeometry& pair) {
  if (model.kind == StiffnessModelKind::yang_lin_1987) {
    throw InputError("stiffness_model", "\"" + to_string(model.kind) + "\"",
                     "a model of the rack-cut tooth from the root circle: \"" +
                         to_string(StiffnessModelKind::potential_energy) + "\" or \"" +
                         to_string(StiffnessModelKind::ross_compatible) + "\"");
  }
  validate_terms(model);
  if (model.terms.has(Term::foundation)) {
    require_bore(pair.gear1, Gear::one);
    require_bore(pair.gear2, Gear::two);
  }
}

PairStiffness pair_stiffness(const RackGearPairGeometry& pair, const StiffnessModel& model,
                             double s_m) {
  validate(model, pair);
  const PairContact contact = pair_contact(pair, s_m);
  const TermSet& on = model.terms;
  const bool any_tooth_term = on.has(Term::bending) || on.has(Term::shear) || on.has(Term::axial) ||
                              on.has(Term::foundation);
  PairStiffness k{};
  if (any_tooth_term) {
    k.gear1 = tooth_compliances(pair.gear1, Gear::one, contact.gear1, pair.contact_width_m, model);
    k.gear2 = tooth_compliances(pair.gear2, Gear::two, contact.gear2, pair.contact_width_m, model);
  }
  if (on.has(Term::hertz)) {
    k.hertz_m_per_n =
        1.0 / hertz_stiffness_two_materials(pair.contact_width_m, pair.gear1.youngs_modulus_pa,
                                            pair.gear1.poisson_ratio, pair.gear2.youngs_modulus_pa,
                                            pair.gear2.poisson_ratio);
  }
  // docs/stiffness-models.md section 2: one pair, every term in series.
  k.stiffness_n_per_m = 1.0 / (k.hertz_m_per_n + k.gear1.total_m_per_n() + k.gear2.total_m_per_n());
  return k;
}

}  // namespace gearimpact
