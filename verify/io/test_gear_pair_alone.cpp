// A gear pair alone (a pair file: [gears] and [model], no torques, no end time) through every
// function that needs the gears only, in the library and the program, and every run refusing it
// by the keys it lacks. The reference of each gears-only result is the same function on the same
// pair given as a whole run case (the pair plus torques and an end time): the run keys must not
// change a result that does not read them, bit for bit.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/case/schema.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/modes/modes.hpp"
#include "gearimpact/stiffness/iso6336.hpp"
#include "gearimpact/stiffness/static_transmission_error.hpp"
#include "gearimpact/stiffness/table.hpp"
#include "run_command.hpp"
#include "scratch.hpp"

using namespace gearimpact;
using namespace gearimpact::verify;

namespace {

// A user's pair, as a designer writes it: the gears and a stiffness model, nothing of a run.
const std::string kPair = R"(name = "p"
[gears]
youngs_modulus = "206 GPa"
poisson_ratio = 0.3
density = "7850 kg/m^3"
backlash = "0.05 mm"
teeth1 = 29
teeth2 = 71
module = "2.5 mm"
face_width = "18 mm"
pressure_angle = "20 deg"
bore_diameter1 = "25 mm"
bore_diameter2 = "60 mm"
[model]
stiffness_model = "potential-energy"
)";

// The same pair as a run: torques, speeds and an end time added.
const std::string kRun = kPair + R"(
[torque1]
kind = "constant"
value = "50 N*m"
[torque2]
kind = "constant"
value = "-122.41379310344827 N*m"
[initial]
w1 = "1000 rpm"
w2 = "408.45070422535213 rpm"
[integrator]
end_time = "1 ms"
)";

const std::vector<std::string> kRunKeys = {"torque1.kind", "torque2.kind", "integrator.end_time"};

// The fields an InputError names, in order.
std::vector<std::string> fields_of(const InputError& e) {
  std::vector<std::string> fields;
  for (const Problem& p : e.problems()) fields.push_back(p.field);
  return fields;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("a gear pair alone: read, written, and the gears-only functions as on the whole case") {
  const PairOrRunCase read = parse_pair_or_run(kPair, "p.toml");
  REQUIRE(read.kind == CaseFileKind::pair);
  const SimulationCase& pair = read.simulation_case;
  CHECK(pair.run_keys_absent == kRunKeys);
  const PairOrRunCase whole = parse_pair_or_run(kRun, "run.toml");
  REQUIRE(whole.kind == CaseFileKind::run);
  const SimulationCase& run = whole.simulation_case;
  CHECK(run.run_keys_absent.empty());

  // Written as a pair file (no section of a run), which reads back to the same text; a run
  // reader refuses it by the keys it lacks.
  const std::string written = write_case_file(pair, CaseUnits::si);
  CHECK_FALSE(has(written, "[torque1]"));
  CHECK_FALSE(has(written, "[integrator]"));
  CHECK_FALSE(has(written, "[initial]"));
  const PairOrRunCase again = parse_pair_or_run(written, "again.toml");
  CHECK(again.kind == CaseFileKind::pair);
  CHECK(write_case_file(again.simulation_case, CaseUnits::si) == written);
  try {
    (void)parse_case(written, "again.toml");
    FAIL("a pair file read as a run");
  } catch (const CaseFileError& e) {
    CHECK(has(e.what(), "torque1"));
  }

  // The gears-only functions: the fields' checks, the mesh stiffness, the STE, ISO 6336 and the
  // modes give on the pair alone exactly what they give on the whole case.
  CHECK_NOTHROW(validate_fields(pair));
  const StiffnessTable pair_table(pair.gears, pair.model.stiffness);
  const StiffnessTable run_table(run.gears, run.model.stiffness);
  const double x = 0.5 * (pair_table.domain_start_m() + pair_table.domain_end_m());
  CHECK(pair_table.stiffness(x) == run_table.stiffness(x));
  const StaticTransmissionError ste =
      static_transmission_error(pair.gears, pair.modifications, 50.0, pair_table);
  const StaticTransmissionError ste_run =
      static_transmission_error(run.gears, run.modifications, 50.0, run_table);
  REQUIRE(ste.points.size() == ste_run.points.size());
  CHECK(ste.ste_peak_to_peak_m == ste_run.ste_peak_to_peak_m);
  CHECK(ste.points.back().ste_m == ste_run.points.back().ste_m);
  CHECK(iso6336_method_b(iso6336_pair(pair.gears, 0.0)).single_stiffness_n_per_m2 ==
        iso6336_method_b(iso6336_pair(run.gears, 0.0)).single_stiffness_n_per_m2);
  const Modes modes = natural_modes(pair);
  const Modes modes_run = natural_modes(run);
  REQUIRE(modes.modes.size() == modes_run.modes.size());
  CHECK(modes.modes.back().frequency_hz == modes_run.modes.back().frequency_hz);
  CHECK(largest_resolving_step_s(pair) == largest_resolving_step_s(run));
}

TEST_CASE("every run refuses a gear pair alone, naming the keys it lacks") {
  const SimulationCase pair = parse_pair_or_run(kPair, "p.toml").simulation_case;
  // Before the library's default torques (zero) and end time (30 ms) could run silently.
  try {
    (void)simulate(pair);
    FAIL("a run of a gear pair alone");
  } catch (const InputError& e) {
    CHECK(fields_of(e) == kRunKeys);
    CHECK(has(e.what(), "torque1.kind = absent"));
    CHECK(has(e.what(), "a run needs it"));
  }
  try {
    validate(pair);
    FAIL("validate passed a gear pair alone");
  } catch (const InputError& e) {
    CHECK(e.field() == "torque1.kind");
  }
  SteadySweepSpec spec;
  spec.base = pair;
  spec.vary = "initial.w1";
  spec.from_si = 100.0;
  spec.to_si = 200.0;
  spec.points = 2;
  try {
    (void)run_steady_sweep(spec);
    FAIL("a sweep of a gear pair alone");
  } catch (const InputError& e) {
    CHECK(e.field() == "torque1.kind");
  }
}

TEST_CASE("the program: a pair file through every gears-only command; simulate refuses it") {
  const Scratch scratch("gear-pair-alone");
  const std::filesystem::path file = scratch.dir / "p.toml";
  std::ofstream(file) << kPair;
  const std::string f = file.string();
  for (const std::string& command :
       {"check-case " + f, "stiffness --points 3 --case-file " + f,
        "mesh-stiffness --samples 8 --summary --case-file " + f, "iso6336 --case-file " + f,
        "energy-ratios --points 3 --case-file " + f,
        "ste " + f + " --torque '50 N*m' --out " + (scratch.dir / "ste").string(),
        "modes " + f + " --out " + (scratch.dir / "modes").string(),
        "report " + f + " --out " + (scratch.dir / "report").string()}) {
    CAPTURE(command);
    const CommandResult r = run_command(cli(command));
    CHECK_MESSAGE(r.exit_code == 0, r.err);
  }
  const CommandResult run = run_command(
      cli("simulate --case-file " + f + " --out " + (scratch.dir / "run.csv").string()));
  CHECK(run.exit_code == 1);
  CHECK_MESSAGE(has(run.err, "torque1"), run.err);
  CHECK_FALSE(std::filesystem::exists(scratch.dir / "run.csv"));
}
