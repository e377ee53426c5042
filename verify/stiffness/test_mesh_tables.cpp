// Teeth that differ (tooth_state.hpp, mesh_tables.hpp; docs/faults.md): two
// healthy teeth compose exactly as mesh_stiffness does, a faulted tooth changes
// the mesh only while it is in contact, one table per combination of states
// that meets, the tables of a spalled or chipped tooth against surface_faults'
// own functions, a spall or a chip across the whole face without contact over
// its extent, and the refusals of faults that do not fit.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

ToothState crack_state(double q_m, double nu_rad) {
  ToothState s;
  s.kind = ToothKind::root_crack;
  s.crack.depth_m = q_m;
  s.crack.angle_rad = nu_rad;
  return s;
}

ToothFault fault(Gear gear, int tooth, ToothState state) {
  ToothFault f;
  f.gear = gear;
  f.tooth = tooth;
  f.state = state;
  return f;
}

ToothState missing() {
  ToothState s;
  s.kind = ToothKind::missing;
  return s;
}

// The paper's pair with bores, so that the rack-cut models' foundation term
// can be computed.
GearPair pair_with_bores() {
  GearPair g = paper_gear_pair();
  g.bore_diameter1_m = 0.020;
  g.bore_diameter2_m = 0.060;
  return g;
}

StiffnessModel model_of(StiffnessModelKind kind) {
  StiffnessModel m;
  m.kind = kind;
  return m;
}

// Sum of Ke over the pairs loaded on N1 at rotation theta1, each read from
// `table_of(k)` (nullptr: carries nothing).
template <typename TableOf>
double tvms(const GearPair& g, double theta1, TableOf table_of) {
  const MeshLayout layout(g, CoastPhase{});
  const double ref = layout.reference_m(Region::n1, theta1);
  const LoadedRange r = layout.loaded(ref);
  double sum = 0.0;
  for (int j = 0; j < r.count; ++j) {
    const StiffnessTable* t = table_of(r.k_first + j);
    if (t != nullptr) sum += t->stiffness(layout.position_m(ref, r.k_first + j));
  }
  return sum;
}

}  // namespace

TEST_CASE("two healthy teeth compose as mesh_stiffness, to the bit") {
  const GearPair g = pair_with_bores();
  for (StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy}) {
    CAPTURE(to_string(kind));
    const StiffnessModel model = model_of(kind);
    const ContactSegment seg = contact_segment(g);
    for (int i = 0; i <= 8; ++i) {
      const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 8.0;
      const MeshStiffness a = mesh_stiffness(g, x, model);
      const MeshStiffness b = mesh_stiffness(g, x, model, ToothState{}, ToothState{});
      CHECK(a.ke == b.ke);
      for (const TermInfo& t : kTerms) CHECK(a.included.of(t.term) == b.included.of(t.term));
    }
  }
}

TEST_CASE("a cracked pair is Hertz plus each tooth's terms, the cracked one from root_crack") {
  // The composition written out here: 1/Ke = 1/Kh + the pinion's cracked
  // terms + the wheel's healthy terms, over the terms the model switches on.
  const GearPair g = paper_gear_pair();
  const StiffnessModel model = model_of(StiffnessModelKind::yang_lin_1987);
  const ToothState cracked = crack_state(0.5e-3, 45.0 * pi / 180.0);
  const double lp = line_of_action_length(g);
  const ContactSegment seg = contact_segment(g);
  for (int i = 0; i <= 4; ++i) {
    const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 4.0;
    const Compliances c1 = cracked_paper_tooth_compliances(
        tooth_of(g, Gear::one), x, g.youngs_modulus_pa, g.face_width_m, model, cracked.crack);
    const Compliances c2 = tooth_compliance(tooth_of(g, Gear::two), lp - x,
                                            youngs_modulus(g, Gear::two), g.face_width_m, model);
    double compliance = 1.0 / hertz_stiffness(g);
    for (const TermInfo& t : kTerms) {
      if (t.per_tooth && model.terms.has(t.term)) compliance += c1.of(t.term) + c2.of(t.term);
    }
    const double ke = mesh_stiffness(g, x, model, cracked, ToothState{}).ke;
    // Two sums of the same five terms in different orders: a few ulps.
    CHECK(relative_difference(ke, 1.0 / compliance) < 1e-14);
    CHECK(ke < mesh_stiffness(g, x, model).ke);
  }
}

TEST_CASE("without faults every pair reads the one healthy table") {
  const GearPair g = paper_gear_pair();
  const MeshTables tables(g, {}, {});
  CHECK(tables.fault_table_count() == 0);
  CHECK(tables.true_period_mesh_periods() == 1);
  for (int k = -25; k <= 25; ++k) {
    CHECK(tables.table(Region::n1, k) == &tables.healthy());
    CHECK(tables.table(Region::n2, k) == &tables.healthy());
  }
}

TEST_CASE("a cracked tooth changes the TVMS only while it is in contact") {
  // Over one pinion revolution, the faulted TVMS equals the healthy one
  // wherever the cracked tooth's pair lies outside the contact segment, which
  // is a window of eps_alpha base pitches, and is lower inside it.
  const GearPair g = paper_gear_pair();
  const int cracked_tooth = 3;
  const MeshTables tables(g, {}, {fault(Gear::one, cracked_tooth, crack_state(0.8e-3, pi / 4))});
  CHECK(tables.fault_table_count() == 1);
  CHECK(tables.true_period_mesh_periods() == g.teeth1);
  const StiffnessTable& healthy = tables.healthy();
  const MeshLayout layout(g, CoastPhase{});
  const double t0 = layout.base_pitch_m();
  const double eps_alpha = (layout.end_m() - layout.start_m()) / t0;
  // The cracked tooth is pair k = -3 on N1: it lies on the segment while
  // X_pitch + Rb1 theta1 - 3 t0 is in [X_start, X_end].
  int inside = 0;
  int outside = 0;
  const int samples = 4000;
  for (int i = 0; i < samples; ++i) {
    const double theta1 = 2.0 * pi * (i + 0.5) / samples;
    const double x_cracked =
        layout.reference_m(Region::n1, theta1) + static_cast<double>(-cracked_tooth) * t0;
    const double faulted = tvms(g, theta1, [&](int k) { return tables.table(Region::n1, k); });
    const double reference = tvms(g, theta1, [&](int) { return &healthy; });
    if (x_cracked >= layout.start_m() && x_cracked <= layout.end_m()) {
      ++inside;
      CHECK(faulted < reference);
    } else {
      ++outside;
      CHECK(faulted == reference);
    }
  }
  // The window's share of a revolution: eps_alpha pitches of z1.
  const double share = static_cast<double>(inside) / samples;
  CHECK(std::fabs(share - eps_alpha / g.teeth1) < 2.0 / samples);
  CHECK(outside > 0);
}

TEST_CASE("one table per distinct combination of states that meets") {
  const GearPair g = paper_gear_pair();  // z1 = 20, z2 = 80: gcd 20
  SUBCASE("five distinct cracks on the pinion: five tables") {
    std::vector<ToothFault> faults;
    for (int i = 0; i < 5; ++i) {
      faults.push_back(fault(Gear::one, 2 * i, crack_state((0.2 + 0.1 * i) * 1e-3, pi / 4)));
    }
    const MeshTables tables(g, {}, faults);
    CHECK(tables.fault_table_count() == 5);
    // Each cracked tooth's pairs read its own table, the others the healthy one.
    for (int n = 0; n < 80; ++n) {
      const int i = n % 20;
      const StiffnessTable* t = tables.table(Region::n1, -n);
      if (i % 2 == 0 && i < 10) {
        CHECK(t != &tables.healthy());
      } else {
        CHECK(t == &tables.healthy());
      }
    }
  }
  SUBCASE("five equal cracks share one table") {
    std::vector<ToothFault> faults;
    for (int i = 0; i < 5; ++i) faults.push_back(fault(Gear::one, i, crack_state(0.3e-3, pi / 4)));
    CHECK(MeshTables(g, {}, faults).fault_table_count() == 1);
  }
  SUBCASE("a cracked pinion tooth and a cracked wheel tooth that never meet") {
    // Pinion tooth 3 meets wheel teeth 3 mod 20 on N1 and 4 mod 20 on N2
    // (teeth_of_pair); wheel tooth 10 meets pinion 10 (N1) and 9 (N2).
    const MeshTables tables(g, {},
                            {fault(Gear::one, 3, crack_state(0.3e-3, pi / 4)),
                             fault(Gear::two, 10, crack_state(0.4e-3, pi / 4))});
    CHECK(tables.fault_table_count() == 2);
  }
  SUBCASE("wheel tooth 4 meets pinion tooth 3 on the coast line: a third table") {
    const MeshTables tables(g, {},
                            {fault(Gear::one, 3, crack_state(0.3e-3, pi / 4)),
                             fault(Gear::two, 4, crack_state(0.4e-3, pi / 4))});
    CHECK(tables.fault_table_count() == 3);
    CHECK(tables.true_period_mesh_periods() == 80);
  }
  SUBCASE("a missing tooth has no table") {
    const MeshTables tables(g, {}, {fault(Gear::one, 3, missing())});
    CHECK(tables.fault_table_count() == 0);
    CHECK(tables.table(Region::n1, -3) == nullptr);
    CHECK(tables.table(Region::n1, -23) == nullptr);
    CHECK(tables.table(Region::n2, 3) == nullptr);
    CHECK(tables.table(Region::n1, -4) == &tables.healthy());
  }
}

TEST_CASE("faults that do not fit are refused before any table is built") {
  const GearPair g = paper_gear_pair();
  const auto message = [&](const std::vector<ToothFault>& faults,
                           StiffnessModelKind kind = StiffnessModelKind::yang_lin_1987) {
    try {
      check_tooth_faults(pair_with_bores(), model_of(kind), faults);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string tooth = message({fault(Gear::one, 25, missing())});
  CHECK(tooth.find("faults[0].tooth") != std::string::npos);
  CHECK(tooth.find("0 ... 19") != std::string::npos);
  const std::string twice =
      message({fault(Gear::two, 7, missing()), fault(Gear::two, 7, crack_state(1e-4, pi / 4))});
  CHECK(twice.find("faults[1].tooth") != std::string::npos);
  // The paper's tooth: h_c = Rb sin theta_b; a crack at 90 deg with q = h_c
  // reaches the centre line.
  const double h_c = base_radius(g, Gear::one) * std::sin(half_tooth_angle(g, Gear::one));
  const std::string deep = message({fault(Gear::one, 0, crack_state(h_c, pi / 2))});
  CHECK(deep.find("q sin nu < h_c") != std::string::npos);
  CHECK(message({fault(Gear::one, 0, crack_state(0.99 * h_c, pi / 2))}).empty());
  const std::string deep_rack = message({fault(Gear::one, 0, crack_state(5e-3, pi / 2))},
                                        StiffnessModelKind::potential_energy);
  CHECK(deep_rack.find("q sin nu < h_c") != std::string::npos);
  CHECK_THROWS_AS(MeshTables(g, {}, {fault(Gear::one, 20, missing())}), InputError);
}

TEST_CASE("the TVMS over the true period names the teeth and differs only where the crack meshes") {
  const GearPair g = paper_gear_pair();
  const std::vector<TruePeriodSample> samples =
      true_period_mesh_stiffness(g, {}, {fault(Gear::one, 3, crack_state(0.8e-3, pi / 4))}, 50)
          .samples;
  // A crack on the pinion only: the true period is one pinion revolution.
  REQUIRE(samples.size() == 50u * 20u);
  CHECK(std::fabs(samples.back().theta1_rad + 2.0 * pi / 1000.0 - 2.0 * pi) < 1e-12);
  int with_crack = 0;
  for (const TruePeriodSample& s : samples) {
    bool cracked = false;
    for (const TeethInContact& t : s.teeth) {
      // On N1 the n-th pair holds pinion tooth n mod 20 and wheel tooth n mod 80.
      CHECK(t.pinion_tooth == t.wheel_tooth % 20);
      cracked = cracked || t.pinion_tooth == 3;
    }
    if (cracked) {
      ++with_crack;
      CHECK(s.ke_n_per_m < s.healthy_ke_n_per_m);
    } else {
      CHECK(s.ke_n_per_m == s.healthy_ke_n_per_m);
    }
  }
  // Tooth 3 meshes eps_alpha of the 20 pitches of a revolution.
  const double eps_alpha = contact_ratio(g);
  CHECK(std::fabs(with_crack / 1000.0 - eps_alpha / 20.0) < 2.0 / 1000.0);
}

namespace {

// A position on the contact segment, a fraction f of its length from X_start.
double along(const GearPair& g, double f) {
  const ContactSegment s = contact_segment(g);
  return s.start_m + f * (s.end_m - s.start_m);
}

// The radius of the pinion's flank point that a contact at X1 touches.
double pinion_radius(const GearPair& g, double x1_m) {
  return radius_at_roll_distance(base_radius(g, Gear::one), x1_m);
}

// A spall on the drive flank of a pinion tooth over 45 % to 70 % of the
// contact segment, 4 mm of the 10 mm face, 0.2 mm deep.
Spall pinion_spall(const GearPair& g) {
  Spall s;
  s.start_radius_m = pinion_radius(g, along(g, 0.45));
  s.end_radius_m = pinion_radius(g, along(g, 0.70));
  s.width_m = 0.4 * g.face_width_m;
  s.depth_m = 0.2e-3;
  return s;
}

ToothState spall_state(const Spall& spall) {
  ToothState s;
  s.kind = ToothKind::spall;
  s.spall = spall;
  return s;
}

ToothState chip_state(const TipChip& chip) {
  ToothState s;
  s.kind = ToothKind::tip_chip;
  s.chip = chip;
  return s;
}

// Ke of a healthy wheel tooth against a pinion tooth whose own compliances
// and contact length come straight from surface_faults.hpp, summed by (29)
// here: the direct route the tables are checked against.
template <typename PinionTooth>
double direct_ke(const GearPair& g, const StiffnessModel& m, double x1_m, double contact_length_m,
                 PinionTooth pinion_tooth) {
  const double lp = line_of_action_length(g);
  double compliance = 1.0 / hertz_stiffness(g, contact_length_m);
  if (m.kind == StiffnessModelKind::yang_lin_1987) {
    compliance += pinion_tooth(x1_m, nullptr).total_m_per_n();
    compliance += tooth_compliance(tooth_of(g, Gear::two), lp - x1_m, youngs_modulus(g, Gear::two),
                                   g.face_width_m, m)
                      .total_m_per_n();
    return 1.0 / compliance;
  }
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(g);
  const PairContact contact = pair_contact(geometry, x1_m);
  compliance += pinion_tooth(x1_m, &contact.gear1).total_m_per_n();
  compliance +=
      tooth_compliances(geometry.gear2, Gear::two, contact.gear2, geometry.contact_width_m, m)
          .total_m_per_n();
  return 1.0 / compliance;
}

}  // namespace

TEST_CASE("a spalled pinion tooth's table equals surface_faults' own values, on every model") {
  const GearPair g = pair_with_bores();
  const Spall spall = pinion_spall(g);
  const double b = g.face_width_m;
  for (StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy,
        StiffnessModelKind::ross_compatible}) {
    CAPTURE(to_string(kind));
    // The Hertz-only reading, whose terms surface_faults gives alone (the rack-cut models'
    // default, effective-width, scales them: test_spall_reading checks its table).
    StiffnessModel m = model_of(kind);
    m.spall_reading = SpallReading::hertz_only;
    const MeshTables tables(g, m, {fault(Gear::one, 0, spall_state(spall))});
    // Pinion tooth 0 meets wheel tooth 0 on N1 (drive flanks) and wheel
    // tooth 1 on N2 (coast flanks): two tables, the pit on one flank.
    const StiffnessTable* drive = tables.table_of_teeth(0, 0, Region::n1);
    const StiffnessTable* coast = tables.table_of_teeth(0, 1, Region::n2);
    REQUIRE(drive != nullptr);
    REQUIRE(coast != nullptr);
    CHECK(drive != coast);
    CHECK(tables.fault_table_count() == 2);
    CHECK(drive->breaks_m().size() == 2);
    const auto pinion_tooth = [&](double x1_m, const ToothContact* contact) {
      Compliances c;
      if (contact == nullptr) {
        c = spalled_paper_tooth_compliances(g, Gear::one, x1_m, m, spall);
      } else {
        const RackGearPairGeometry geometry = rack_gear_pair_geometry(g);
        const ToothCompliances t = spalled_tooth_compliances(geometry.gear1, Gear::one, *contact,
                                                             geometry.contact_width_m, m, spall);
        c.of(Term::bending) = t.bending_m_per_n;
        c.of(Term::shear) = t.shear_m_per_n;
        c.of(Term::axial) = t.axial_m_per_n;
        c.of(Term::foundation) = t.foundation_m_per_n;
      }
      return c;
    };
    for (double f : {0.05, 0.3, 0.44, 0.46, 0.5, 0.6, 0.69, 0.71, 0.85, 0.97}) {
      CAPTURE(f);
      const double x = along(g, f);
      const bool in_band = f > 0.45 && f < 0.70;
      // On the drive flank the contact in the band runs over b - b_s; on the
      // coast flank over b, its sections pitted all the same.
      const double on_drive = direct_ke(g, m, x, in_band ? b - spall.width_m : b, pinion_tooth);
      const double on_coast = direct_ke(g, m, x, b, pinion_tooth);
      // The table's fit (near 1e-14, benchmarks/README.md) and both routes'
      // quadrature at the model's tolerance, 1e-12 each.
      CHECK(relative_difference(drive->stiffness(x), on_drive) < 1e-11);
      CHECK(relative_difference(coast->stiffness(x), on_coast) < 1e-11);
      CHECK(relative_difference(drive->compliance(x).total_m_per_n(), 1.0 / on_drive) < 1e-11);
      const double healthy = mesh_stiffness(g, x, m).ke;
      if (f < 0.45) {
        // Below the spall the contact loads no pitted section: healthy, to the bit.
        CHECK(mesh_stiffness(g, x, m, spall_state(spall), ToothState{}).ke == healthy);
        CHECK(mesh_stiffness(g, x, m, spall_state(spall), ToothState{}, CrackFlank::unloaded).ke ==
              healthy);
        CHECK(relative_difference(drive->stiffness(x), tables.healthy().stiffness(x)) < 1e-12);
      } else {
        // In and above it the pitted sections bend more; in it, on the
        // drive flank, the shorter contact line adds to that.
        CHECK(on_coast < healthy);
        if (in_band) CHECK(on_drive < on_coast);
      }
    }
  }
}

TEST_CASE("a chipped tip lowers the stiffness only where the contact is above r_k") {
  const GearPair g = pair_with_bores();
  TipChip chip;
  chip.radius_m = pinion_radius(g, along(g, 0.8));
  chip.width_m = 0.5 * g.face_width_m;
  for (StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy}) {
    CAPTURE(to_string(kind));
    const StiffnessModel m = model_of(kind);
    const MeshTables tables(g, m, {fault(Gear::one, 0, chip_state(chip))});
    const StiffnessTable* drive = tables.table_of_teeth(0, 0, Region::n1);
    REQUIRE(drive != nullptr);
    // A chip is on both flanks: the coast line shares the table.
    CHECK(tables.table_of_teeth(0, 1, Region::n2) == drive);
    const auto pinion_tooth = [&](double x1_m, const ToothContact* contact) {
      Compliances c;
      if (contact == nullptr) {
        c = chipped_paper_tooth_compliances(g, Gear::one, x1_m, m, chip);
      } else {
        const RackGearPairGeometry geometry = rack_gear_pair_geometry(g);
        const ToothCompliances t = chipped_tooth_compliances(geometry.gear1, Gear::one, *contact,
                                                             geometry.contact_width_m, m, chip);
        c.of(Term::bending) = t.bending_m_per_n;
        c.of(Term::shear) = t.shear_m_per_n;
        c.of(Term::axial) = t.axial_m_per_n;
        c.of(Term::foundation) = t.foundation_m_per_n;
      }
      return c;
    };
    for (double f : {0.1, 0.5, 0.79, 0.81, 0.9, 0.99}) {
      CAPTURE(f);
      const double x = along(g, f);
      const double healthy = mesh_stiffness(g, x, m).ke;
      const double chipped = mesh_stiffness(g, x, m, chip_state(chip), ToothState{}).ke;
      if (f < 0.8) {
        CHECK(chipped == healthy);
      } else {
        CHECK(chipped < healthy);
        const double direct = direct_ke(g, m, x, g.face_width_m - chip.width_m, pinion_tooth);
        // As for the spall: the fit and two quadratures at 1e-12.
        CHECK(relative_difference(drive->stiffness(x), direct) < 1e-11);
        CHECK(relative_difference(chipped, direct) < 1e-11);
      }
    }
  }
}

TEST_CASE("a spall or a chip across the whole face: no contact over its extent, Ke = 0 there") {
  // Across the whole face the contact length b - b_s (in the spall's band, on its flank) or
  // b - b_k (above r_k) is 0: the pair has no contact there, its table's part there carries
  // nothing (Ke exactly 0) and the parts about it are those of the direct route. The chip's
  // edge is where chipped_contact_segment ends the pinion tooth's contact.
  const GearPair g = pair_with_bores();
  Spall spall = pinion_spall(g);
  spall.width_m = g.face_width_m;
  TipChip chip;
  chip.radius_m = pinion_radius(g, along(g, 0.8));
  chip.width_m = g.face_width_m;
  const std::optional<ContactSegment> chipped = chipped_contact_segment(g, Gear::one, chip);
  REQUIRE(chipped);
  CHECK(std::fabs(chipped->end_m - along(g, 0.8)) < 1e-12);
  for (const StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy,
        StiffnessModelKind::ross_compatible}) {
    CAPTURE(to_string(kind));
    const StiffnessModel m = model_of(kind);
    for (const ToothState& state : {spall_state(spall), chip_state(chip)}) {
      const bool is_spall = state.kind == ToothKind::spall;
      CAPTURE(is_spall);
      const MeshTables tables(g, m, {fault(Gear::one, 0, state)});
      const StiffnessTable* table = tables.table_of_teeth(0, 0, Region::n1);
      REQUIRE(table != nullptr);
      // Inside the extent, and outside it on either side where there is one.
      const std::vector<double> inside =
          is_spall ? std::vector<double>{0.5, 0.6, 0.69} : std::vector<double>{0.81, 0.9, 1.0};
      const std::vector<double> outside = is_spall ? std::vector<double>{0.1, 0.44, 0.71, 0.95}
                                                   : std::vector<double>{0.1, 0.5, 0.79};
      for (double f : inside) {
        CAPTURE(f);
        const double x = along(g, f);
        CHECK(table->stiffness(x) == 0.0);
        CHECK(table->stiffness_derivative(x) == 0.0);
        CHECK_FALSE(table->part_in_contact(table->part_of(x)));
        CHECK(mesh_stiffness(g, x, m, state, ToothState{}).ke == 0.0);
      }
      for (double f : outside) {
        CAPTURE(f);
        const double x = along(g, f);
        const double direct = mesh_stiffness(g, x, m, state, ToothState{}).ke;
        CHECK(direct > 0.0);
        // The table's fit, as the partial faults' tables above.
        CHECK(relative_difference(table->stiffness(x), direct) < 1e-10);
        CHECK(table->part_in_contact(table->part_of(x)));
      }
      // The spall lies on the drive flank: on the coast line the pair keeps its contact.
      if (is_spall) {
        const StiffnessTable* coast = tables.table_of_teeth(0, 1, Region::n2);
        REQUIRE(coast != nullptr);
        CHECK(coast->stiffness(along(g, 0.6)) > 0.0);
      }
    }
  }
}

TEST_CASE(
    "a cracked tooth's table, the healthy tooth plus the crack's change, equals the full "
    "integration on every model and both lines") {
  // MeshTables builds a cracked tooth as its healthy tooth plus the change
  // the crack makes, integrated over the cut sections only
  // (PaperCrackChange, RackCrackChange); the reference here is a table of
  // the same grid (the same breaks) fitted to mesh_stiffness with the tooth states, which
  // integrates the cracked tooth whole (cracked_paper_tooth_compliances,
  // cracked_tooth_compliances). Both routes ask each quadrature for 1e-12
  // relative to its own integral, and the change is a part of the tooth's
  // term, so the node values differ by a few 1e-12 at most; the two fits are
  // the same linear map of the node values, which can grow a difference by
  // its Lebesgue constant (below 3 at order 7): 1e-10 leaves a margin of ten.
  const GearPair g = pair_with_bores();
  const ContactSegment seg = contact_segment(g);
  ToothState partial = crack_state(0.6e-3, pi / 3);
  partial.crack.profile = CrackProfile::partial_width;
  partial.crack.width_m = 0.6 * g.face_width_m;
  struct Case {
    StiffnessModelKind kind;
    StiffnessRoute route;
    int pieces;
  };
  // The rack-cut teeth's x-form solves for every section: on 3 pieces.
  for (const Case c : {Case{StiffnessModelKind::yang_lin_1987, StiffnessRoute::tau_form, 64},
                       Case{StiffnessModelKind::yang_lin_1987, StiffnessRoute::x_form, 64},
                       Case{StiffnessModelKind::potential_energy, StiffnessRoute::tau_form, 64},
                       Case{StiffnessModelKind::potential_energy, StiffnessRoute::x_form, 3},
                       Case{StiffnessModelKind::ross_compatible, StiffnessRoute::tau_form, 64}}) {
    StiffnessModel m = model_of(c.kind);
    m.route = c.route;
    CAPTURE(to_string(c.kind));
    CAPTURE(static_cast<int>(c.route));
    for (const ToothFault& f :
         {fault(Gear::one, 1, crack_state(0.3e-3, pi / 4)),
          fault(Gear::two, 2, crack_state(1.0e-3, pi / 4)), fault(Gear::one, 4, partial)}) {
      CAPTURE(f.gear == Gear::one ? "pinion" : "wheel");
      CAPTURE(f.state.crack.depth_m);
      StiffnessTableOptions options;
      options.pieces = c.pieces;
      const MeshTables tables(g, m, {f}, nullptr, options);
      const ToothState s1 = f.gear == Gear::one ? f.state : ToothState{};
      const ToothState s2 = f.gear == Gear::two ? f.state : ToothState{};
      for (const Region line : {Region::n1, Region::n2}) {
        CAPTURE(line == Region::n1 ? "N1" : "N2");
        // A pair of this line with the cracked tooth in it.
        const StiffnessTable* fast = nullptr;
        for (int k = -2 * g.teeth1 * g.teeth2; k <= 0 && fast == nullptr; ++k) {
          const TeethInContact t = teeth_of_pair(g.teeth1, g.teeth2, line, k);
          const bool cracked =
              f.gear == Gear::one ? t.pinion_tooth == f.tooth : t.wheel_tooth == f.tooth;
          if (cracked) fast = tables.table(line, k);
        }
        REQUIRE(fast != nullptr);
        REQUIRE(fast != &tables.healthy());
        const CrackFlank flank = line == Region::n1 ? CrackFlank::loaded : CrackFlank::unloaded;
        // On the same grid: cut where the fast table is cut (the crack's
        // kinks, which the test below checks against the untabled stiffness).
        const StiffnessTable full(
            seg.start_m, seg.end_m,
            [&](double x1_m) { return mesh_stiffness(g, x1_m, m, s1, s2, flank).included; },
            fast->breaks_m(), options);
        double largest_change = 0.0;
        for (int i = 0; i <= 200; ++i) {
          const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 200.0;
          CAPTURE(x);
          CHECK(relative_difference(fast->stiffness(x), full.stiffness(x)) < 1e-10);
          const Compliances a = fast->compliance(x);
          const Compliances b = full.compliance(x);
          for (Term t : {Term::bending, Term::shear, Term::axial}) {
            if (b.of(t) != 0.0) CHECK(relative_difference(a.of(t), b.of(t)) < 1e-10);
          }
          largest_change =
              std::max(largest_change,
                       relative_difference(fast->stiffness(x), tables.healthy().stiffness(x)));
        }
        // The crack does change the table, by far more than the bound.
        CHECK(largest_change > 1e-4);
      }
    }
  }
}

namespace {

// The positions X1 on the contact segment where the half thickness of the
// contact's own section crosses `level`, found here by scanning and
// bisection: for the paper's tooth from its section formula (20)-(24), the
// section at tau = theta_b - X / Rb of half thickness
// Rb [sin tau + (theta_b - tau) cos tau]; for a rack-cut tooth from the
// contact point's half thickness in the tooth frame (pair_contact).
std::vector<double> level_crossings(const GearPair& g, StiffnessModelKind kind, Gear gear,
                                    double level) {
  const ContactSegment seg = contact_segment(g);
  const double lp = line_of_action_length(g);
  const InvoluteTooth tooth = tooth_of(g, gear);
  const RackGearPairGeometry rack = rack_gear_pair_geometry(g);
  const auto half_thickness = [&](double x1) {
    if (kind == StiffnessModelKind::yang_lin_1987) {
      const double rb = tooth.base_radius_m;
      const double theta_b = tooth.half_tooth_angle_rad;
      const double tau = theta_b - (gear == Gear::one ? x1 : lp - x1) / rb;
      return rb * (std::sin(tau) + (theta_b - tau) * std::cos(tau)) - level;
    }
    const double s = std::clamp(x1, rack.start_of_active_profile_m, rack.end_of_active_profile_m);
    const PairContact c = pair_contact(rack, s);
    return (gear == Gear::one ? c.gear1 : c.gear2).x_m - level;
  };
  std::vector<double> found;
  constexpr int samples = 2000;
  for (int i = 0; i < samples; ++i) {
    double a = seg.start_m + (seg.end_m - seg.start_m) * i / samples;
    double b = seg.start_m + (seg.end_m - seg.start_m) * (i + 1) / samples;
    double fa = half_thickness(a);
    if (!(fa * half_thickness(b) < 0.0)) continue;
    for (int k = 0; k < 200; ++k) {
      const double m = 0.5 * (a + b);
      if (m <= a || m >= b) break;
      const double fm = half_thickness(m);
      if ((fm < 0.0) == (fa < 0.0)) {
        a = m;
        fa = fm;
      } else {
        b = m;
      }
    }
    found.push_back(0.5 * (a + b));
  }
  return found;
}

}  // namespace

TEST_CASE(
    "a cracked tooth's table meets the direct stiffness to 1e-12 at every kink of the crack") {
  // Where the contact's own section is one where the crack's cut starts
  // (half thickness h_c - q_max sin nu) or kinks (h_c - q_min sin nu, h_c),
  // the cracked tooth's terms kink as functions of X1. The table promises
  // 1e-12 relative against mesh_stiffness with the tooth states, which
  // integrates the cracked tooth whole at each position (docs/faults.md); a
  // Chebyshev piece fitted across a kink misses it by orders more (1.3e-7 at
  // q = 0.5 q_max on the paper's pair when the kinks were not breaks). The
  // kinks are found here from the section's own formula, the reference is
  // the untabled stiffness; the points run up to two pieces either side of
  // each kink and down to 1e-9 m of it. The two routes' quadratures each
  // meet 1e-12 relative of their integrals (in fact near 1e-15) and the fit
  // of a smooth piece is near 1e-14 (StiffnessTableOptions): 1e-12 is the
  // promise (observed 1.2e-14 over the 44 kinks).
  const GearPair g = pair_with_bores();
  const ContactSegment seg = contact_segment(g);
  const double nu = pi / 4;
  const double piece = (seg.end_m - seg.start_m) / StiffnessTableOptions{}.pieces;
  struct Case {
    StiffnessModelKind kind;
    StiffnessRoute route;
  };
  int kinks_checked = 0;
  double worst_of_all = 0.0;
  for (const Case c : {Case{StiffnessModelKind::yang_lin_1987, StiffnessRoute::tau_form},
                       Case{StiffnessModelKind::yang_lin_1987, StiffnessRoute::x_form},
                       Case{StiffnessModelKind::potential_energy, StiffnessRoute::tau_form}}) {
    StiffnessModel m = model_of(c.kind);
    m.route = c.route;
    CAPTURE(to_string(c.kind));
    CAPTURE(static_cast<int>(c.route));
    for (const Gear gear : {Gear::one, Gear::two}) {
      CAPTURE(gear == Gear::one ? "pinion" : "wheel");
      // h_c of the tooth's crack start, and q_max = h_c / sin nu.
      const double h_c =
          c.kind == StiffnessModelKind::yang_lin_1987
              ? tooth_of(g, gear).base_radius_m * std::sin(tooth_of(g, gear).half_tooth_angle_rad)
              : [&] {
                  const RackGearPairGeometry rack = rack_gear_pair_geometry(g);
                  return place_crack(crack_state(1e-4, nu).crack,
                                     gear == Gear::one ? rack.gear1 : rack.gear2, c.kind,
                                     rack.contact_width_m)
                      .start_half_thickness_m;
                }();
      const double q_max = h_c / std::sin(nu);
      std::vector<ToothState> states;
      for (double fraction : {0.25, 0.5, 0.75}) states.push_back(crack_state(fraction * q_max, nu));
      // A depth across the face from 0.6 q_max to 0.3 q_max: three kinks.
      ToothState graded = crack_state(0.6 * q_max, nu);
      graded.crack.profile = CrackProfile::full_width;
      graded.crack.end_depth_m = 0.3 * q_max;
      states.push_back(graded);
      for (const ToothState& state : states) {
        CAPTURE(state.crack.depth_m / q_max);
        CAPTURE(static_cast<int>(state.crack.profile));
        const int tooth = 1;
        const MeshTables tables(g, m, {fault(gear, tooth, state)});
        const ToothState s1 = gear == Gear::one ? state : ToothState{};
        const ToothState s2 = gear == Gear::two ? state : ToothState{};
        const StiffnessTable* table = nullptr;
        for (int k = -2 * g.teeth1 * g.teeth2; k <= 0 && table == nullptr; ++k) {
          const TeethInContact t = teeth_of_pair(g.teeth1, g.teeth2, Region::n1, k);
          if ((gear == Gear::one ? t.pinion_tooth : t.wheel_tooth) == tooth) {
            table = tables.table(Region::n1, k);
          }
        }
        REQUIRE(table != nullptr);
        std::vector<double> levels{h_c - std::sin(nu) * largest_crack_depth(state.crack), h_c,
                                   h_c - std::sin(nu) * smallest_crack_depth(state.crack)};
        int kinks = 0;
        for (double level : levels) {
          for (double kink : level_crossings(g, c.kind, gear, level)) {
            CAPTURE(kink);
            ++kinks;
            double worst = 0.0;
            std::vector<double> offsets{0.0};
            for (double d : {1e-9, 1e-7, 1e-5}) {
              offsets.push_back(d);
              offsets.push_back(-d);
            }
            for (int j = 1; j <= 14; ++j) {
              offsets.push_back(piece * j / 7.0);
              offsets.push_back(-piece * j / 7.0);
            }
            for (double d : offsets) {
              const double x = kink + d;
              if (!(x > seg.start_m && x < seg.end_m)) continue;
              const double direct = mesh_stiffness(g, x, m, s1, s2, CrackFlank::loaded).ke;
              worst = std::max(worst, relative_difference(table->stiffness(x), direct));
            }
            CAPTURE(worst);
            CHECK(worst < 1e-12);
            worst_of_all = std::max(worst_of_all, worst);
          }
        }
        // Up to half of q_max the cut starts on the segment (a deeper crack
        // may cut every section the contact meets there).
        if (state.crack.profile == CrackProfile::uniform && state.crack.depth_m <= 0.5 * q_max) {
          CHECK(kinks >= 1);
        }
        kinks_checked += kinks;
      }
    }
  }
  MESSAGE("kinks checked: " << kinks_checked << ", largest relative difference " << worst_of_all);
}

TEST_CASE("a crack of depth 0 gives the table the full integration gives, to the bit") {
  // Nothing is cut: the change is 0 without a quadrature, and either route
  // computes the healthy tooth as it is.
  const GearPair g = pair_with_bores();
  const ContactSegment seg = contact_segment(g);
  for (StiffnessModelKind kind :
       {StiffnessModelKind::yang_lin_1987, StiffnessModelKind::potential_energy}) {
    CAPTURE(to_string(kind));
    const StiffnessModel m = model_of(kind);
    const ToothState none = crack_state(0.0, pi / 4);
    const MeshTables tables(g, m, {fault(Gear::one, 0, none)});
    const StiffnessTable* fast = tables.table_of_teeth(0, 0, Region::n1);
    REQUIRE(fast != nullptr);
    const StiffnessTable full(seg.start_m, seg.end_m, [&](double x1_m) {
      return mesh_stiffness(g, x1_m, m, none, ToothState{}).included;
    });
    for (int i = 0; i <= 50; ++i) {
      const double x = seg.start_m + (seg.end_m - seg.start_m) * i / 50.0;
      CHECK(fast->stiffness(x) == full.stiffness(x));
    }
  }
}
