#include "gearimpact/stiffness/mesh_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gearimpact/stiffness/tau_form.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "gearimpact/stiffness/x_form.hpp"
#include "pair_crack_change.hpp"
#include "solve_on.hpp"

namespace gearimpact {

InvoluteTooth tooth_of(const GearPair& pair, Gear gear) {
  return {base_radius(pair, gear), half_tooth_angle(pair, gear)};
}

double hertz_stiffness(const GearPair& pair) {
  return hertz_stiffness(pair, pair.face_width_m);
}

double hertz_stiffness(const GearPair& pair, double contact_length_m) {
  if (!(contact_length_m >= 0.0 && contact_length_m <= pair.face_width_m)) {
    throw InputError("contact length", contact_length_m,
                     "[0, " + format_number(pair.face_width_m) + "] m: within the face width");
  }
  const double e2 = youngs_modulus(pair, Gear::two);
  const double nu2 = poisson_ratio(pair, Gear::two);
  if (e2 != pair.youngs_modulus_pa || nu2 != pair.poisson_ratio) {
    return hertz_stiffness_two_materials(contact_length_m, pair.youngs_modulus_pa,
                                         pair.poisson_ratio, e2, nu2);
  }
  // (4) with L in place of b
  const double nu = pair.poisson_ratio;
  return pi * pair.youngs_modulus_pa * contact_length_m / (4.0 * (1.0 - nu * nu));
}

Compliances tooth_compliance(const InvoluteTooth& tooth, double contact_x_m,
                             double youngs_modulus_pa, double face_width_m,
                             const StiffnessModel& model) {
  if (!std::isfinite(contact_x_m) || contact_x_m <= 0.0) {
    throw InputError("contact position from the base-circle tangent point", contact_x_m,
                     "(0, tip] m: the contact must lie above the base circle");
  }
  return model.route == StiffnessRoute::x_form
             ? x_form_compliances(tooth, contact_x_m, youngs_modulus_pa, face_width_m, model)
             : tau_form_compliances(tooth, contact_x_m, youngs_modulus_pa, face_width_m, model);
}

double MeshStiffness::stiffness(Term term, Gear gear) const {
  if (!info(term).per_tooth) return 1.0 / pair.of(term);
  return 1.0 / (gear == Gear::one ? tooth1 : tooth2).of(term);
}

namespace {

// The per-pair and included terms and Ke (29) from the two teeth's terms,
// Hertz over the contact length L (the face width of healthy teeth).
void combine(const GearPair& pair, const StiffnessModel& model, MeshStiffness& k,
             double contact_length_m) {
  for (const TermInfo& t : kTerms) {
    k.pair.of(t.term) = t.per_tooth ? k.tooth1.of(t.term) + k.tooth2.of(t.term) : 0.0;
  }
  k.pair.of(Term::hertz) = 1.0 / hertz_stiffness(pair, contact_length_m);
  k.included = included(k.pair, model.terms);
  // (29) 1/Ke = 1/Kh + 1/Kb1 + 1/Ka1 + 1/Kb2 + 1/Ka2 over the terms switched
  // on, and for the models beyond the paper 1/Ks and 1/Kf of both teeth
  // (docs/stiffness-models.md section 2).
  k.ke = 1.0 / k.included.total_m_per_n();
}

void combine(const GearPair& pair, const StiffnessModel& model, MeshStiffness& k) {
  combine(pair, model, k, pair.face_width_m);
}

// The Hertzian contact length a tooth in `state` leaves to a contact at
// `roll_distance_m` from its base-circle tangent point on `flank`.
double contact_length(const GearPair& pair, Gear gear, const ToothState& state,
                      double roll_distance_m, CrackFlank flank) {
  const double b = pair.face_width_m;
  const double r = radius_at_roll_distance(base_radius(pair, gear), roll_distance_m);
  if (state.kind == ToothKind::spall) return spall_contact_length(state.spall, flank, r, b);
  if (state.kind == ToothKind::tip_chip) return chip_contact_length(state.chip, r, b);
  return b;
}

Compliances tooth_terms(const ToothCompliances& c) {
  Compliances result;
  result.of(Term::bending) = c.bending_m_per_n;
  result.of(Term::shear) = c.shear_m_per_n;
  result.of(Term::axial) = c.axial_m_per_n;
  result.of(Term::foundation) = c.foundation_m_per_n;
  return result;
}

// A tooth the compliance can be computed for: any but a missing one.
void check_loadable(const ToothState& tooth) {
  if (tooth.kind == ToothKind::missing) {
    throw std::logic_error("mesh_stiffness of a pair with a missing tooth: it carries nothing");
  }
}

// One rack-cut tooth in `state` (null: healthy).
ToothCompliances rack_tooth(const RackGearGeometry& gear, Gear which, const ToothContact& contact,
                            double width_m, const StiffnessModel& model, const ToothState* state) {
  if (state == nullptr) return tooth_compliances(gear, which, contact, width_m, model);
  switch (state->kind) {
    case ToothKind::root_crack:
      return cracked_tooth_compliances(gear, which, contact, width_m, model, state->crack);
    case ToothKind::spall:
      return spalled_tooth_compliances(gear, which, contact, width_m, model, state->spall);
    case ToothKind::tip_chip:
      return chipped_tooth_compliances(gear, which, contact, width_m, model, state->chip);
    case ToothKind::healthy:
    case ToothKind::missing:
      break;
  }
  return tooth_compliances(gear, which, contact, width_m, model);
}

// The beam terms come out of one integration together; the switches act in
// combine(). Hertz is (4) here, as for the paper's model.
StiffnessModel rack_tooth_model(const StiffnessModel& model) {
  StiffnessModel rack_model = model;
  for (Term term : {Term::bending, Term::shear, Term::axial}) rack_model.terms.set(term, true);
  rack_model.terms.set(Term::hertz, false);
  return rack_model;
}

// InputError for X1 off the contact segment.
void check_on_segment(const GearPair& pair, double x1_m, const StiffnessModel& model) {
  const ContactSegment segment = contact_segment(pair);
  if (!(x1_m >= segment.start_m && x1_m <= segment.end_m)) {
    throw InputError("contact position X1", x1_m,
                     "[" + format_number(segment.start_m) + ", " + format_number(segment.end_m) +
                         "] m, the contact segment: the " + to_string(model.kind) +
                         " model loads the involutes only");
  }
}

// The rack pair's s for X1 on the contact segment. The path's ends are
// computed here and in rack_generation.cpp by different roundings of the same
// lengths: an end of the contact segment may sit an ulp outside the rack
// pair's path.
double rack_position(const RackGearPairGeometry& geometry, double x1_m) {
  return std::clamp(x1_m, geometry.start_of_active_profile_m, geometry.end_of_active_profile_m);
}

// potential_energy and ross_compatible: the rack-cut teeth of mesh_models.hpp.
MeshStiffness rack_model_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model) {
  check_on_segment(pair, x1_m, model);
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const double s_m = rack_position(geometry, x1_m);
  const PairStiffness rack = pair_stiffness(geometry, rack_tooth_model(model), s_m);
  MeshStiffness k{};
  k.tooth1 = tooth_terms(rack.gear1);
  k.tooth2 = tooth_terms(rack.gear2);
  k.foundation_extrapolated =
      rack.gear1.foundation_extrapolated || rack.gear2.foundation_extrapolated;
  combine(pair, model, k);
  return k;
}

// The rack-cut tooth of `gear` in `state` by its own route: pair_stiffness
// tooth by tooth.
ToothTerms rack_faulted_tooth(const GearPair& pair, Gear gear, double x1_m,
                              const StiffnessModel& model, const ToothState* state) {
  check_on_segment(pair, x1_m, model);
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const double s_m = rack_position(geometry, x1_m);
  const StiffnessModel rack_model = rack_tooth_model(model);
  validate(rack_model, geometry);
  const PairContact contact = pair_contact(geometry, s_m);
  const ToothCompliances c = gear == Gear::one
                                 ? rack_tooth(geometry.gear1, Gear::one, contact.gear1,
                                              geometry.contact_width_m, rack_model, state)
                                 : rack_tooth(geometry.gear2, Gear::two, contact.gear2,
                                              geometry.contact_width_m, rack_model, state);
  return {tooth_terms(c), c.foundation_extrapolated};
}

// The paper's tooth of `gear` at `contact_x_m` from its base-circle tangent
// point, in `state`.
Compliances paper_tooth_terms(const GearPair& pair, Gear gear, double contact_x_m,
                              const StiffnessModel& model, const ToothState& state) {
  const double e = gear == Gear::one ? pair.youngs_modulus_pa : youngs_modulus(pair, Gear::two);
  switch (state.kind) {
    case ToothKind::root_crack:
      return cracked_paper_tooth_compliances(tooth_of(pair, gear), contact_x_m, e,
                                             pair.face_width_m, model, state.crack);
    case ToothKind::spall:
      return spalled_paper_tooth_compliances(pair, gear, contact_x_m, model, state.spall);
    case ToothKind::tip_chip:
      return chipped_paper_tooth_compliances(pair, gear, contact_x_m, model, state.chip);
    case ToothKind::healthy:
    case ToothKind::missing:
      break;
  }
  return tooth_compliance(tooth_of(pair, gear), contact_x_m, e, pair.face_width_m, model);
}

}  // namespace

std::vector<FoundationExtrapolation> foundation_extrapolations(const GearPair& pair,
                                                               const StiffnessModel& model) {
  if (!provides(model.kind, Term::foundation) || !model.terms.has(Term::foundation)) return {};
  return foundation_extrapolations(rack_gear_pair_geometry(pair), model);
}

MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model) {
  validate_terms(model);
  if (model.kind != StiffnessModelKind::yang_lin_1987)
    return rack_model_stiffness(pair, x1_m, model);
  const double lp = line_of_action_length(pair);
  if (!std::isfinite(x1_m) || x1_m <= 0.0 || x1_m >= lp) {
    throw InputError(
        "contact position X1", x1_m,
        "(0, lp) with lp = " + format_number(lp) + " m: between the tangent points C1 and C2");
  }
  const double width = pair.face_width_m;
  MeshStiffness k{};
  k.tooth1 =
      tooth_compliance(tooth_of(pair, Gear::one), x1_m, pair.youngs_modulus_pa, width, model);
  // (25),(26): gear 2 sees the contact at lp - X1 from C2.
  k.tooth2 = tooth_compliance(tooth_of(pair, Gear::two), lp - x1_m, youngs_modulus(pair, Gear::two),
                              width, model);
  combine(pair, model, k);
  return k;
}

MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model,
                             const ToothState& tooth1, const ToothState& tooth2) {
  return mesh_stiffness(pair, x1_m, model, tooth1, tooth2, CrackFlank::loaded);
}

ToothTerms faulted_pair_tooth_terms(const GearPair& pair, Gear gear, double x1_m,
                                    const StiffnessModel& model, const ToothState& state) {
  check_loadable(state);
  validate_terms(model);
  const ToothState* faulted = state.kind != ToothKind::healthy ? &state : nullptr;
  if (model.kind != StiffnessModelKind::yang_lin_1987) {
    return rack_faulted_tooth(pair, gear, x1_m, model, faulted);
  }
  const double lp = line_of_action_length(pair);
  if (!std::isfinite(x1_m) || x1_m <= 0.0 || x1_m >= lp) {
    throw InputError(
        "contact position X1", x1_m,
        "(0, lp) with lp = " + format_number(lp) + " m: between the tangent points C1 and C2");
  }
  // (25),(26): gear 2 sees the contact at lp - X1 from C2.
  return {paper_tooth_terms(pair, gear, gear == Gear::one ? x1_m : lp - x1_m, model, state), false};
}

namespace {

// The effective-width reading (spall_width_factors): where a spall shortens the pair's
// contact to L < b, both teeth's beam and foundation terms grow by their factors.
void spread_over_effective_width(const GearPair& pair, double x1_m, const ToothState& tooth1,
                                 const ToothState& tooth2, CrackFlank contact_flank,
                                 MeshStiffness& k) {
  const double b = pair.face_width_m;
  const double lp = line_of_action_length(pair);
  double length = b;
  if (tooth1.kind == ToothKind::spall) {
    length = std::min(length, contact_length(pair, Gear::one, tooth1, x1_m, contact_flank));
  }
  if (tooth2.kind == ToothKind::spall) {
    length = std::min(length, contact_length(pair, Gear::two, tooth2, lp - x1_m, contact_flank));
  }
  if (!(length < b)) return;
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  const RackGearGeometry* gears[2] = {&geometry.gear1, &geometry.gear2};
  Compliances* teeth[2] = {&k.tooth1, &k.tooth2};
  for (int g = 0; g < 2; ++g) {
    const SpallWidthFactors f = spall_width_factors(length, b, root_thickness(*gears[g]));
    for (Term term : {Term::bending, Term::shear, Term::axial}) teeth[g]->of(term) *= f.beam;
    teeth[g]->of(Term::foundation) *= f.foundation;
  }
}

}  // namespace

double pair_contact_length_m(const GearPair& pair, double x1_m, const ToothState& tooth1,
                             const ToothState& tooth2, CrackFlank contact_flank) {
  const double lp = line_of_action_length(pair);
  // (25),(26): gear 2 sees the contact at lp - X1 from C2.
  return std::min(contact_length(pair, Gear::one, tooth1, x1_m, contact_flank),
                  contact_length(pair, Gear::two, tooth2, lp - x1_m, contact_flank));
}

MeshStiffness mesh_stiffness_of_teeth(const GearPair& pair, double x1_m,
                                      const StiffnessModel& model, const ToothState& tooth1,
                                      const ToothState& tooth2, CrackFlank contact_flank,
                                      const ToothTerms& terms1, const ToothTerms& terms2) {
  const double length = pair_contact_length_m(pair, x1_m, tooth1, tooth2, contact_flank);
  // A fault across the whole face leaves no contact here: the pair carries nothing.
  if (!(length > 0.0)) return MeshStiffness{};
  MeshStiffness k{};
  k.tooth1 = terms1.terms;
  k.tooth2 = terms2.terms;
  if (applied_spall_reading(model) == SpallReading::effective_width) {
    check_spall_reading(model);
    spread_over_effective_width(pair, x1_m, tooth1, tooth2, contact_flank, k);
  }
  k.foundation_extrapolated = terms1.foundation_extrapolated || terms2.foundation_extrapolated;
  combine(pair, model, k, length);
  return k;
}

MeshStiffness mesh_stiffness(const GearPair& pair, double x1_m, const StiffnessModel& model,
                             const ToothState& tooth1, const ToothState& tooth2,
                             CrackFlank contact_flank) {
  check_loadable(tooth1);
  check_loadable(tooth2);
  if (tooth1.kind == ToothKind::healthy && tooth2.kind == ToothKind::healthy) {
    return mesh_stiffness(pair, x1_m, model);
  }
  if (!(pair_contact_length_m(pair, x1_m, tooth1, tooth2, contact_flank) > 0.0)) {
    return MeshStiffness{};
  }
  return mesh_stiffness_of_teeth(pair, x1_m, model, tooth1, tooth2, contact_flank,
                                 faulted_pair_tooth_terms(pair, Gear::one, x1_m, model, tooth1),
                                 faulted_pair_tooth_terms(pair, Gear::two, x1_m, model, tooth2));
}

PairCrackChange::PairCrackChange(const GearPair& pair, const StiffnessModel& model, Gear gear,
                                 const RootCrack& crack)
    : pair_(pair), model_(model), gear_(gear) {
  validate_terms(model);
  if (model.kind == StiffnessModelKind::yang_lin_1987) {
    const double e = gear == Gear::one ? pair.youngs_modulus_pa : youngs_modulus(pair, Gear::two);
    paper_.emplace(tooth_of(pair, gear), e, pair.face_width_m, model, crack);
    return;
  }
  geometry_ = std::make_shared<const RackGearPairGeometry>(rack_gear_pair_geometry(pair));
  const StiffnessModel rack_model = rack_tooth_model(model);
  validate(rack_model, *geometry_);
  rack_.emplace(gear == Gear::one ? geometry_->gear1 : geometry_->gear2, geometry_->contact_width_m,
                rack_model, crack);
}

Compliances PairCrackChange::at(double x1_m) const {
  if (paper_) {
    const double lp = line_of_action_length(pair_);
    if (!std::isfinite(x1_m) || x1_m <= 0.0 || x1_m >= lp) {
      throw InputError(
          "contact position X1", x1_m,
          "(0, lp) with lp = " + format_number(lp) + " m: between the tangent points C1 and C2");
    }
    // (25),(26): gear 2 sees the contact at lp - X1 from C2.
    return paper_->at(gear_ == Gear::one ? x1_m : lp - x1_m);
  }
  check_on_segment(pair_, x1_m, model_);
  const PairContact contact = pair_contact(*geometry_, rack_position(*geometry_, x1_m));
  const BeamCompliance beam = rack_->at(gear_ == Gear::one ? contact.gear1 : contact.gear2);
  Compliances c;
  c.of(Term::bending) = beam.bending_m_per_n;
  c.of(Term::shear) = beam.shear_m_per_n;
  c.of(Term::axial) = beam.axial_m_per_n;
  return c;
}

std::vector<double> PairCrackChange::kinks_x1_m() const {
  const ContactSegment segment = contact_segment(pair_);
  std::vector<double> kinks;
  if (paper_) {
    // (25),(26): gear 2 sees the contact at lp - X1 from C2.
    const double lp = line_of_action_length(pair_);
    for (double x : paper_->kinks_m()) {
      const double x1 = gear_ == Gear::one ? x : lp - x;
      if (x1 > segment.start_m && x1 < segment.end_m) kinks.push_back(x1);
    }
  } else {
    // The height of the contact on the tooth rises with its radius, which
    // rises (gear 1) or falls (gear 2) with X1 along the segment: each
    // height is met at most once, where the contact's height crosses it.
    const auto height_at = [&](double x1_m) {
      const PairContact contact = pair_contact(*geometry_, rack_position(*geometry_, x1_m));
      return (gear_ == Gear::one ? contact.gear1 : contact.gear2).y_m;
    };
    const double y_start = height_at(segment.start_m);
    const double y_end = height_at(segment.end_m);
    for (double y : rack_->kink_heights_m()) {
      if ((y_start - y) * (y_end - y) < 0.0) {
        kinks.push_back(solve_on([&](double x1_m) { return height_at(x1_m) - y; }, segment.start_m,
                                 segment.end_m));
      }
    }
  }
  std::sort(kinks.begin(), kinks.end());
  return kinks;
}

}  // namespace gearimpact
