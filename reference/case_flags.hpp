// The command-line flags that set keys of the case schema, shared by
// `simulate`, `sweep-friction` and `schema --flags` (the table in
// docs/case-files.md).
#pragma once

namespace gearimpact::cli {

// A flag that sets one key of the case. Its value is read and checked by the
// key's schema row (a plain number is SI, "20 ms" carries its unit); the
// default is the case's own. A switch (`switch_value` set) takes no value and
// sets that one.
struct CaseFlag {
  const char* flag;
  const char* key;
  bool on_sweep;  // also a flag of sweep-friction, which sets f itself and runs RK4
  const char* switch_value = nullptr;
};

inline constexpr CaseFlag kCaseFlags[] = {
    {"--friction", "model.friction_coefficient", false},
    {"--dt", "integrator.step", true},
    {"--t-end", "integrator.end_time", true},
    {"--integrator", "integrator.kind", false},
    {"--rtol", "integrator.relative_tolerance", false},
    {"--every", "integrator.output_every", false},
    {"--damping-form", "model.damping_form", true},
    {"--damping-stiffness", "model.damping_stiffness", true},
    {"--restitution-coefficient", "model.restitution_coefficient", true},
    {"--restitution-exponent", "model.restitution_exponent", true},
    {"--speed-unit", "model.restitution_speed_unit", true},
    {"--coast-phase", "model.coast_phase", true},
    {"--flipped-moment", "model.moment_sign", true, "flipped"},
};

// Values the command line used to spell otherwise than case files; they are
// still read, with a notice naming the case-file spelling.
struct OldSpelling {
  const char* key;
  const char* old_text;
  const char* text;
};

inline constexpr OldSpelling kOldSpellings[] = {
    {"model.damping_stiffness", "pair", "current-pair"},
    {"model.damping_stiffness", "pitch-pair", "pitch-pair-at-impact"},
    {"model.coast_phase", "half-pitch", "half-base-pitch"},
    {"model.restitution_speed_unit", "mm/s", "1 mm/s"},
    {"model.restitution_speed_unit", "in/s", "1 in/s"},
    {"model.restitution_speed_unit", "m/s", "1 m/s"},
};

}  // namespace gearimpact::cli
