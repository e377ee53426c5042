#include "gearimpact/stiffness/root_crack.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/tau_form.hpp"
#include "gearimpact/stiffness/x_form.hpp"
#include "solve_on.hpp"

namespace gearimpact {

namespace {

// Every width integrand below is a polynomial the 61-point rule integrates
// exactly; the tolerance only asks the estimate to confirm it.
constexpr QuadratureTolerance kWidthTolerance{1e-13, 0.0};

// t = x + min(x, h_q) + max(0, x - h_c) with h_q = h_c - s q <= h_c is
// 2 x - max(0, s q - delta), delta = max(0, h_c - x): the slice loses what
// of s q reaches past the gap between the section's side and h_c.
double slice_height(double x, double cut) {
  return 2.0 * x - cut;
}

// Int t dz and Int t^3 / 12 dz over a set of z where the slices are cut by
// `cut(p)`, p running over [p0, p1] with dz = weight(p) dp, plus `intact_m`
// of uncut width.
SectionProperties integrate_slices(double x, double intact_m,
                                   const std::function<double(double)>& cut,
                                   const std::function<double(double)>& weight, double p0,
                                   double p1) {
  const double t0 = 2.0 * x;
  SectionProperties s{intact_m * t0, intact_m * t0 * t0 * t0 / 12.0};
  if (p1 > p0) {
    s.area_m2 += integrate_gsl_qag([&](double p) { return slice_height(x, cut(p)) * weight(p); },
                                   p0, p1, kWidthTolerance)
                     .value;
    s.second_moment_m4 += integrate_gsl_qag(
                              [&](double p) {
                                const double t = slice_height(x, cut(p));
                                return t * t * t / 12.0 * weight(p);
                              },
                              p0, p1, kWidthTolerance)
                              .value;
  }
  return s;
}

// The heights at which x(y) - level changes sign on the flank, above y_min:
// each piece sampled at 64 points, each sign change solved for.
std::vector<double> heights_where_half_thickness_is(const std::vector<FlankPiece>& flank,
                                                    double level, double y_min) {
  std::vector<double> found;
  for (const FlankPiece& piece : flank) {
    const auto f = [&](double p) { return piece.point(p).x_m - level; };
    constexpr int samples = 64;
    double p_prev = piece.parameter_root;
    double f_prev = f(p_prev);
    for (int i = 1; i <= samples; ++i) {
      const double p = piece.parameter_root + (piece.parameter_top - piece.parameter_root) * i /
                                                  static_cast<double>(samples);
      const double f_here = f(p);
      if ((f_prev < 0.0 && f_here > 0.0) || (f_prev > 0.0 && f_here < 0.0)) {
        const double y = piece.point(solve_on(f, p_prev, p)).y_m;
        if (y > y_min) found.push_back(y);
      }
      p_prev = p;
      f_prev = f_here;
    }
  }
  return found;
}

// The parameter at which the piece reaches height y (y strictly inside it).
double parameter_at(const FlankPiece& piece, double y) {
  return solve_on([&](double p) { return piece.point(p).y_m - y; }, piece.parameter_root,
                  piece.parameter_top);
}

// The flank with every piece cut at the heights strictly inside it.
std::vector<FlankPiece> split_at_heights(const std::vector<FlankPiece>& flank,
                                         std::vector<double> heights) {
  std::sort(heights.begin(), heights.end());
  std::vector<FlankPiece> split;
  for (const FlankPiece& piece : flank) {
    const double y_root = piece.point(piece.parameter_root).y_m;
    const double y_top = piece.point(piece.parameter_top).y_m;
    double p_start = piece.parameter_root;
    for (double y : heights) {
      if (!(y > y_root && y < y_top)) continue;
      const double p = parameter_at(piece, y);
      if (p == p_start || p == piece.parameter_top) continue;
      split.push_back({piece.point, p_start, p});
      p_start = p;
    }
    split.push_back({piece.point, p_start, piece.parameter_top});
  }
  return split;
}

// The rack-cut tooth from the root circle to its tip.
std::vector<FlankPiece> whole_flank(const RackGearGeometry& gear) {
  return flank_to_contact(gear, gear.tip_tau_rad);
}

}  // namespace

double crack_depth_at(const RootCrack& crack, double z_m, double face_width_m) {
  switch (crack.profile) {
    case CrackProfile::uniform:
      return crack.depth_m;
    case CrackProfile::partial_width:
      return z_m < crack.width_m ? crack.depth_m * std::sqrt((crack.width_m - z_m) / crack.width_m)
                                 : 0.0;
    case CrackProfile::full_width:
      return std::sqrt((crack.end_depth_m * crack.end_depth_m - crack.depth_m * crack.depth_m) *
                           z_m / face_width_m +
                       crack.depth_m * crack.depth_m);
  }
  return 0.0;
}

double largest_crack_depth(const RootCrack& crack) {
  return crack.profile == CrackProfile::full_width ? std::max(crack.depth_m, crack.end_depth_m)
                                                   : crack.depth_m;
}

double smallest_crack_depth(const RootCrack& crack) {
  switch (crack.profile) {
    case CrackProfile::uniform:
      return crack.depth_m;
    case CrackProfile::partial_width:
      return 0.0;  // q(W_c) = 0
    case CrackProfile::full_width:
      return std::min(crack.depth_m, crack.end_depth_m);
  }
  return 0.0;
}

SectionProperties healthy_section(double x, double b) {
  // The expressions of tooth_beam.cpp, so that an uncut section is the
  // healthy one to the bit.
  return {2.0 * x * b, 2.0 / 3.0 * x * x * x * b};
}

namespace {

// The partial- and full-width profiles of cut_section, where the cut
// reaches past the gap delta.
SectionProperties cut_across_width(const RootCrack& crack, double s, double x, double delta,
                                   double b) {
  if (crack.profile == CrackProfile::partial_width) {
    // z = W_c (1 - w^2), q = q0 w, dz = 2 W_c w dw; cut where s q0 w > delta.
    const double a = s * crack.depth_m;
    const double w0 = delta / a;
    const double cut_width = crack.width_m * (1.0 - w0 * w0);
    return integrate_slices(
        x, b - cut_width, [&](double w) { return a * w - delta; },
        [&](double w) { return 2.0 * crack.width_m * w; }, w0, 1.0);
  }
  const double q0 = crack.depth_m;
  const double q2 = crack.end_depth_m;
  if (q0 == q2) {
    const double t = slice_height(x, s * q0 - delta);
    return {b * t, b * t * t * t / 12.0};
  }
  // z = (v^2 - q0^2) b / (q2^2 - q0^2), q = v, |dz| = 2 v b / |q2^2 - q0^2| dv.
  const double span = std::abs(q2 * q2 - q0 * q0);
  const double v_low = std::max(delta / s, std::min(q0, q2));
  const double v_high = std::max(q0, q2);
  const double cut_width = b * (v_high * v_high - v_low * v_low) / span;
  return integrate_slices(
      x, b - cut_width, [&](double v) { return s * v - delta; },
      [&](double v) { return 2.0 * v * b / span; }, v_low, v_high);
}

// cracked_section with s = sin nu given: the sections of one crack at many
// heights compute the sine once, and the uniform depth's closed form stays
// small enough to inline into their integrands.
inline SectionProperties cut_section(const RootCrack& crack, double s, double x, double h_c,
                                     double b) {
  const double delta = std::max(0.0, h_c - x);
  const double largest =
      crack.profile == CrackProfile::uniform ? crack.depth_m : largest_crack_depth(crack);
  // Nothing reaches past the gap: the healthy section.
  if (!(s * largest > delta)) return healthy_section(x, b);
  if (crack.profile != CrackProfile::uniform) return cut_across_width(crack, s, x, delta, b);
  const double t = slice_height(x, s * crack.depth_m - delta);
  return {b * t, b * t * t * t / 12.0};
}

}  // namespace

SectionProperties cracked_section(const RootCrack& crack, double x, double h_c, double b) {
  return cut_section(crack, std::sin(crack.angle_rad), x, h_c, b);
}

SectionProperties cracked_section_over_width(const std::function<double(double)>& depth_m_at_z,
                                             const std::vector<double>& breaks_m, double sin_nu,
                                             double x, double h_c, double b) {
  const double delta = std::max(0.0, h_c - x);
  const auto cut = [&](double z) { return std::max(0.0, sin_nu * depth_m_at_z(z) - delta); };
  std::vector<double> ends{0.0};
  for (double z : breaks_m) ends.push_back(z);
  ends.push_back(b);
  SectionProperties s{0.0, 0.0};
  for (std::size_t i = 1; i < ends.size(); ++i) {
    const SectionProperties piece = integrate_slices(
        x, 0.0, cut, [](double) { return 1.0; }, ends[i - 1], ends[i]);
    s.area_m2 += piece.area_m2;
    s.second_moment_m4 += piece.second_moment_m4;
  }
  return s;
}

double default_crack_start_radius(const RackGearGeometry& gear, StiffnessModelKind kind) {
  if (kind == StiffnessModelKind::yang_lin_1987) return gear.base_radius_m;
  // On the trochoid the tangent turns from across the tooth (gamma = pi/2, at
  // the root circle) towards the involute's direction (gamma = a0): the 30 deg
  // point is where |dx| = tan 30 deg |dy|.
  const double tan30 = std::tan(pi / 6.0);
  const auto f = [&](double gamma) {
    const ProfilePoint p = trochoid_point(gear, gamma);
    return std::abs(p.dx_m) - tan30 * std::abs(p.dy_m);
  };
  // Just inside pi/2: at the root circle itself dy = 0.
  const double top = 0.5 * pi - 1e-9;
  if (!(f(top) > 0.0 && f(gear.pressure_angle_rad) < 0.0)) {
    throw InputError("crack start radius", "absent",
                     "a radius given explicitly: this tooth's fillet has no point whose tangent "
                     "makes 30 deg with the centre line");
  }
  return trochoid_point(gear, solve_on(f, gear.pressure_angle_rad, top)).y_m;
}

namespace {

// The checks that need no tooth: depths, width, angle.
void check_crack_shape(const RootCrack& crack, double b) {
  if (!(crack.depth_m >= 0.0)) throw InputError("crack depth q", crack.depth_m, ">= 0 m");
  if (crack.profile == CrackProfile::full_width && !(crack.end_depth_m >= 0.0)) {
    throw InputError("crack end depth q2", crack.end_depth_m, ">= 0 m");
  }
  if (crack.profile == CrackProfile::partial_width &&
      !(crack.width_m > 0.0 && crack.width_m <= b)) {
    throw InputError("crack width W_c", crack.width_m,
                     "(0, " + format_number(b) + "] m: within the face width");
  }
  if (!(crack.angle_rad > 0.0 && crack.angle_rad <= 0.5 * pi)) {
    throw InputError("crack angle nu", crack.angle_rad, "(0, pi/2] rad");
  }
}

// The crack tip may not reach the centre line (docs/stiffness-models.md, "A
// root crack in one tooth", Refusals): the reading's h_c - q sin nu, the
// cracked side's extent, is a distance from that line and turns negative past it.
void check_crack_reach(const RootCrack& crack, double h_c, double r_s) {
  const double q_top = largest_crack_depth(crack);
  const double reach = q_top * std::sin(crack.angle_rad);
  if (!(reach < h_c)) {
    throw InputError(
        crack.profile == CrackProfile::full_width && crack.end_depth_m > crack.depth_m
            ? "crack end depth q2"
            : "crack depth q",
        q_top,
        "q sin nu < h_c: the crack may not pass the tooth centre line; here q sin nu "
        "= " +
            format_number(reach) + " m with nu = " + format_number(crack.angle_rad * 180.0 / pi) +
            " deg and h_c = " + format_number(h_c) + " m at r_s = " + format_number(r_s) +
            " m, so q < " + format_number(h_c / std::sin(crack.angle_rad)) + " m");
  }
}

}  // namespace

PlacedCrack place_crack(const RootCrack& crack, const RackGearGeometry& gear,
                        StiffnessModelKind kind, double b) {
  check_crack_shape(crack, b);
  const double r_s =
      crack.start_radius_m ? *crack.start_radius_m : default_crack_start_radius(gear, kind);
  const double r_low =
      kind == StiffnessModelKind::yang_lin_1987 ? gear.base_radius_m : gear.root_radius_m;
  if (!(r_s >= r_low && r_s < gear.tip_radius_m)) {
    throw InputError("crack start radius r_s", r_s,
                     "[" + format_number(r_low) + ", " + format_number(gear.tip_radius_m) +
                         ") m: on the tooth, below its tip");
  }
  // h_c = x(r_s) on the flank from the root circle.
  double h_c = 0.0;
  for (const FlankPiece& piece : whole_flank(gear)) {
    const double y_root = piece.point(piece.parameter_root).y_m;
    const double y_top = piece.point(piece.parameter_top).y_m;
    if (r_s <= y_root) {
      h_c = piece.point(piece.parameter_root).x_m;
      break;
    }
    if (r_s <= y_top) {
      h_c = piece.point(parameter_at(piece, r_s)).x_m;
      break;
    }
  }
  check_crack_reach(crack, h_c, r_s);
  return {crack, r_s, h_c};
}

BeamCompliance cracked_beam_compliance(const std::vector<FlankPiece>& flank, const BeamLoad& load,
                                       const BeamMaterial& material, const PlacedCrack& placed,
                                       StiffnessRoute route, double relative_tolerance) {
  const double r_s = placed.start_radius_m;
  const double h_c = placed.start_half_thickness_m;
  const double s = std::sin(placed.crack.angle_rad);
  // A crack of depth 0 cuts nothing: the healthy tooth, computed as it is.
  if (!(s * largest_crack_depth(placed.crack) > 0.0)) {
    return tooth_beam_compliance(flank, load, material, route, relative_tolerance);
  }
  // Where the section jumps (r_s) and where its cut kinks: x = h_c (the
  // bulge's part beyond h_c starts or stops) and x = h_c - s q for the
  // largest and the smallest depth (the cut starts or ends across the face).
  std::vector<double> heights{r_s};
  for (double level : {h_c, h_c - s * largest_crack_depth(placed.crack),
                       h_c - s * smallest_crack_depth(placed.crack)}) {
    for (double y : heights_where_half_thickness_is(flank, level, r_s)) heights.push_back(y);
  }
  const RootCrack crack = placed.crack;
  const double b = material.width_m;
  // Exactly at r_s the section is the cracked one; rounding of the split
  // point is the parameter solver's, far below the tolerance's reach.
  const BeamSections sections = [crack, r_s, h_c, b](double x, double y) {
    const SectionProperties p =
        y >= r_s ? cracked_section(crack, x, h_c, b) : healthy_section(x, b);
    return BeamSection{p.area_m2, p.second_moment_m4};
  };
  return tooth_beam_compliance(split_at_heights(flank, heights), load, material, route,
                               relative_tolerance, sections);
}

ToothCompliances cracked_tooth_compliances(const RackGearGeometry& gear, Gear which,
                                           const ToothContact& contact, double contact_width_m,
                                           const StiffnessModel& model, const RootCrack& crack) {
  if (model.kind == StiffnessModelKind::yang_lin_1987) {
    throw InputError("stiffness_model", "\"" + to_string(model.kind) + "\"",
                     "\"potential-energy\" or \"ross-compatible\" for a cracked rack-cut tooth");
  }
  const PlacedCrack placed = place_crack(crack, gear, model.kind, contact_width_m);
  // The foundation (and the contact's range check) as for the healthy tooth.
  ToothCompliances c{};
  if (model.terms.has(Term::foundation)) {
    StiffnessModel foundation_only = model;
    for (Term t : {Term::bending, Term::shear, Term::axial}) foundation_only.terms.set(t, false);
    c = tooth_compliances(gear, which, contact, contact_width_m, foundation_only);
  }
  const double e = gear.youngs_modulus_pa;
  const BeamCompliance beam = cracked_beam_compliance(
      flank_to_contact(gear, contact.tau_rad), {contact.x_m, contact.y_m, contact.tau_rad},
      {e, e / (2.0 * (1.0 + gear.poisson_ratio)), contact_width_m}, placed, model.route,
      model.relative_tolerance);
  if (model.terms.has(Term::bending)) c.bending_m_per_n = beam.bending_m_per_n;
  if (model.terms.has(Term::shear)) c.shear_m_per_n = beam.shear_m_per_n;
  if (model.terms.has(Term::axial)) c.axial_m_per_n = beam.axial_m_per_n;
  return c;
}

namespace {

// The points of [a, b] where f(p) - level changes sign, for each level, with
// a and b: the ends of pieces on which a section's cut is smooth. f sampled
// at 64 points, each sign change solved for.
std::vector<double> pieces_between(const std::function<double(double)>& f,
                                   const std::vector<double>& levels, double a, double b) {
  std::vector<double> ends{a, b};
  constexpr int samples = 64;
  for (double level : levels) {
    const auto g = [&](double p) { return f(p) - level; };
    double p_prev = a;
    double g_prev = g(a);
    for (int i = 1; i <= samples; ++i) {
      const double p = a + (b - a) * i / static_cast<double>(samples);
      const double g_here = g(p);
      if ((g_prev < 0.0 && g_here > 0.0) || (g_prev > 0.0 && g_here < 0.0)) {
        ends.push_back(solve_on(g, p_prev, p));
      }
      p_prev = p;
      g_prev = g_here;
    }
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

double integrate_pieces(QuadratureRule rule, const Integrand& f, const std::vector<double>& ends,
                        QuadratureTolerance tolerance) {
  double sum = 0.0;
  for (std::size_t i = 1; i < ends.size(); ++i) {
    sum += integrate(rule, f, ends[i - 1], ends[i], tolerance).value;
  }
  return sum;
}

}  // namespace

double paper_crack_start_half_thickness(const InvoluteTooth& tooth) {
  return tooth.base_radius_m * std::sin(tooth.half_tooth_angle_rad);
}

void check_paper_crack(const InvoluteTooth& tooth, double b, const RootCrack& crack) {
  check_crack_shape(crack, b);
  const double rb = tooth.base_radius_m;
  if (crack.start_radius_m) {
    throw InputError("crack start radius r_s", *crack.start_radius_m,
                     "absent for yang-lin-1987: the paper's tooth, and its crack, start at the "
                     "base-circle section (r_s = " +
                         format_number(rb) + " m)");
  }
  check_crack_reach(crack, paper_crack_start_half_thickness(tooth), rb);
}

Compliances cracked_paper_tooth_compliances(const InvoluteTooth& tooth, double contact_x_m,
                                            double e, double b, const StiffnessModel& model,
                                            const RootCrack& crack) {
  check_paper_crack(tooth, b, crack);
  const double rb = tooth.base_radius_m;
  const double theta_b = tooth.half_tooth_angle_rad;
  const double h_c = paper_crack_start_half_thickness(tooth);
  const double s = std::sin(crack.angle_rad);
  if (!(s * largest_crack_depth(crack) > 0.0)) {
    return model.route == StiffnessRoute::tau_form
               ? tau_form_compliances(tooth, contact_x_m, e, b, model)
               : x_form_compliances(tooth, contact_x_m, e, b, model);
  }
  // Kinks of the cut (as in cracked_beam_compliance); every section of the
  // paper's tooth is at or above the start.
  const std::vector<double> levels{h_c, h_c - s * largest_crack_depth(crack),
                                   h_c - s * smallest_crack_depth(crack)};
  // The healthy section over the cracked one: the factor by which each
  // integrand of the healthy tooth grows.
  const auto bending_factor = [&](double x) {
    return healthy_section(x, b).second_moment_m4 /
           cracked_section(crack, x, h_c, b).second_moment_m4;
  };
  const auto axial_factor = [&](double x) {
    return healthy_section(x, b).area_m2 / cracked_section(crack, x, h_c, b).area_m2;
  };
  const QuadratureTolerance tolerance{model.relative_tolerance, 0.0};
  Compliances c;
  if (model.route == StiffnessRoute::tau_form) {
    // (20)-(24) as tau_form_compliances, the section at tau of half
    // thickness Rb [sin tau + (theta_b - tau) cos tau].
    const double phi = contact_x_m / rb - theta_b;
    const auto half_thickness = [&](double tau) {
      return rb * (std::sin(tau) + (theta_b - tau) * std::cos(tau));
    };
    const std::vector<double> ends = pieces_between(half_thickness, levels, -phi, theta_b);
    const double scale = 1.0 / (e * b);
    c.of(Term::bending) =
        scale * integrate_pieces(
                    model.rule,
                    [&](double tau) {
                      return bending_integrand(theta_b, phi, tau, model.moment_sign) *
                             bending_factor(half_thickness(tau));
                    },
                    ends, tolerance);
    c.of(Term::axial) =
        scale * integrate_pieces(
                    model.rule,
                    [&](double tau) {
                      return axial_integrand(theta_b, phi, tau) * axial_factor(half_thickness(tau));
                    },
                    ends, tolerance);
    return c;
  }
  // (16)-(19) as x_form_compliances: x = l u^2 along the centre line.
  const PolarContact contact = polar_contact(tooth, contact_x_m);
  const double l = contact.arm.height_l_m;
  const double h = contact.arm.offset_h_m;
  const double fb = std::cos(contact.phi_rad);
  const double fa = std::sin(contact.phi_rad);
  const double axial_arm = model.moment_sign == AxialMomentSign::physical ? -fa * h : fa * h;
  const auto half_thickness = [&](double u) { return section_half_thickness(tooth, l * u * u); };
  const std::vector<double> ends = pieces_between(half_thickness, levels, 0.0, 1.0);
  c.of(Term::bending) = integrate_pieces(
      model.rule,
      [&](double u) {
        const double x = l * u * u;
        const double y = section_half_thickness(tooth, x);
        const double moment = fb * (l - x) + axial_arm;
        return moment * moment / (e * cracked_section(crack, y, h_c, b).second_moment_m4) * 2.0 *
               l * u;
      },
      ends, tolerance);
  c.of(Term::axial) = integrate_pieces(
      model.rule,
      [&](double u) {
        const double y = half_thickness(u);
        return fa * fa / (e * cracked_section(crack, y, h_c, b).area_m2) * 2.0 * l * u;
      },
      ends, tolerance);
  return c;
}

namespace {

// The largest cut, q_max sin nu.
double largest_cut(const RootCrack& crack, double sin_nu) {
  return sin_nu * largest_crack_depth(crack);
}

// Whether the section of half thickness x (at or above the start) is cut.
bool is_cut(const RootCrack& crack, double sin_nu, double x, double h_c) {
  return largest_cut(crack, sin_nu) > std::max(0.0, h_c - x);
}

// The bending and the axial change at one point.
struct PointChange {
  double bending;
  double axial;
};

// The integrals over the pieces between `ends` of both parts of f, by one
// rule: the axial integral of a piece asks for the points its bending integral
// did, in the same order (the same rule on the same interval), so each
// point's section, the costly part of f, is found once. A point it asks for
// beyond them is evaluated.
template <class PointChangeAt>
PointChange integrate_both(QuadratureRule rule, const PointChangeAt& f,
                           const std::vector<double>& ends, QuadratureTolerance tolerance) {
  // What the two passes share, captured by one reference so that the
  // integrands stay small enough for std::function to hold without
  // allocating.
  struct Points {
    const PointChangeAt& f;
    std::vector<std::pair<double, double>> axial_at;
    std::size_t next = 0;
  } points{f, {}, 0};
  points.axial_at.reserve(61);  // the 61-point rules' first pass
  PointChange sum{0.0, 0.0};
  for (std::size_t i = 1; i < ends.size(); ++i) {
    points.axial_at.clear();
    sum.bending += integrate(
                       rule,
                       [&points](double p) {
                         const PointChange c = points.f(p);
                         points.axial_at.emplace_back(p, c.axial);
                         return c.bending;
                       },
                       ends[i - 1], ends[i], tolerance)
                       .value;
    points.next = 0;
    sum.axial += integrate(
                     rule,
                     [&points](double p) {
                       std::vector<std::pair<double, double>>& at = points.axial_at;
                       if (points.next < at.size() && at[points.next].first == p) {
                         return at[points.next++].second;
                       }
                       points.next = at.size();
                       return points.f(p).axial;
                     },
                     ends[i - 1], ends[i], tolerance)
                     .value;
  }
  return sum;
}

}  // namespace

PaperCrackChange::PaperCrackChange(const InvoluteTooth& tooth, double youngs_modulus_pa,
                                   double face_width_m, const StiffnessModel& model,
                                   const RootCrack& crack)
    : tooth_(tooth),
      youngs_modulus_pa_(youngs_modulus_pa),
      face_width_m_(face_width_m),
      model_(model),
      crack_(crack),
      sin_nu_(std::sin(crack.angle_rad)),
      h_c_(tooth.base_radius_m * std::sin(tooth.half_tooth_angle_rad)) {
  check_paper_crack(tooth, face_width_m, crack);
  if (!(largest_cut(crack, sin_nu_) > 0.0)) return;
  const double rb = tooth.base_radius_m;
  const double theta_b = tooth.half_tooth_angle_rad;
  // x(tau) = Rb [sin tau + (theta_b - tau) cos tau] has the slope
  // -Rb (theta_b - tau) sin tau: it rises on (-pi/2, 0) from -Rb to Rb theta_b
  // and falls on (0, theta_b] to h_c = Rb sin theta_b. A level in (0, h_c]
  // (h_c - q sin nu > 0 is checked) is met once on (-pi/2, 0), and every
  // section on (0, theta_b] is wider than h_c, so cut.
  for (double level :
       {h_c_ - largest_cut(crack, sin_nu_), h_c_, h_c_ - sin_nu_ * smallest_crack_depth(crack)}) {
    tau_ends_.push_back(solve_on(
        [&](double tau) { return rb * (std::sin(tau) + (theta_b - tau) * std::cos(tau)) - level; },
        -0.5 * pi, 0.0));
  }
  std::sort(tau_ends_.begin(), tau_ends_.end());
  tau_ends_.erase(std::unique(tau_ends_.begin(), tau_ends_.end()), tau_ends_.end());
}

Compliances PaperCrackChange::at(double contact_x_m) const {
  if (tau_ends_.empty()) return {};
  return model_.route == StiffnessRoute::tau_form ? tau_form_change(contact_x_m)
                                                  : x_form_change(contact_x_m);
}

std::vector<double> PaperCrackChange::kinks_m() const {
  // tau_form_change integrates from tau = -phi, phi = X / Rb - theta_b: the
  // contact's own section is at tau for X = Rb (theta_b - tau), which falls
  // as tau rises.
  std::vector<double> kinks;
  for (auto tau = tau_ends_.rbegin(); tau != tau_ends_.rend(); ++tau) {
    kinks.push_back(tooth_.base_radius_m * (tooth_.half_tooth_angle_rad - *tau));
  }
  return kinks;
}

Compliances PaperCrackChange::tau_form_change(double contact_x_m) const {
  const double rb = tooth_.base_radius_m;
  const double theta_b = tooth_.half_tooth_angle_rad;
  const double b = face_width_m_;
  const double phi = contact_x_m / rb - theta_b;
  // The cut sections from the load or the start of the cut, whichever is
  // lower on the tooth, to the base circle (tau = theta_b).
  std::vector<double> ends{std::max(-phi, tau_ends_.front())};
  if (!(ends.front() < theta_b)) return {};
  for (double tau : tau_ends_) {
    if (tau > ends.front() && tau < theta_b) ends.push_back(tau);
  }
  ends.push_back(theta_b);
  const TauFormContact contact = tau_form_contact(theta_b, phi, model_.moment_sign);
  // The healthy integrands times healthy / cracked - 1, the healthy section
  // over the cracked one, as cracked_paper_tooth_compliances grows them.
  const auto change = [&](double tau) {
    const double sin_tau = std::sin(tau);
    const double cos_tau = std::cos(tau);
    const double x = rb * section_factor(theta_b, tau, sin_tau, cos_tau);
    const SectionProperties healthy = healthy_section(x, b);
    const SectionProperties cut = cut_section(crack_, sin_nu_, x, h_c_, b);
    return PointChange{
        bending_integrand(contact, tau, sin_tau, cos_tau) *
            ((healthy.second_moment_m4 - cut.second_moment_m4) / cut.second_moment_m4),
        axial_integrand(contact, tau, sin_tau, cos_tau) *
            ((healthy.area_m2 - cut.area_m2) / cut.area_m2)};
  };
  const PointChange sum =
      integrate_both(model_.rule, change, ends, {model_.relative_tolerance, 0.0});
  const double scale = 1.0 / (youngs_modulus_pa_ * b);
  Compliances c;
  c.of(Term::bending) = scale * sum.bending;
  c.of(Term::axial) = scale * sum.axial;
  return c;
}

Compliances PaperCrackChange::x_form_change(double contact_x_m) const {
  const double rb = tooth_.base_radius_m;
  const double theta_b = tooth_.half_tooth_angle_rad;
  const double b = face_width_m_;
  const double e = youngs_modulus_pa_;
  // As x_form_compliances: x = l u^2 along the centre line from the base
  // circle. The section at tau lies at the height
  // Rb [cos tau + (tau - theta_b) sin tau - cos theta_b], which falls as tau
  // rises: the cut runs from the base circle (u = 0) to the height of the
  // first of tau_ends_.
  const PolarContact contact = polar_contact(tooth_, contact_x_m);
  const double l = contact.arm.height_l_m;
  const double h = contact.arm.offset_h_m;
  const double fb = std::cos(contact.phi_rad);
  const double fa = std::sin(contact.phi_rad);
  const double axial_arm = model_.moment_sign == AxialMomentSign::physical ? -fa * h : fa * h;
  const auto u_at = [&](double tau) {
    return std::sqrt(rb * (std::cos(tau) + (tau - theta_b) * std::sin(tau) - std::cos(theta_b)) /
                     l);
  };
  // Up to the load when the cut reaches past it.
  const double top = std::min(1.0, u_at(tau_ends_.front()));
  std::vector<double> ends{0.0};
  for (std::size_t k = tau_ends_.size() - 1; k > 0; --k) {
    const double u = u_at(tau_ends_[k]);
    if (u > ends.back() && u < top) ends.push_back(u);
  }
  ends.push_back(top);
  const auto change = [&](double u) {
    const double x = l * u * u;
    const double y = section_half_thickness(tooth_, x);
    const SectionProperties healthy = healthy_section(y, b);
    const SectionProperties cut = cut_section(crack_, sin_nu_, y, h_c_, b);
    const double moment = fb * (l - x) + axial_arm;
    return PointChange{moment * moment / e *
                           (1.0 / cut.second_moment_m4 - 1.0 / healthy.second_moment_m4) * 2.0 * l *
                           u,
                       fa * fa / e * (1.0 / cut.area_m2 - 1.0 / healthy.area_m2) * 2.0 * l * u};
  };
  const PointChange sum =
      integrate_both(model_.rule, change, ends, {model_.relative_tolerance, 0.0});
  Compliances c;
  c.of(Term::bending) = sum.bending;
  c.of(Term::axial) = sum.axial;
  return c;
}

RackCrackChange::RackCrackChange(const RackGearGeometry& gear, double contact_width_m,
                                 const StiffnessModel& model, const RootCrack& crack)
    : gear_(&gear),
      contact_width_m_(contact_width_m),
      model_(model),
      placed_(place_crack(crack, gear, model.kind, contact_width_m)),
      sin_nu_(std::sin(crack.angle_rad)) {
  if (!(largest_cut(crack, sin_nu_) > 0.0)) return;
  const double r_s = placed_.start_radius_m;
  const double h_c = placed_.start_half_thickness_m;
  heights_.push_back(r_s);
  // The levels of cracked_beam_compliance, over the whole flank.
  for (double level :
       {h_c, h_c - largest_cut(crack, sin_nu_), h_c - sin_nu_ * smallest_crack_depth(crack)}) {
    for (double y : heights_where_half_thickness_is(whole_flank(gear), level, r_s)) {
      heights_.push_back(y);
    }
  }
}

BeamCompliance RackCrackChange::at(const ToothContact& contact) const {
  if (heights_.empty()) return {0.0, 0.0, 0.0};
  const double r_s = placed_.start_radius_m;
  const double h_c = placed_.start_half_thickness_m;
  // The pieces between r_s and the kinks up to the contact; the cut ones
  // are those whose middle is.
  std::vector<FlankPiece> cut_pieces;
  for (FlankPiece& piece : split_at_heights(flank_to_contact(*gear_, contact.tau_rad), heights_)) {
    const ProfilePoint middle = piece.point(0.5 * (piece.parameter_root + piece.parameter_top));
    if (middle.y_m >= r_s && is_cut(placed_.crack, sin_nu_, middle.x_m, h_c)) {
      cut_pieces.push_back(std::move(piece));
    }
  }
  const RootCrack& crack = placed_.crack;
  const double b = contact_width_m_;
  const double s = sin_nu_;
  const BeamSections sections = [&crack, s, h_c, b](double x, double) {
    const SectionProperties p = cut_section(crack, s, x, h_c, b);
    return BeamSection{p.area_m2, p.second_moment_m4};
  };
  const double e = gear_->youngs_modulus_pa;
  return tooth_beam_compliance_change(cut_pieces, {contact.x_m, contact.y_m, contact.tau_rad},
                                      {e, e / (2.0 * (1.0 + gear_->poisson_ratio)), b},
                                      model_.route, model_.relative_tolerance, sections);
}

}  // namespace gearimpact
