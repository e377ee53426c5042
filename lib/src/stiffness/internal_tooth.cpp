#include "gearimpact/stiffness/internal_tooth.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/root_crack.hpp"

namespace gearimpact {

namespace {

double involute(double alpha_rad) {
  return std::tan(alpha_rad) - alpha_rad;
}

// The involute parameter u = tan(alpha) at radius R of the base circle r_b.
double parameter_at(double base_radius_m, double radius_m) {
  return std::sqrt(radius_m * radius_m - base_radius_m * base_radius_m) / base_radius_m;
}

Compliances beam_terms(const BeamCompliance& beam) {
  Compliances c;
  c.of(Term::bending) = beam.bending_m_per_n;
  c.of(Term::shear) = beam.shear_m_per_n;
  c.of(Term::axial) = beam.axial_m_per_n;
  return c;
}

}  // namespace

RingTooth ring_tooth(int teeth, double module_m, double pressure_angle_rad,
                     double addendum_coefficient, double dedendum_coefficient) {
  RingTooth t;
  t.teeth = teeth;
  t.pitch_radius_m = 0.5 * teeth * module_m;
  t.base_radius_m = t.pitch_radius_m * std::cos(pressure_angle_rad);
  t.tip_radius_m = t.pitch_radius_m - addendum_coefficient * module_m;
  t.root_radius_m = t.pitch_radius_m + dedendum_coefficient * module_m;
  t.half_angle_base_rad = 0.5 * pi / teeth - involute(pressure_angle_rad);
  if (!(t.tip_radius_m > t.base_radius_m)) {
    throw InputError("teeth", std::to_string(teeth),
                     "a ring whose tip circle lies outside its base circle: Z_r (1 - cos a0) > "
                     "2 h_a");
  }
  const double tip_half_angle =
      t.half_angle_base_rad + involute(std::acos(t.base_radius_m / t.tip_radius_m));
  if (!(tip_half_angle > 0.0)) {
    throw InputError("teeth", std::to_string(teeth), "a ring tooth of positive width at its tip");
  }
  return t;
}

ProfilePoint ring_flank_point(const RingTooth& tooth, double u) {
  const double rb = tooth.base_radius_m;
  const double root = std::sqrt(1.0 + u * u);
  const double radius = rb * root;
  // beta = half_angle_base + inv(alpha) with tan(alpha) = u.
  const double beta = tooth.half_angle_base_rad + u - std::atan(u);
  const double radius_rate = rb * u / root;        // dR/du
  const double beta_rate = u * u / (1.0 + u * u);  // d beta/du
  const double s = std::sin(beta);
  const double c = std::cos(beta);
  return {radius * s, -radius * c, radius_rate * s + radius * c * beta_rate,
          -(radius_rate * c - radius * s * beta_rate)};
}

BeamCompliance ring_tooth_compliance(const RingTooth& tooth, double roll_distance_m,
                                     const BeamMaterial& material, StiffnessRoute route,
                                     double relative_tolerance) {
  const double rb = tooth.base_radius_m;
  const double radius = std::hypot(rb, roll_distance_m);
  // Lengths and radii round differently: a contact at the segment's end may
  // sit an ulp outside the tip circle.
  const double slack = 64.0 * std::numeric_limits<double>::epsilon() * tooth.root_radius_m;
  if (!(roll_distance_m > 0.0 && radius >= tooth.tip_radius_m - slack &&
        radius < tooth.root_radius_m)) {
    throw InputError("ring contact radius", radius,
                     "[" + format_number(tooth.tip_radius_m) + ", " +
                         format_number(tooth.root_radius_m) +
                         ") m: on the ring's involute, between its tip and root circles");
  }
  const double u_contact = roll_distance_m / rb;
  const double u_root = parameter_at(rb, tooth.root_radius_m);
  const ProfilePoint contact = ring_flank_point(tooth, u_contact);
  // The normal at the contact runs to the base circle's tangent point at
  // polar angle beta + alpha from the centre line; in the mirrored frame the
  // push into the tooth is (-cos tau, -sin tau), tau = alpha + beta.
  const double tau =
      std::atan(u_contact) + tooth.half_angle_base_rad + involute(std::atan(u_contact));
  const RingTooth* t = &tooth;
  const std::vector<FlankPiece> flank{
      {[t](double u) { return ring_flank_point(*t, u); }, u_root, u_contact}};
  return tooth_beam_compliance(flank, {contact.x_m, contact.y_m, tau}, material, route,
                               relative_tolerance);
}

GearPair planet_twin(const GearPair& ring_planet) {
  GearPair twin = ring_planet;
  twin.teeth1 = ring_planet.teeth2;
  twin.profile_shift1 = ring_planet.profile_shift2;
  twin.bore_diameter1_m = ring_planet.bore_diameter2_m;
  twin.youngs_modulus_pa = youngs_modulus(ring_planet, Gear::two);
  twin.poisson_ratio = poisson_ratio(ring_planet, Gear::two);
  twin.youngs_modulus2_pa.reset();
  twin.poisson_ratio2.reset();
  return twin;
}

void check_planet_form_circle(const GearPair& ring_planet, const InternalMesh& mesh) {
  const GearPair twin = planet_twin(ring_planet);
  const RackGearGeometry planet = rack_gear_geometry(twin, Gear::two);
  const double start_radius = std::hypot(planet.base_radius_m, mesh.segment_start_m);
  if (!(start_radius >= planet.form_radius_m)) {
    throw InputError(
        "rack_tip_radius_coefficient",
        twin.rack_tip_radius_coefficient.value_or(largest_rack_tip_radius_coefficient(twin)),
        "a rack tip round that leaves the planet's form circle (now " +
            format_number(planet.form_radius_m) + " m) inside the ring's first contact at " +
            format_number(start_radius) +
            " m: the ring's tip would meet the planet's fillet, which the potential-energy "
            "route does not load");
  }
}

namespace {

// The pair with the planet's tooth healthy (null) or cracked as the ring
// mesh loads it.
MeshStiffness ring_planet_pair(const GearPair& ring_planet, const InternalMesh& mesh, double x_m,
                               const StiffnessModel& model, const RootCrack* crack) {
  if (model.kind != StiffnessModelKind::potential_energy) {
    throw InputError("stiffness_model", "\"" + to_string(model.kind) + "\"",
                     "\"" + to_string(StiffnessModelKind::potential_energy) +
                         "\": the ring's tooth has that model's terms only");
  }
  validate_terms(model);
  const RackGearGeometry planet = rack_gear_geometry(planet_twin(ring_planet), Gear::two);
  const RingTooth ring =
      ring_tooth(ring_planet.teeth1, ring_planet.module_m, ring_planet.pressure_angle_rad,
                 ring_planet.addendum_coefficient, ring_planet.dedendum_coefficient);
  const double width = ring_planet.face_width_m;
  MeshStiffness k{};
  // The planet's beam terms come out of one integration; the switches act below.
  StiffnessModel beam_model = model;
  for (Term term : {Term::bending, Term::shear, Term::axial}) beam_model.terms.set(term, true);
  beam_model.terms.set(Term::hertz, false);
  const ToothContact contact = tooth_contact(planet, x_m);
  const ToothCompliances p =
      crack == nullptr
          ? tooth_compliances(planet, Gear::two, contact, width, beam_model)
          : cracked_tooth_compliances(planet, Gear::two, contact, width, beam_model, *crack);
  k.tooth1.of(Term::bending) = p.bending_m_per_n;
  k.tooth1.of(Term::shear) = p.shear_m_per_n;
  k.tooth1.of(Term::axial) = p.axial_m_per_n;
  k.tooth1.of(Term::foundation) = p.foundation_m_per_n;
  k.foundation_extrapolated = p.foundation_extrapolated;
  // The ring's tangent point T_a lies on T_b's side of the pitch point,
  // Rb_a tan a_w' from it: the ring's roll distance is X less T_a's X.
  const double ring_roll = x_m +
                           mesh.ring_base_radius_m * std::tan(mesh.working_pressure_angle_rad) -
                           mesh.pitch_point_m;
  const double e_ring = ring_planet.youngs_modulus_pa;
  k.tooth2 = beam_terms(ring_tooth_compliance(
      ring, ring_roll, {e_ring, e_ring / (2.0 * (1.0 + ring_planet.poisson_ratio)), width},
      model.route, model.relative_tolerance));
  for (const TermInfo& t : kTerms) {
    k.pair.of(t.term) = t.per_tooth ? k.tooth1.of(t.term) + k.tooth2.of(t.term) : 0.0;
  }
  k.pair.of(Term::hertz) = 1.0 / hertz_stiffness(ring_planet);
  k.included = included(k.pair, model.terms);
  // (29) over the terms switched on.
  k.ke = 1.0 / k.included.total_m_per_n();
  return k;
}

}  // namespace

MeshStiffness internal_mesh_stiffness(const GearPair& ring_planet, const InternalMesh& mesh,
                                      double x_m, const StiffnessModel& model) {
  return ring_planet_pair(ring_planet, mesh, x_m, model, nullptr);
}

MeshStiffness internal_mesh_stiffness(const GearPair& ring_planet, const InternalMesh& mesh,
                                      double x_m, const StiffnessModel& model,
                                      const RootCrack& planet_crack) {
  RootCrack here = planet_crack;
  here.flank = planet_crack.flank == CrackFlank::loaded ? CrackFlank::unloaded : CrackFlank::loaded;
  return ring_planet_pair(ring_planet, mesh, x_m, model, &here);
}

StiffnessTable internal_potential_energy_table(const GearPair& ring_planet,
                                               const InternalMesh& mesh,
                                               const StiffnessModel& model,
                                               StiffnessTableOptions options) {
  return StiffnessTable(
      mesh.segment_start_m, mesh.segment_end_m,
      [&](double x_m) { return internal_mesh_stiffness(ring_planet, mesh, x_m, model).included; },
      options);
}

double internal_mean_mesh_stiffness(const StiffnessTable& table, double base_pitch_m) {
  // 4-point Gauss-Legendre on [-1, 1]: nodes +-sqrt(3/7 -+ 2/7 sqrt(6/5)).
  const double r = 2.0 / 7.0 * std::sqrt(6.0 / 5.0);
  const double inner = std::sqrt(3.0 / 7.0 - r);
  const double outer = std::sqrt(3.0 / 7.0 + r);
  const double w_inner = (18.0 + std::sqrt(30.0)) / 36.0;
  const double w_outer = (18.0 - std::sqrt(30.0)) / 36.0;
  const std::array<std::array<double, 2>, 4> rule{
      {{-outer, w_outer}, {-inner, w_inner}, {inner, w_inner}, {outer, w_outer}}};
  double sum = 0.0;
  for (int part = 0; part < table.part_count(); ++part) {
    const double a = table.part_start_m(part);
    const double b = table.part_end_m(part);
    const double h = (b - a) / table.pieces();
    for (int i = 0; i < table.pieces(); ++i) {
      const double middle = a + (i + 0.5) * h;
      for (const auto& [t, w] : rule) {
        sum += w * 0.5 * h *
               table.stiffness_and_derivative_in_part(middle + 0.5 * h * t, part).stiffness_n_per_m;
      }
    }
  }
  return sum / base_pitch_m;
}

}  // namespace gearimpact
