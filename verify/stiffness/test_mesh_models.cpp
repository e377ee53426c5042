// docs/stiffness-models.md sections 2 and 3: the named models `potential-energy`
// and `ross-compatible`, per term and per pair, and their time-varying mesh
// stiffness. The peer values are ROSS's own (paper_data/peer-values/
// ross-pair-a.csv, with its provenance in its header).
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/paper/statements.hpp"
#include "gearimpact/stiffness/fillet_foundation.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/time_varying_stiffness.hpp"
#include "rack_pairs.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::check_refused;
using gearimpact::verify::relative_difference;

namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

struct PeerRow {
  std::map<std::string, double> value;
};

struct PeerFile {
  std::vector<PeerRow> rows;
  double tvms_min = 0.0;
  double tvms_max = 0.0;
  double tvms_mean = 0.0;
};

// The number after `key` in `text`.
double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  return std::stod(text.substr(at + key.size()));
}

PeerFile read_peer_file() {
  const std::string path = std::string(GEARIMPACT_PAPER_DATA_DIR) + "/peer-values/ross-pair-a.csv";
  std::ifstream in(path);
  REQUIRE(in.good());
  PeerFile file;
  std::vector<std::string> columns;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (line.find("TVMS over one mesh period") != std::string::npos) {
        file.tvms_min = number_after(line, "min ");
        file.tvms_max = number_after(line, "max ");
        file.tvms_mean = number_after(line, "time mean ");
      }
      continue;
    }
    const std::vector<std::string> fields = split_csv_line(line);
    if (columns.empty()) {
      columns = fields;
      continue;
    }
    REQUIRE(fields.size() == columns.size());
    PeerRow row;
    for (std::size_t i = 0; i < fields.size(); ++i) row.value[columns[i]] = std::stod(fields[i]);
    file.rows.push_back(row);
  }
  REQUIRE(file.rows.size() == 5);
  REQUIRE(file.tvms_mean > 0.0);
  return file;
}

// The peer's s, within rounding of our path's ends, onto our path: ROSS
// computes T1T2 as (r_b1 + r_b2) tan a0 in a different order of operations,
// and its s_SAP differs from ours in the last bits.
double onto_path(const RackGearPairGeometry& pair, double s) {
  const double slack = 8.0 * eps * pair.line_of_action_length_m;
  if (std::fabs(s - pair.start_of_active_profile_m) <= slack) return pair.start_of_active_profile_m;
  if (std::fabs(s - pair.end_of_active_profile_m) <= slack) return pair.end_of_active_profile_m;
  return s;
}

StiffnessModel model_of(StiffnessModelKind kind) {
  StiffnessModel model;
  model.kind = kind;
  return model;
}

// The model of rack-cut teeth with every term.
StiffnessModel potential_energy() {
  return model_of(StiffnessModelKind::potential_energy);
}

}  // namespace

TEST_CASE("ross-compatible reproduces ROSS per term, per tooth, at five positions") {
  // ROSS integrates with scipy's quad at its default tolerances (1.5e-8);
  // the peer values agree with ours far below that, and 1e-6 is the bound
  // the specification asks for.
  constexpr double bound = 1e-6;
  const PeerFile peer = read_peer_file();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const StiffnessModel model = model_of(StiffnessModelKind::ross_compatible);
  double worst = 0.0;
  for (const PeerRow& row : peer.rows) {
    const double s = onto_path(pair, row.value.at("s_from_T1_m"));
    const PairStiffness k = pair_stiffness(pair, model, s);
    const std::pair<const char*, double> ours[] = {{"pinion_inv_kb", k.gear1.bending_m_per_n},
                                                   {"pinion_inv_ks", k.gear1.shear_m_per_n},
                                                   {"pinion_inv_ka", k.gear1.axial_m_per_n},
                                                   {"pinion_inv_kf", k.gear1.foundation_m_per_n},
                                                   {"wheel_inv_kb", k.gear2.bending_m_per_n},
                                                   {"wheel_inv_ks", k.gear2.shear_m_per_n},
                                                   {"wheel_inv_ka", k.gear2.axial_m_per_n},
                                                   {"wheel_inv_kf", k.gear2.foundation_m_per_n},
                                                   {"inv_kh", k.hertz_m_per_n},
                                                   {"k_single_pair_N_per_m", k.stiffness_n_per_m}};
    for (const auto& [column, value] : ours) {
      const double d = relative_difference(value, row.value.at(column));
      CAPTURE(s);
      CAPTURE(column);
      CHECK(d <= bound);
      worst = std::max(worst, d);
    }
  }
  MESSAGE("ross-compatible vs ROSS: worst relative difference over 50 values " << worst);
}

TEST_CASE("ross-compatible reproduces ROSS's TVMS min, max and time mean") {
  const PeerFile peer = read_peer_file();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const TimeVaryingMeshStiffness t =
      time_varying_mesh_stiffness(pair, model_of(StiffnessModelKind::ross_compatible));
  // The bound the specification asks for.
  constexpr double bound = 1e-6;
  CHECK(relative_difference(t.min_n_per_m, peer.tvms_min) <= bound);
  CHECK(relative_difference(t.max_n_per_m, peer.tvms_max) <= bound);
  CHECK(relative_difference(t.mean_n_per_m, peer.tvms_mean) <= bound);
  // Our max is the supremum polished by Brent's method; a maximum taken over
  // samples cannot exceed it.
  CHECK(t.max_n_per_m >= peer.tvms_max);
  MESSAGE("TVMS vs ROSS: min " << relative_difference(t.min_n_per_m, peer.tvms_min) << ", max "
                               << relative_difference(t.max_n_per_m, peer.tvms_max)
                               << " (ours higher by " << t.max_n_per_m - peer.tvms_max
                               << " N/m), mean "
                               << relative_difference(t.mean_n_per_m, peer.tvms_mean));
}

TEST_CASE("potential-energy against ross-compatible: the foundation term, and by how much") {
  // The two models share the tooth (bending, shear, axial) and Hertz; they
  // differ in theta_f and u_f of the foundation term only.
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const PeerFile peer = read_peer_file();
  for (const RackGearGeometry* gear : {&pair.gear1, &pair.gear2}) {
    // ROSS's theta_f lacks c m tan a0 in the round centre's offset b1:
    // 2 c tan a0 / z less, analytically.
    const double gap = foundation_root_half_angle(*gear, StiffnessModelKind::potential_energy) -
                       foundation_root_half_angle(*gear, StiffnessModelKind::ross_compatible);
    const double expected = 2.0 * 0.25 * std::tan(gear->pressure_angle_rad) / gear->teeth;
    // A difference of two angles near 0.15 rad: 8 ulps of that.
    CHECK(std::fabs(gap - expected) <= 8.0 * eps * 0.15);
  }
  const StiffnessModel pe = model_of(StiffnessModelKind::potential_energy);
  const StiffnessModel ross = model_of(StiffnessModelKind::ross_compatible);
  for (const PeerRow& row : peer.rows) {
    const double s = onto_path(pair, row.value.at("s_from_T1_m"));
    const PairStiffness a = pair_stiffness(pair, pe, s);
    const PairStiffness b = pair_stiffness(pair, ross, s);
    CHECK(a.gear1.bending_m_per_n == b.gear1.bending_m_per_n);
    CHECK(a.gear2.shear_m_per_n == b.gear2.shear_m_per_n);
    CHECK(a.gear1.axial_m_per_n == b.gear1.axial_m_per_n);
    CHECK(a.hertz_m_per_n == b.hertz_m_per_n);
    // u_f of potential-energy is lower by x_t tan tau (the load line meets
    // the centre line below the contact point), and theta_f is larger: both
    // lower the foundation compliance.
    CHECK(a.gear1.foundation_m_per_n < b.gear1.foundation_m_per_n);
    CHECK(a.gear2.foundation_m_per_n < b.gear2.foundation_m_per_n);
    MESSAGE("s = " << s * 1e3 << " mm: potential-energy vs ross-compatible, pinion 1/kf "
                   << 100.0 * (a.gear1.foundation_m_per_n / b.gear1.foundation_m_per_n - 1.0)
                   << " %, wheel 1/kf "
                   << 100.0 * (a.gear2.foundation_m_per_n / b.gear2.foundation_m_per_n - 1.0)
                   << " %, pair k " << 100.0 * (a.stiffness_n_per_m / b.stiffness_n_per_m - 1.0)
                   << " % (kb, ks, ka, kh: 0 %)");
  }
  const TimeVaryingMeshStiffness ta = time_varying_mesh_stiffness(pair, pe);
  const TimeVaryingMeshStiffness tb = time_varying_mesh_stiffness(pair, ross);
  MESSAGE("TVMS potential-energy: min "
          << ta.min_n_per_m << ", max " << ta.max_n_per_m << ", mean " << ta.mean_n_per_m
          << " N/m; vs ross: " << 100.0 * (ta.min_n_per_m / tb.min_n_per_m - 1.0) << " %, "
          << 100.0 * (ta.max_n_per_m / tb.max_n_per_m - 1.0) << " %, "
          << 100.0 * (ta.mean_n_per_m / tb.mean_n_per_m - 1.0) << " %");
}

TEST_CASE("Hertz for two materials reduces to the paper's (4) for equal materials") {
  // mesh_stiffness.hpp's (4) pi E L / (4 (1 - nu^2)) is independent code.
  const GearPair paper = paper_gear_pair();
  const double two = hertz_stiffness_two_materials(paper.face_width_m, paper.youngs_modulus_pa,
                                                   paper.poisson_ratio, paper.youngs_modulus_pa,
                                                   paper.poisson_ratio);
  CHECK(relative_difference(two, hertz_stiffness(paper)) <= 4.0 * eps);
  // Steel on aluminium: symmetric in the two bodies, and between the two
  // equal-material values (the harmonic mean of their compliances).
  const double sa = hertz_stiffness_two_materials(10e-3, 206.8e9, 0.3, 70e9, 0.33);
  CHECK(sa == hertz_stiffness_two_materials(10e-3, 70e9, 0.33, 206.8e9, 0.3));
  const double ss = hertz_stiffness_two_materials(10e-3, 206.8e9, 0.3, 206.8e9, 0.3);
  const double aa = hertz_stiffness_two_materials(10e-3, 70e9, 0.33, 70e9, 0.33);
  CHECK(relative_difference(1.0 / sa, 0.5 * (1.0 / ss + 1.0 / aa)) <= 4.0 * eps);
}

TEST_CASE("fillet foundation: the coefficient table and the fit's range") {
  // The table of docs/stiffness-models.md typed again here, at one (h_f, theta_f):
  // a transcription check of fillet_foundation.cpp.
  const double h = 2.5;
  const double t = 0.08;
  const auto x = [&](double a, double b, double c, double d, double e, double f) {
    return a / (t * t) + b * h * h + c * h / t + d / t + e * h + f;
  };
  const FoundationFit fit = sainsot_coefficients(h, t);
  CHECK(relative_difference(fit.coefficients.l, x(-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3,
                                                  0.0271, 6.8045)) <= 4.0 * eps);
  CHECK(relative_difference(fit.coefficients.m, x(60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3,
                                                  0.1624, 0.9086)) <= 4.0 * eps);
  CHECK(relative_difference(fit.coefficients.p, x(-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3,
                                                  0.2895, 0.9236)) <= 4.0 * eps);
  CHECK(relative_difference(fit.coefficients.q, x(-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3,
                                                  -0.1472, 0.6904)) <= 16.0 * eps);
  CHECK_FALSE(fit.extrapolated);
  CHECK(sainsot_coefficients(1.3, 0.08).extrapolated);
  CHECK(sainsot_coefficients(7.5, 0.08).extrapolated);
  CHECK(sainsot_coefficients(2.5, 0.005).extrapolated);
  CHECK(sainsot_coefficients(2.5, 0.13).extrapolated);

  // The paper's pinion has theta_f = 0.1506 rad (0.1416 by ROSS's formula),
  // above the fit's 0.12: extrapolated, and said so; its wheel is inside.
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  for (StiffnessModelKind kind :
       {StiffnessModelKind::potential_energy, StiffnessModelKind::ross_compatible}) {
    const PairStiffness k = pair_stiffness(pair, model_of(kind), pair.start_of_active_profile_m);
    CHECK(k.gear1.foundation_extrapolated);
    CHECK_FALSE(k.gear2.foundation_extrapolated);
    // The flag the stiffness carries names that gear and its inputs.
    const std::vector<FoundationExtrapolation> found =
        foundation_extrapolations(pair, model_of(kind));
    REQUIRE(found.size() == 1);
    CHECK(found[0].gear == Gear::one);
    CHECK(found[0].theta_f_rad == foundation_root_half_angle(pair.gear1, kind));
    CHECK(found[0].h_f == pair.gear1.root_radius_m / (0.5 * *pair.gear1.bore_diameter_m));
    CHECK(found[0].theta_f_outside());
    CHECK_FALSE(found[0].h_f_outside());
  }
  // The words: gear, parameter, value to three digits, the fit's range; h_f when it is outside.
  CHECK(describe({Gear::one, 2.0, 0.1506}) ==
        "pinion (gear 1): theta_f = 0.151 rad, outside the fit's [0.01, 0.12] rad");
  CHECK(describe({Gear::two, 1.2, 0.05}) ==
        "wheel (gear 2): h_f = r_f / r_int = 1.2, outside the fit's [1.4, 7]");
  CHECK(foundation_extrapolation_warning({}).empty());
  CHECK(foundation_extrapolation_warning({{Gear::two, 7.5, 0.13}}) ==
        "the fillet-foundation fit of Sainsot et al. (2004) is used outside its range (wheel "
        "(gear 2): theta_f = 0.13 rad, outside the fit's [0.01, 0.12] rad; h_f = r_f / r_int = "
        "7.5, outside the fit's [1.4, 7]): the foundation term is an extrapolation");
  MESSAGE("paper pair: theta_f pinion "
          << pair.gear1.root_half_angle_rad << " rad (ROSS "
          << foundation_root_half_angle(pair.gear1, StiffnessModelKind::ross_compatible)
          << "), wheel " << pair.gear2.root_half_angle_rad << " rad; h_f "
          << pair.gear1.root_radius_m / 10e-3 << ", " << pair.gear2.root_radius_m / 30e-3);
}

TEST_CASE("every term can be switched off, and the pair's compliance loses exactly it") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(verify::ross_pair_a());
  const double s = 0.5 * (pair.start_of_active_profile_m + pair.end_of_active_profile_m);
  const StiffnessModel all = potential_energy();
  const PairStiffness k = pair_stiffness(pair, all, s);
  const double total = 1.0 / k.stiffness_n_per_m;
  // The terms in series: the sum of their compliances, to rounding.
  CHECK(relative_difference(total, k.hertz_m_per_n + k.gear1.total_m_per_n() +
                                       k.gear2.total_m_per_n()) <= 4.0 * eps);
  const std::pair<Term, double> terms[] = {
      {Term::hertz, k.hertz_m_per_n},
      {Term::bending, k.gear1.bending_m_per_n + k.gear2.bending_m_per_n},
      {Term::shear, k.gear1.shear_m_per_n + k.gear2.shear_m_per_n},
      {Term::axial, k.gear1.axial_m_per_n + k.gear2.axial_m_per_n},
      {Term::foundation, k.gear1.foundation_m_per_n + k.gear2.foundation_m_per_n}};
  for (const auto& [term, compliance] : terms) {
    StiffnessModel without = all;
    without.terms.set(term, false);
    const double rest = 1.0 / pair_stiffness(pair, without, s).stiffness_n_per_m;
    // A sum of five terms minus one: rounding of the total.
    CHECK(std::fabs((total - compliance) - rest) <= 8.0 * eps * total);
  }
  // The foundation term off needs no bore.
  GearPair no_bores = verify::ross_pair_a();
  no_bores.bore_diameter1_m.reset();
  no_bores.bore_diameter2_m.reset();
  StiffnessModel no_foundation = potential_energy();
  no_foundation.terms.set(Term::foundation, false);
  CHECK_NOTHROW(pair_stiffness(rack_gear_pair_geometry(no_bores), no_foundation, s));
}

TEST_CASE("the model by both beam routes gives the same pair stiffness") {
  // Each compliance by either route meets 1e-12; their sums agree to 1e-10
  // (as the beam integrals do, test_tooth_beam).
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    const StiffnessModel a = potential_energy();
    StiffnessModel b = potential_energy();
    b.route = StiffnessRoute::x_form;
    for (int i = 0; i <= 8; ++i) {
      const double s = pair.start_of_active_profile_m +
                       (pair.end_of_active_profile_m - pair.start_of_active_profile_m) * i / 8.0;
      CAPTURE(named.name);
      CAPTURE(s);
      CHECK(relative_difference(pair_stiffness(pair, a, s).stiffness_n_per_m,
                                pair_stiffness(pair, b, s).stiffness_n_per_m) <= 1e-10);
    }
  }
}

TEST_CASE("TVMS: the exact mean by two routes, pairs in contact, extremes bound the samples") {
  for (const auto& named : verify::varied_rack_pairs()) {
    const RackGearPairGeometry pair = rack_gear_pair_geometry(named.pair);
    const StiffnessModel model = potential_energy();
    const TimeVaryingMeshStiffness t = time_varying_mesh_stiffness(pair, model, 100);
    const double path_mean = path_mean_mesh_stiffness(pair, model);
    CAPTURE(named.name);
    // Each mean is an adaptive quadrature to 1e-10 (GSL over the pieces of
    // the period, Boost over the path of contact): 1e-9 leaves a factor 5.
    CHECK(relative_difference(t.mean_n_per_m, path_mean) <= 1e-9);
    const double leave = pair.contact_ratio - std::floor(pair.contact_ratio);
    for (const MeshStiffnessSample& sample : t.samples) {
      CAPTURE(sample.fraction);
      CHECK(sample.pairs == (sample.fraction <= leave ? 2 : 1));
      CHECK(sample.stiffness_n_per_m >= t.min_n_per_m);
      CHECK(sample.stiffness_n_per_m <= t.max_n_per_m);
      CHECK(std::fabs(sample.theta1_rad - sample.fraction * 2.0 * pi / pair.gear1.teeth) <=
            4.0 * eps);
    }
    MESSAGE(named.name << ": TVMS min " << t.min_n_per_m << ", max " << t.max_n_per_m << ", mean "
                       << t.mean_n_per_m << " N/m; the two means differ by "
                       << relative_difference(t.mean_n_per_m, path_mean));
  }
}

TEST_CASE("bad input: the foundation term without a bore") {
  GearPair p = verify::ross_pair_a();
  p.bore_diameter2_m.reset();
  const RackGearPairGeometry pair = rack_gear_pair_geometry(p);
  // Wheel root diameter 2 r_f = 160 mm - 5 mm.
  check_refused([&] { pair_stiffness(pair, potential_energy(), pair.start_of_active_profile_m); },
                "bore_diameter2", "a diameter in (0, " + format_number(0.155) + ") m");
  check_refused([&] { time_varying_mesh_stiffness(pair, potential_energy()); }, "bore_diameter2",
                "the fillet-foundation term needs the bore");
  StiffnessModel none = potential_energy();
  none.terms.on = {false, false, false, false, false};
  check_refused([&] { pair_stiffness(pair, none, pair.start_of_active_profile_m); }, "hertz_term",
                "at least one term of (29)");
  StiffnessModel no_foundation = potential_energy();
  no_foundation.terms.set(Term::foundation, false);
  check_refused([&] { pair_stiffness(pair, no_foundation, 0.0); }, "contact position s",
                "the path of contact");
  // The models of this file by name, and the paper's refused here.
  check_refused([&] { parse_stiffness_model("yang-lin", "stiffness_model"); }, "stiffness_model",
                "potential-energy, ross-compatible");
  check_refused([&] { pair_stiffness(pair, StiffnessModel{}, pair.start_of_active_profile_m); },
                "stiffness_model", "\"potential-energy\" or \"ross-compatible\"");
}
