#include "gearimpact/stiffness/surface_faults.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/tooth_profile.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/tau_form.hpp"
#include "gearimpact/stiffness/x_form.hpp"
#include "solve_on.hpp"

namespace gearimpact {

namespace {

// sqrt(r^2 - Rb^2) as (r - Rb)(r + Rb), which keeps its precision just above
// the base circle.
double roll_distance_at_radius(double base_radius_m, double radius_m) {
  return std::sqrt((radius_m - base_radius_m) * (radius_m + base_radius_m));
}

// A contact computed at the end of a shortened segment lies on r_k up to the
// rounding of sqrt(Rb^2 + L^2): a few ulps above it are r_k.
bool above(double radius_m, double limit_m) {
  return radius_m > limit_m * (1.0 + 64.0 * std::numeric_limits<double>::epsilon());
}

// The radii [low, high] over which a fault changes the sections, what it
// makes of a section of half thickness x there, and whether no tooth is left
// there at all (a full-width chip, whose contact never reaches its band).
struct Band {
  double low_m;
  double high_m;
  std::function<SectionProperties(double)> section;
  bool empty;
  bool contains(double radius_m) const { return radius_m >= low_m && radius_m <= high_m; }
};

Band band_of(const Spall& spall, double b) {
  return {spall.start_radius_m, spall.end_radius_m,
          [spall, b](double x) { return spalled_section(spall, x, b); }, false};
}

Band band_of(const TipChip& chip, double b) {
  return {chip.radius_m, std::numeric_limits<double>::infinity(),
          [chip, b](double x) { return chipped_section(chip, x, b); }, !(chip.width_m < b)};
}

// The band's ends that lie strictly between two radii.
std::vector<double> band_ends_between(const Band& band, double r0, double r1) {
  std::vector<double> ends;
  for (double r : {band.low_m, band.high_m}) {
    if (r > r0 && r < r1) ends.push_back(r);
  }
  return ends;
}

void check_width(const std::string& field, double width_m, double b) {
  if (!(width_m > 0.0 && width_m <= b)) {
    throw InputError(field, width_m, "(0, " + format_number(b) + "] m: within the face width");
  }
}

// place_spall on any tooth: its involute from r_low to the tip r_high, and
// x(r) the half thickness of the section through the flank at radius r.
PlacedSpall place_spall_on(const Spall& spall, double base_radius_m, double r_low, double r_high,
                           const std::function<double(double)>& half_thickness_at, double b) {
  const double r1 = spall.start_radius_m;
  const double r2 = spall.end_radius_m;
  if (!(r1 >= r_low && r1 < r_high)) {
    throw InputError("spall start radius", r1,
                     "[" + format_number(r_low) + ", " + format_number(r_high) +
                         ") m: on the involute, below the tip");
  }
  if (!(r2 > r1 && r2 <= r_high)) {
    throw InputError("spall end radius", r2,
                     "(" + format_number(r1) + ", " + format_number(r_high) +
                         "] m: above the spall's start, up to the tip");
  }
  check_width("spall width b_s", spall.width_m, b);
  if (!(spall.depth_m >= 0.0)) throw InputError("spall depth d_s", spall.depth_m, ">= 0 m");
  // x rises to one maximum and falls along the involute (dx/dtau = -r_b (tau
  // + theta_b) sin tau): the band's thinnest section is one of its ends.
  const double x1 = half_thickness_at(r1);
  const double x2 = half_thickness_at(r2);
  const double x_min = std::min(x1, x2);
  const double r_min = x1 <= x2 ? r1 : r2;
  if (!(spall.depth_m < x_min)) {
    throw InputError("spall depth d_s", spall.depth_m,
                     "d_s < x = " + format_number(x_min) +
                         " m, the half thickness at r = " + format_number(r_min) +
                         " m, the thinnest section of the spall: the pit may not reach the centre "
                         "line");
  }
  return {spall, roll_distance_at_radius(base_radius_m, r1),
          roll_distance_at_radius(base_radius_m, r2)};
}

PlacedChip place_chip_on(const TipChip& chip, double r_root, double r_tip, const char* root_name,
                         double b) {
  if (!(chip.radius_m > r_root && chip.radius_m <= r_tip)) {
    throw InputError("chip radius r_k", chip.radius_m,
                     "(" + format_number(r_root) + ", " + format_number(r_tip) + "] m: above the " +
                         root_name + ", up to the tip");
  }
  check_width("chip width b_k", chip.width_m, b);
  return {chip, chip.width_m < b ? r_tip : chip.radius_m};
}

// The full-width chip's contact may not pass r_k.
void check_contact_below_chip(const TipChip& chip, double contact_radius_m, double b) {
  if (chip.width_m < b || !above(contact_radius_m, chip.radius_m)) return;
  throw InputError("contact radius", contact_radius_m,
                   "<= r_k = " + format_number(chip.radius_m) +
                       " m: a full-width chip ends this tooth's contact there "
                       "(chipped_contact_segment)");
}

// The radius of a flank point.
double radius_of(const FlankPiece& piece, double p) {
  const ProfilePoint q = piece.point(p);
  return std::hypot(q.x_m, q.y_m);
}

// tooth_beam_compliance of the rack-cut tooth with the band's sections. The
// flank is cut where its radius crosses the band's ends (it rises along
// every piece); each piece is in or out of the band as a whole, decided at
// its middle, so that no point near a cut is judged by rounding.
BeamCompliance banded_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                      const BeamMaterial& material, const Band& band,
                                      StiffnessRoute route, double relative_tolerance) {
  BeamCompliance sum{0.0, 0.0, 0.0};
  const BeamSections in_band = [&band](double x, double) {
    const SectionProperties p = band.section(x);
    return BeamSection{p.area_m2, p.second_moment_m4};
  };
  for (const FlankPiece& piece : flank) {
    const double r_root = radius_of(piece, piece.parameter_root);
    const double r_top = radius_of(piece, piece.parameter_top);
    std::vector<double> cuts{piece.parameter_root};
    for (double r : band_ends_between(band, r_root, r_top)) {
      cuts.push_back(solve_on([&](double p) { return radius_of(piece, p) - r; },
                              piece.parameter_root, piece.parameter_top));
    }
    cuts.push_back(piece.parameter_top);
    for (std::size_t i = 1; i < cuts.size(); ++i) {
      if (cuts[i] == cuts[i - 1]) continue;
      const FlankPiece part{piece.point, cuts[i - 1], cuts[i]};
      const bool inside = band.contains(radius_of(piece, 0.5 * (cuts[i - 1] + cuts[i])));
      // What lies in an empty band is the rounding above r_k of a contact at r_k.
      if (inside && band.empty) continue;
      const BeamCompliance c =
          inside ? tooth_beam_compliance({part}, load, material, route, relative_tolerance, in_band)
                 : tooth_beam_compliance({part}, load, material, route, relative_tolerance);
      sum.bending_m_per_n += c.bending_m_per_n;
      sum.shear_m_per_n += c.shear_m_per_n;
      sum.axial_m_per_n += c.axial_m_per_n;
    }
  }
  return sum;
}

ToothCompliances banded_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                          const ToothContact& contact, double contact_width_m,
                                          const StiffnessModel& model, const Band& band) {
  // The foundation (and the contact's range check) as for the healthy tooth.
  ToothCompliances c{};
  if (model.terms.has(Term::foundation)) {
    StiffnessModel foundation_only = model;
    for (Term t : {Term::bending, Term::shear, Term::axial}) foundation_only.terms.set(t, false);
    c = tooth_compliances(gear, which, contact, contact_width_m, foundation_only);
  }
  const double e = gear.youngs_modulus_pa;
  const BeamCompliance beam = banded_beam_compliance(
      flank_to_contact(gear, contact.tau_rad), {contact.x_m, contact.y_m, contact.tau_rad},
      {e, e / (2.0 * (1.0 + gear.poisson_ratio)), contact_width_m}, band, model.route,
      model.relative_tolerance);
  if (model.terms.has(Term::bending)) c.bending_m_per_n = beam.bending_m_per_n;
  if (model.terms.has(Term::shear)) c.shear_m_per_n = beam.shear_m_per_n;
  if (model.terms.has(Term::axial)) c.axial_m_per_n = beam.axial_m_per_n;
  return c;
}

void refuse_paper_model(const StiffnessModel& model, const char* what) {
  if (model.kind == StiffnessModelKind::yang_lin_1987) {
    throw InputError("stiffness_model", "\"" + to_string(model.kind) + "\"",
                     std::string("\"potential-energy\" or \"ross-compatible\" for a rack-cut "
                                 "tooth with ") +
                         what);
  }
}

// The paper's tooth with the band's sections, by the model's route: the
// integration range cut at the band's ends, each piece in or out of the band
// as a whole (decided at its middle).
Compliances banded_paper_tooth_compliances(const InvoluteTooth& tooth, double contact_x_m, double e,
                                           double b, const StiffnessModel& model,
                                           const Band& band) {
  const double rb = tooth.base_radius_m;
  const double theta_b = tooth.half_tooth_angle_rad;
  const double contact_radius = radius_at_roll_distance(rb, contact_x_m);
  const QuadratureTolerance tolerance{model.relative_tolerance, 0.0};
  Compliances c;
  // Integrates `integrand(p, in_band)` over the pieces between `ends`, with
  // `radius(p)` the flank radius of the section at p.
  const auto over_pieces = [&](const std::vector<double>& ends,
                               const std::function<double(double)>& radius,
                               const std::function<double(double, bool)>& integrand) {
    double sum = 0.0;
    for (std::size_t i = 1; i < ends.size(); ++i) {
      if (ends[i] == ends[i - 1]) continue;
      const bool inside = band.contains(radius(0.5 * (ends[i - 1] + ends[i])));
      if (inside && band.empty) continue;
      sum += integrate(
                 model.rule, [&](double p) { return integrand(p, inside); }, ends[i - 1], ends[i],
                 tolerance)
                 .value;
    }
    return sum;
  };
  if (model.route == StiffnessRoute::tau_form) {
    // (20)-(24) as tau_form_compliances. The section at tau meets the flank
    // at roll distance Rb (theta_b - tau), from the contact (tau = -phi) to
    // the base circle (tau = theta_b).
    const double phi = contact_x_m / rb - theta_b;
    const auto half_thickness = [&](double tau) {
      return rb * (std::sin(tau) + (theta_b - tau) * std::cos(tau));
    };
    const auto radius = [&](double tau) {
      return radius_at_roll_distance(rb, rb * (theta_b - tau));
    };
    std::vector<double> ends{-phi, theta_b};
    for (double r : band_ends_between(band, rb, contact_radius)) {
      ends.push_back(theta_b - roll_distance_at_radius(rb, r) / rb);
    }
    std::sort(ends.begin(), ends.end());
    // The healthy section over the faulted one: the factor by which each
    // integrand of the healthy tooth grows.
    const auto bending_factor = [&](double tau, bool inside) {
      if (!inside) return 1.0;
      const double x = half_thickness(tau);
      return healthy_section(x, b).second_moment_m4 / band.section(x).second_moment_m4;
    };
    const auto axial_factor = [&](double tau, bool inside) {
      if (!inside) return 1.0;
      const double x = half_thickness(tau);
      return healthy_section(x, b).area_m2 / band.section(x).area_m2;
    };
    const double scale = 1.0 / (e * b);
    c.of(Term::bending) = scale * over_pieces(ends, radius, [&](double tau, bool inside) {
                            return bending_integrand(theta_b, phi, tau, model.moment_sign) *
                                   bending_factor(tau, inside);
                          });
    c.of(Term::axial) = scale * over_pieces(ends, radius, [&](double tau, bool inside) {
                          return axial_integrand(theta_b, phi, tau) * axial_factor(tau, inside);
                        });
    return c;
  }
  // (16)-(19) as x_form_compliances: x = l u^2 along the centre line; the
  // flank point at radius r lies r cos psi(r) - Rb cos theta_b above the
  // base-circle section.
  const PolarContact contact = polar_contact(tooth, contact_x_m);
  const double l = contact.arm.height_l_m;
  const double h = contact.arm.offset_h_m;
  const double fb = std::cos(contact.phi_rad);
  const double fa = std::sin(contact.phi_rad);
  const double axial_arm = model.moment_sign == AxialMomentSign::physical ? -fa * h : fa * h;
  const double root_height = rb * std::cos(theta_b);
  std::vector<double> ends{0.0};
  for (double r : band_ends_between(band, rb, contact_radius)) {
    const double height = r * std::cos(flank_half_angle(tooth, r)) - root_height;
    if (height > 0.0 && height < l) ends.push_back(std::sqrt(height / l));
  }
  ends.push_back(1.0);
  std::sort(ends.begin(), ends.end());
  const auto radius = [&](double u) {
    const double x = l * u * u;
    return std::hypot(section_half_thickness(tooth, x), root_height + x);
  };
  const auto section = [&](double y, bool inside) {
    return inside ? band.section(y) : healthy_section(y, b);
  };
  c.of(Term::bending) = over_pieces(ends, radius, [&](double u, bool inside) {
    const double x = l * u * u;
    const double y = section_half_thickness(tooth, x);
    const double moment = fb * (l - x) + axial_arm;
    return moment * moment / (e * section(y, inside).second_moment_m4) * 2.0 * l * u;
  });
  c.of(Term::axial) = over_pieces(ends, radius, [&](double u, bool inside) {
    const double y = section_half_thickness(tooth, l * u * u);
    return fa * fa / (e * section(y, inside).area_m2) * 2.0 * l * u;
  });
  return c;
}

Compliances healthy_paper_tooth(const InvoluteTooth& tooth, double contact_x_m, double e, double b,
                                const StiffnessModel& model) {
  return model.route == StiffnessRoute::tau_form
             ? tau_form_compliances(tooth, contact_x_m, e, b, model)
             : x_form_compliances(tooth, contact_x_m, e, b, model);
}

}  // namespace

double radius_at_roll_distance(double base_radius_m, double roll_distance_m) {
  return std::hypot(base_radius_m, roll_distance_m);
}

SectionProperties spalled_section(const Spall& spall, double x, double b) {
  const double b_s = spall.width_m;
  const double t = 2.0 * x - spall.depth_m;
  const SectionProperties intact = healthy_section(x, b - b_s);
  return {intact.area_m2 + b_s * t, intact.second_moment_m4 + b_s * t * t * t / 12.0};
}

SectionProperties chipped_section(const TipChip& chip, double x, double b) {
  return healthy_section(x, b - chip.width_m);
}

double spall_contact_length(const Spall& spall, CrackFlank contact_flank, double contact_radius_m,
                            double b) {
  const bool met = spall.flank == contact_flank && spall.depth_m > 0.0 &&
                   contact_radius_m >= spall.start_radius_m &&
                   contact_radius_m <= spall.end_radius_m;
  return met ? b - spall.width_m : b;
}

double chip_contact_length(const TipChip& chip, double contact_radius_m, double b) {
  return above(contact_radius_m, chip.radius_m) ? b - chip.width_m : b;
}

PlacedSpall place_spall(const Spall& spall, const RackGearGeometry& gear, double b) {
  const double rb = gear.base_radius_m;
  const double theta_b = gear.half_tooth_angle_base_rad;
  return place_spall_on(
      spall, rb, gear.form_radius_m, gear.tip_radius_m,
      [&](double r) {
        return involute_point(gear, roll_distance_at_radius(rb, r) / rb - theta_b).x_m;
      },
      b);
}

PlacedSpall place_spall(const Spall& spall, const GearPair& pair, Gear which) {
  const InvoluteTooth tooth = tooth_of(pair, which);
  return place_spall_on(
      spall, tooth.base_radius_m, tooth.base_radius_m, tip_radius(pair, which),
      [&](double r) { return r * std::sin(flank_half_angle(tooth, r)); }, pair.face_width_m);
}

double flank_half_thickness(const GearPair& pair, Gear which, StiffnessModelKind kind,
                            double radius_m) {
  if (kind == StiffnessModelKind::yang_lin_1987) {
    return radius_m * std::sin(flank_half_angle(tooth_of(pair, which), radius_m));
  }
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const RackGearGeometry& gear = which == Gear::one ? geometry.gear1 : geometry.gear2;
  const double rb = gear.base_radius_m;
  return involute_point(gear,
                        roll_distance_at_radius(rb, radius_m) / rb - gear.half_tooth_angle_base_rad)
      .x_m;
}

PlacedChip place_chip(const TipChip& chip, const RackGearGeometry& gear, double b) {
  return place_chip_on(chip, gear.root_radius_m, gear.tip_radius_m, "root circle", b);
}

PlacedChip place_chip(const TipChip& chip, const GearPair& pair, Gear which) {
  return place_chip_on(chip, base_radius(pair, which), tip_radius(pair, which),
                       "base circle (the paper's tooth starts there)", pair.face_width_m);
}

std::optional<ContactSegment> chipped_contact_segment(const GearPair& pair, Gear which,
                                                      const TipChip& chip) {
  check_width("chip width b_k", chip.width_m, pair.face_width_m);
  const ContactSegment segment = contact_segment(pair);
  if (chip.width_m < pair.face_width_m) return segment;
  const double rb = base_radius(pair, which);
  // Below the base circle the involute, and with it every contact, is gone.
  const double reach = chip.radius_m > rb ? roll_distance_at_radius(rb, chip.radius_m) : 0.0;
  ContactSegment s = segment;
  if (which == Gear::one) {
    s.end_m = std::min(segment.end_m, reach);
  } else {
    s.start_m = std::max(segment.start_m, line_of_action_length(pair) - reach);
  }
  if (!(s.end_m > s.start_m)) return std::nullopt;
  return s;
}

ToothCompliances spalled_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const Spall& spall) {
  refuse_paper_model(model, "a spall");
  place_spall(spall, gear, contact_width_m);
  // A contact at or below the band loads no section of it: the healthy tooth.
  if (!(spall.depth_m > 0.0) || contact.radius_m <= spall.start_radius_m) {
    return tooth_compliances(gear, which, contact, contact_width_m, model);
  }
  return banded_tooth_compliances(gear, which, contact, contact_width_m, model,
                                  band_of(spall, contact_width_m));
}

ToothCompliances chipped_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const TipChip& chip) {
  refuse_paper_model(model, "a chip");
  place_chip(chip, gear, contact_width_m);
  check_contact_below_chip(chip, contact.radius_m, contact_width_m);
  if (!(chip.radius_m < gear.tip_radius_m) || contact.radius_m <= chip.radius_m) {
    return tooth_compliances(gear, which, contact, contact_width_m, model);
  }
  return banded_tooth_compliances(gear, which, contact, contact_width_m, model,
                                  band_of(chip, contact_width_m));
}

Compliances spalled_paper_tooth_compliances(const GearPair& pair, Gear which, double contact_x_m,
                                            const StiffnessModel& model, const Spall& spall) {
  place_spall(spall, pair, which);
  const InvoluteTooth tooth = tooth_of(pair, which);
  const double e = youngs_modulus(pair, which);
  const double b = pair.face_width_m;
  // A contact at or below the band loads no section of it: the healthy tooth.
  if (!(spall.depth_m > 0.0) ||
      radius_at_roll_distance(tooth.base_radius_m, contact_x_m) <= spall.start_radius_m) {
    return healthy_paper_tooth(tooth, contact_x_m, e, b, model);
  }
  return banded_paper_tooth_compliances(tooth, contact_x_m, e, b, model, band_of(spall, b));
}

Compliances chipped_paper_tooth_compliances(const GearPair& pair, Gear which, double contact_x_m,
                                            const StiffnessModel& model, const TipChip& chip) {
  place_chip(chip, pair, which);
  const InvoluteTooth tooth = tooth_of(pair, which);
  const double e = youngs_modulus(pair, which);
  const double b = pair.face_width_m;
  check_contact_below_chip(chip, radius_at_roll_distance(tooth.base_radius_m, contact_x_m), b);
  if (!(chip.radius_m < tip_radius(pair, which)) ||
      radius_at_roll_distance(tooth.base_radius_m, contact_x_m) <= chip.radius_m) {
    return healthy_paper_tooth(tooth, contact_x_m, e, b, model);
  }
  return banded_paper_tooth_compliances(tooth, contact_x_m, e, b, model, band_of(chip, b));
}

SpallWidthFactors spall_width_factors(double contact_length_m, double face_width_m,
                                      double root_thickness_m) {
  const double b = face_width_m;
  const double length = contact_length_m;
  if (!(b > 0.0 && length > 0.0 && length <= b && root_thickness_m > 0.0)) {
    throw std::invalid_argument("spall_width_factors: 0 < L <= b and S_f > 0");
  }
  // b_eff = L + lambda (1 - exp(-(b - L) / lambda)), with expm1 for a short unloaded width.
  const auto factor = [&](double lambda) {
    return b / (length - lambda * std::expm1(-(b - length) / lambda));
  };
  return {factor(kSpallBeamSpread * root_thickness_m),
          factor(kSpallFoundationSpread * root_thickness_m)};
}

double root_thickness(const RackGearGeometry& gear) {
  return 2.0 * gear.root_radius_m * std::sin(gear.root_half_angle_rad);
}

}  // namespace gearimpact
