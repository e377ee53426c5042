// The effective-width reading of a partial-width spall (surface_faults.hpp,
// spall_width_factors; model.spall_reading = "effective-width") against the 3-D
// finite elements of verify/data/fe_spall_3d.csv (gearimpact fe-check
// --spall-width, docs/verification.md "The spall in 3-D"): each tooth's
// compliance growth, and the pair's stiffness lost through mesh_stiffness with a
// spalled tooth, on the rig pair whose rows fitted the reading's two constants,
// on the paper's pair, which the fit did not see, and on a third pair unlike
// both (27/43, 25 deg, b / m = 8, shifted), which the reading misses by more,
// always short of the FE's loss: the record of why the default stays
// Hertz-only (docs/faults.md). Also the factors' closed
// form and limits, the default reading unchanged, and the refusal with the
// paper's model.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/mesh_tables.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gearimpact/stiffness/tooth_state.hpp"

using namespace gearimpact;

namespace {

struct FeRow {
  std::string case_name;
  double s_m;
  double spall_width_m;
  int gear;
  double whole_face_m_per_n;
  double loaded_width_m_per_n;
  double last_mesh_change;
};

std::vector<FeRow> fe_rows() {
  std::ifstream in(std::string(GEARIMPACT_VERIFY_DATA_DIR) + "/fe_spall_3d.csv");
  REQUIRE(in);
  std::vector<FeRow> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::istringstream fields(line);
    FeRow r;
    std::string cell;
    std::getline(fields, r.case_name, ',');
    std::getline(fields, cell, ',');
    r.s_m = std::stod(cell);
    std::getline(fields, cell, ',');
    r.spall_width_m = std::stod(cell);
    std::getline(fields, cell, ',');
    r.gear = std::stoi(cell);
    std::getline(fields, cell, ',');
    r.whole_face_m_per_n = std::stod(cell);
    std::getline(fields, cell, ',');
    r.loaded_width_m_per_n = std::stod(cell);
    std::getline(fields, cell, ',');
    r.last_mesh_change = std::stod(cell);
    rows.push_back(r);
  }
  return rows;
}

// The rig and the paper's pair are examples; the third pair, kept for this check alone, lies
// beside the data.
GearPair pair_of(const std::string& case_name) {
  const std::string dir = case_name.rfind("fe_spall_", 0) == 0
                              ? std::string(GEARIMPACT_VERIFY_DATA_DIR)
                              : std::string(GEARIMPACT_EXAMPLES_DIR);
  return read_pair_or_run_file(dir + "/" + case_name + ".toml").simulation_case.gears;
}

const std::string kThirdPair = "fe_spall_pair_27_43";

StiffnessModel potential_energy(SpallReading reading) {
  StiffnessModel m;
  m.kind = StiffnessModelKind::potential_energy;
  m.spall_reading = reading;
  return m;
}

// The spall of fe-check --spall-width: on the pinion's drive flank, +-0.5 mm of roll about s,
// d_s = 0.2 mm.
ToothState spall_at(const GearPair& pair, double s_m, double width_m) {
  const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
  ToothState state;
  state.kind = ToothKind::spall;
  state.spall.start_radius_m = radius_at_roll_distance(geometry.gear1.base_radius_m, s_m - 5e-4);
  state.spall.end_radius_m = radius_at_roll_distance(geometry.gear1.base_radius_m, s_m + 5e-4);
  state.spall.width_m = width_m;
  state.spall.depth_m = 2e-4;
  return state;
}

// Bands (docs/verification.md, "The spall in 3-D"): each tooth's FE compliance growth C(L)/C(b)
// met within 3 % on the rig (the rows the fit saw: largest 2.5 %) and 6 % on the paper's pair
// (unseen by the fit: largest 5.8 %, its pinion at L = b/4); the pair's stiffness lost within
// 2.5 points of the FE's on both (largest 1.7 and 2.1 points). The FE's own error, under 0.5 %,
// is well inside each. The third pair (unseen by the fit, pressure angle 25 deg, b / m = 8):
// each tooth's growth within 9 % (largest 8.5 %, the wheel at s = 11.5 mm, L = b/4) and always
// below the FE's; the pair's loss short of the FE's on every row, by under 4 points (2.3 to
// 3.7): outside the band above, yet a tenth of the Hertz-only reading's shortfall there (12 to
// 44 points), which is why the rack-cut models read a spall by it by default.
constexpr double kToothBandRig = 0.03;
constexpr double kToothBandPaper = 0.06;
constexpr double kToothBandThird = 0.09;
constexpr double kLossBand = 0.025;
constexpr double kLossShortThird = 0.04;

}  // namespace

TEST_CASE("spall_width_factors: the closed form, the whole face, and its limits") {
  const double b = 0.015;
  const double sf = 0.008;
  const SpallWidthFactors whole = spall_width_factors(b, b, sf);
  CHECK(whole.beam == 1.0);
  CHECK(whole.foundation == 1.0);
  for (const double length : {0.25 * b, 0.5 * b, 0.75 * b}) {
    const SpallWidthFactors f = spall_width_factors(length, b, sf);
    // b / (L + lambda (1 - exp(-(b - L) / lambda))) written out with exp.
    for (const auto& [factor, lambda] : {std::pair{f.beam, kSpallBeamSpread * sf},
                                         std::pair{f.foundation, kSpallFoundationSpread * sf}}) {
      const double expected = b / (length + lambda * (1.0 - std::exp(-(b - length) / lambda)));
      CHECK(std::fabs(factor / expected - 1.0) < 1e-14);
      // Between the whole face (1) and the loaded width alone (b / L).
      CHECK(factor > 1.0);
      CHECK(factor < b / length);
    }
    // The foundation spreads further than the beam: it grows less.
    CHECK(f.foundation < f.beam);
  }
  // A tooth far thinner than the unloaded width spreads the load over L + lambda.
  const double thin = 1e-5;
  const SpallWidthFactors f = spall_width_factors(0.5 * b, b, thin);
  CHECK(std::fabs(f.beam / (b / (0.5 * b + kSpallBeamSpread * thin)) - 1.0) < 1e-12);
  CHECK_THROWS_AS(spall_width_factors(0.0, b, sf), std::invalid_argument);
  CHECK_THROWS_AS(spall_width_factors(1.1 * b, b, sf), std::invalid_argument);
  CHECK_THROWS_AS(spall_width_factors(0.5 * b, b, 0.0), std::invalid_argument);
}

TEST_CASE("The effective-width reading meets each tooth's 3-D FE compliance growth") {
  const std::vector<FeRow> rows = fe_rows();
  REQUIRE(rows.size() >= 18);
  StiffnessModel model = potential_energy(SpallReading::effective_width);
  std::map<std::string, double> worst;
  for (const FeRow& r : rows) {
    CAPTURE(r.case_name);
    CAPTURE(r.s_m);
    CAPTURE(r.spall_width_m);
    CAPTURE(r.gear);
    // The FE's own error, below the band by far.
    REQUIRE(r.last_mesh_change < 0.005);
    const RackGearPairGeometry pair = rack_gear_pair_geometry(pair_of(r.case_name));
    const PairContact contact = pair_contact(pair, r.s_m);
    const RackGearGeometry& gear = r.gear == 1 ? pair.gear1 : pair.gear2;
    const ToothCompliances c =
        tooth_compliances(gear, r.gear == 1 ? Gear::one : Gear::two,
                          r.gear == 1 ? contact.gear1 : contact.gear2, pair.contact_width_m, model);
    const double b = pair.contact_width_m;
    const SpallWidthFactors f = spall_width_factors(b - r.spall_width_m, b, root_thickness(gear));
    const double beam = c.bending_m_per_n + c.shear_m_per_n + c.axial_m_per_n;
    const double model_growth =
        (f.beam * beam + f.foundation * c.foundation_m_per_n) / c.total_m_per_n();
    const double fe_growth = r.loaded_width_m_per_n / r.whole_face_m_per_n;
    const double error = std::fabs(model_growth / fe_growth - 1.0);
    worst[r.case_name] = std::max(worst[r.case_name], error);
    if (r.case_name == kThirdPair) {
      CHECK(error < kToothBandThird);
      CHECK(model_growth < fe_growth);
    } else {
      CHECK(error < (r.case_name == "rig_17_38" ? kToothBandRig : kToothBandPaper));
    }
    // Neither older reading is within the band: the beam over the whole face (growth 1) ...
    CHECK(fe_growth - 1.0 > 0.09);
  }
  // The three pairs are all there (before the message below names them).
  CHECK(worst.size() == 3);
  MESSAGE("largest tooth errors: rig " << worst["rig_17_38"] << ", paper's pair "
                                       << worst["paper_pair_bores"] << ", third pair "
                                       << worst[kThirdPair]);
}

TEST_CASE("mesh_stiffness with a spalled pinion: the pair's stiffness lost against the FE's") {
  const std::vector<FeRow> rows = fe_rows();
  const StiffnessModel effective = potential_energy(SpallReading::effective_width);
  const StiffnessModel hertz_only = potential_energy(SpallReading::hertz_only);
  const ToothState healthy;
  int compared = 0;
  for (const FeRow& r : rows) {
    if (r.gear != 1) continue;
    // The wheel's row of the same case, position and width.
    const auto wheel = std::find_if(rows.begin(), rows.end(), [&](const FeRow& w) {
      return w.gear == 2 && w.case_name == r.case_name && w.s_m == r.s_m &&
             w.spall_width_m == r.spall_width_m;
    });
    REQUIRE(wheel != rows.end());
    CAPTURE(r.case_name);
    CAPTURE(r.s_m);
    CAPTURE(r.spall_width_m);
    const GearPair pair = pair_of(r.case_name);
    const double b = pair.face_width_m;
    // The FE pair: Hertz (4) over the contact length plus both teeth, as the models add.
    const double fe_healthy =
        1.0 / hertz_stiffness(pair, b) + r.whole_face_m_per_n + wheel->whole_face_m_per_n;
    const double fe_spalled = 1.0 / hertz_stiffness(pair, b - r.spall_width_m) +
                              r.loaded_width_m_per_n + wheel->loaded_width_m_per_n;
    const double fe_loss = 1.0 - fe_healthy / fe_spalled;
    const ToothState spalled = spall_at(pair, r.s_m, r.spall_width_m);
    const double k_healthy = mesh_stiffness(pair, r.s_m, effective).ke;
    const double loss =
        1.0 - mesh_stiffness(pair, r.s_m, effective, spalled, healthy).ke / k_healthy;
    if (r.case_name == kThirdPair) {
      CHECK(fe_loss - loss > 0.0);
      CHECK(fe_loss - loss < kLossShortThird);
    } else {
      CHECK(std::fabs(loss - fe_loss) < kLossBand);
    }
    // The Hertz-only reading misses most of the FE's loss.
    const double loss_hertz = 1.0 - mesh_stiffness(pair, r.s_m, hertz_only, spalled, healthy).ke /
                                        mesh_stiffness(pair, r.s_m, hertz_only).ke;
    CHECK(loss_hertz < 0.5 * fe_loss);
    // The rack-cut model's default reading is the effective-width one, to the bit.
    StiffnessModel by_default;
    by_default.kind = StiffnessModelKind::potential_energy;
    CHECK(mesh_stiffness(pair, r.s_m, by_default, spalled, healthy).ke ==
          mesh_stiffness(pair, r.s_m, effective, spalled, healthy).ke);
    ++compared;
  }
  CHECK(compared == 27);
}

TEST_CASE("The effective-width reading leaves a healthy pair and a spall out of contact alone") {
  const GearPair pair = pair_of("rig_17_38");
  const StiffnessModel effective = potential_energy(SpallReading::effective_width);
  const StiffnessModel hertz_only = potential_energy(SpallReading::hertz_only);
  const ToothState healthy;
  // The spall's band about s = 8 mm; a contact at s = 12 mm lies above it: the whole face.
  const ToothState spalled = spall_at(pair, 8e-3, 7.5e-3);
  for (const double s : {4e-3, 12e-3}) {
    CHECK(mesh_stiffness(pair, s, effective, spalled, healthy).ke ==
          mesh_stiffness(pair, s, hertz_only, spalled, healthy).ke);
  }
  CHECK(mesh_stiffness(pair, 8e-3, effective).ke == mesh_stiffness(pair, 8e-3, hertz_only).ke);
}

TEST_CASE("The paper's model reads a spall Hertz-only by default, to the bit") {
  const GearPair pair = pair_of("paper_pair_bores");
  StiffnessModel by_default;
  StiffnessModel hertz_only;
  hertz_only.spall_reading = SpallReading::hertz_only;
  REQUIRE(by_default.kind == StiffnessModelKind::yang_lin_1987);
  CHECK_NOTHROW(check_spall_reading(by_default, "model"));
  const ToothState spalled = spall_at(pair, 6.8e-3, 5e-3);
  for (const double s : {6.6e-3, 6.8e-3, 7e-3}) {
    CAPTURE(s);
    // In the band the spall shortens the contact: the default is not the healthy pair.
    CHECK(mesh_stiffness(pair, s, by_default, spalled, ToothState{}).ke <
          mesh_stiffness(pair, s, by_default).ke);
    CHECK(mesh_stiffness(pair, s, by_default, spalled, ToothState{}).ke ==
          mesh_stiffness(pair, s, hertz_only, spalled, ToothState{}).ke);
  }
  CHECK(parse_spall_reading("by-model", "spall_reading") == SpallReading::by_model);
}

TEST_CASE("The effective-width reading is refused with the paper's model, naming its key") {
  StiffnessModel model;
  model.kind = StiffnessModelKind::yang_lin_1987;
  model.spall_reading = SpallReading::effective_width;
  try {
    check_spall_reading(model, "model");
    FAIL("no refusal");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("model.spall_reading") != std::string::npos);
    CHECK(std::string(e.what()).find("hertz-only") != std::string::npos);
  }
  model.kind = StiffnessModelKind::ross_compatible;
  CHECK_NOTHROW(check_spall_reading(model, "model"));
  CHECK(parse_spall_reading("effective-width", "spall_reading") == SpallReading::effective_width);
  CHECK_THROWS_AS(parse_spall_reading("width", "spall_reading"), InputError);
}

TEST_CASE("model.spall_reading in a case file: read, written back, refused by name") {
  const std::string gears =
      "[gears]\nteeth1 = 17\nteeth2 = 38\nmodule = \"3 mm\"\nface_width = \"15 mm\"\n"
      "bore_diameter1 = \"20 mm\"\nbore_diameter2 = \"40 mm\"\npressure_angle = \"20 deg\"\n"
      "youngs_modulus = \"206 GPa\"\npoisson_ratio = 0.3\ndensity = \"7850 kg/m^3\"\n"
      "backlash = \"0.05 mm\"\nprofile_shift1 = 0.1\nprofile_shift2 = -0.1\n";
  const PairOrRunCase read =
      parse_pair_or_run(gears +
                            "[model]\nstiffness_model = \"potential-energy\"\nspall_reading = "
                            "\"effective-width\"\n",
                        "spall.toml");
  CHECK(read.simulation_case.model.stiffness.spall_reading == SpallReading::effective_width);
  CHECK(write_case_file(read.simulation_case).find("spall_reading = \"effective-width\"") !=
        std::string::npos);
  // Absent: the default, by the model: effective-width for the rack-cut models, Hertz-only for
  // the paper's (the file's model is the default, yang-lin-1987), and not written back.
  const PairOrRunCase absent = parse_pair_or_run(gears, "healthy.toml");
  CHECK(absent.simulation_case.model.stiffness.spall_reading == SpallReading::by_model);
  CHECK(applied_spall_reading(absent.simulation_case.model.stiffness) == SpallReading::hertz_only);
  CHECK(write_case_file(absent.simulation_case).find("spall_reading") == std::string::npos);
  const PairOrRunCase absent_pe =
      parse_pair_or_run(gears + "[model]\nstiffness_model = \"potential-energy\"\n", "pe.toml");
  CHECK(applied_spall_reading(absent_pe.simulation_case.model.stiffness) ==
        SpallReading::effective_width);
  for (const std::string& model :
       {std::string("spall_reading = \"effective-width\"\n"),
        std::string("stiffness_model = \"potential-energy\"\nspall_reading = \"wide\"\n")}) {
    CAPTURE(model);
    try {
      parse_pair_or_run(gears + "[model]\n" + model, "bad.toml");
      FAIL("no refusal");
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find("model.spall_reading") != std::string::npos);
    }
  }
}

TEST_CASE("The run's tables read the effective-width reading as mesh_stiffness does") {
  const GearPair pair = pair_of("rig_17_38");
  const StiffnessModel effective = potential_energy(SpallReading::effective_width);
  const StiffnessModel hertz_only = potential_energy(SpallReading::hertz_only);
  ToothFault fault;
  fault.gear = Gear::one;
  fault.tooth = 0;
  fault.state = spall_at(pair, 8e-3, 7.5e-3);
  const MeshTables tables(pair, effective, {fault});
  const MeshTables default_tables(pair, hertz_only, {fault});
  const StiffnessTable* drive = tables.table_of_teeth(0, 0, Region::n1);
  const StiffnessTable* drive_default = default_tables.table_of_teeth(0, 0, Region::n1);
  REQUIRE(drive != nullptr);
  REQUIRE(drive_default != nullptr);
  for (const double s : {6e-3, 7.6e-3, 8e-3, 8.4e-3, 10e-3}) {
    CAPTURE(s);
    const double direct = mesh_stiffness(pair, s, effective, fault.state, ToothState{}).ke;
    // The table's fit and the quadrature at the model's tolerance (as test_mesh_tables).
    CHECK(std::fabs(drive->stiffness(s) / direct - 1.0) < 1e-11);
    const bool in_band = s > 7.5e-3 && s < 8.5e-3;
    if (in_band) {
      CHECK(drive->stiffness(s) < 0.8 * drive_default->stiffness(s));
    } else {
      CHECK(std::fabs(drive->stiffness(s) / drive_default->stiffness(s) - 1.0) < 1e-12);
    }
  }
}
