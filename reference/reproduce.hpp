// `gearimpact reproduce`: the paper's figures and statements, one function a
// figure, each writing its CSV and plots into the output folder and returning
// its section of REPORT.md.
#pragma once

#include <filesystem>
#include <string>

#include "gearimpact/batch/pool.hpp"
#include "gearimpact/batch/sweep_friction.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/paper/statements.hpp"
#include "gnuplot.hpp"
#include "report.hpp"

namespace gearimpact::cli {

struct ReproduceContext {
  std::filesystem::path out;
  std::filesystem::path paper_data;
  // Every simulation of the reproduction runs here, once.
  RunPool* pool = nullptr;
};

// `value` with `digits` significant digits.
std::string number(double value, int digits);

// A report row for statement `s`: the paper's value or range as text, ours
// as given, the tolerance from the statement, pass or fail.
ReportRow statement_row(const PaperStatement& s, const std::string& ours, bool matches);

ReportSection reproduce_fig8(const ReproduceContext& context);
// The three stiffness models and ISO 6336-1 for the paper's pair with the
// bores of the ROSS peer run (20 mm, 60 mm).
ReportSection reproduce_stiffness(const ReproduceContext& context);
ReportSection reproduce_time_histories(const ReproduceContext& context);
ReportSection reproduce_fig7(const ReproduceContext& context);
ReportSection reproduce_readings(const ReproduceContext& context);
ReportSection reproduce_case3_ensemble(const ReproduceContext& context);
// The loaded pair swept in w1 through ISO's N = 1/2, 1, 2 (docs/steady-state.md section 4).
ReportSection reproduce_steady_state(const ReproduceContext& context);
// A loose gear against a driver of fluctuating speed, mapped over the
// driver's speed amplitude and frequency, with the closed-form separation
// boundary (docs/model.md, section Rattle of a loose gear).
ReportSection reproduce_rattle(const ReproduceContext& context);
// The paper's pair with faulted and modified teeth (docs/faults.md): the mesh stiffness over a
// pinion revolution, its loss against crack depth, and the STE with a tip relief.
ReportSection reproduce_faults(const ReproduceContext& context);
// The test-rig-like pair of examples/rig_17_38.toml on elastic bearings (docs/vibration.md,
// docs/signals.md): its modes, the pinion bearing's signal healthy and with a root crack of
// growing depth (spectrum, TSA, condition indicators), and the pair at low load with a torque
// ripple, where the teeth separate.
ReportSection reproduce_vibration(const ReproduceContext& context);
// The finite-element check (fe-check, docs/verification.md), opt-in (`reproduce --fe`, minutes):
// the paper's wheel healthy and cracked in 2-D, the rig pair's half-face spall in 3-D.
ReportSection reproduce_fe(const ReproduceContext& context);
// The planetary stage (docs/planetary.md): the modes of Lin & Parker's (1999) example system for
// N = 3, 4 and 5 against their published frequencies, types and multiplicities; the ring-housing
// sensor's spectrum of the nonlinear stage healthy and with a cracked sun tooth; the phasing rule
// on a nonlinear run's mesh forces.
ReportSection reproduce_planetary(const ReproduceContext& context);
// The text of examples/rig_17_38.toml, compiled in.
const char* rig_17_38_toml();
// The texts of examples/planetary_lp99.toml and examples/planetary_stage_cracked_sun.toml.
const char* planetary_lp99_toml();
const char* planetary_stage_cracked_sun_toml();

}  // namespace gearimpact::cli
