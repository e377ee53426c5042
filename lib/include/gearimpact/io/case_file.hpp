// Case files: a SimulationCase written as TOML with units on every quantity.
// The keys, their units, ranges and defaults are the rows of the case schema
// (case/schema.hpp; the table in docs/case-files.md). Everything is read and
// checked here, before any work starts; the conversion to SI happens once.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

// A case file that cannot be used. The message names the file (and line when
// known), the field as section.key, the value as written and what is allowed.
class CaseFileError : public Error {
 public:
  CaseFileError(std::string file, std::string field, const std::string& message);
  // Every problem of the file at once (at least one), each with its "file:line".
  CaseFileError(std::string file, std::vector<Problem> problems);

  const std::string& file() const noexcept { return file_; }
  // "gears.module"; empty when the file is not valid TOML or cannot be read.
  const std::string& field() const noexcept { return field_; }
  // One per problem, the first's field is field().
  const std::vector<Problem>& problems() const noexcept { return problems_; }

 private:
  std::string file_;
  std::string field_;
  std::vector<Problem> problems_;
};

// Parses and validates `toml_text`; `file_name` is used in messages and, when
// the file has no `name` key, its stem names the case. Throws CaseFileError.
// Checks every key by its schema row, then the checks across keys
// (validate_relations) and the step against the contact resolution
// (validate_step), each at the line of the key it names.
SimulationCase parse_case(std::string_view toml_text, std::string_view file_name);

// Reads and parses a case file (at most 1 MiB). Throws CaseFileError.
SimulationCase read_case_file(const std::filesystem::path& path);

// The text a case file gives `key` (section.key) when it is a string, "1000 rpm" say, so that a
// program can show a value in the unit its user chose; empty when the file cannot be read as
// TOML, lacks the key or gives it another type (read_case_file says what is wrong with it).
std::string case_file_text(const std::filesystem::path& path, const std::string& key);

// What a case file describes. A pair file has pair sections only (is_pair_section; and the
// top-level `name`): a gear pair and its models, enough for the stiffness commands and `report`;
// the torques, initial conditions and integrator keep their defaults, the keys a run would need
// are listed in SimulationCase::run_keys_absent, and every run refuses the case naming them. A run
// file is anything else, read as read_case_file reads it: a file with [initial] but no [torque1]
// is a run file missing a section, and is told so.
enum class CaseFileKind { pair, run };

struct PairOrRunCase {
  SimulationCase simulation_case;
  CaseFileKind kind = CaseFileKind::run;
};

// The sections of a pair file: [gears], [model], [modifications], [bearings] and [shafts].
bool is_pair_section(std::string_view section);

// parse_case for a pair file or a run file: a pair file's keys are checked by their schema rows,
// then the relations of the pair (validate_relations); what a run implies (validate_implied) is
// checked for a run file only. Throws CaseFileError.
PairOrRunCase parse_pair_or_run(std::string_view toml_text, std::string_view file_name);
PairOrRunCase read_pair_or_run_file(const std::filesystem::path& path);

struct GearTrain;
struct PlanetaryStage;

// True when the TOML text has [[bodies]]: a train file. Throws CaseFileError
// for text that is no TOML.
bool is_train_text(std::string_view toml_text, std::string_view file_name);
bool is_train_file(const std::filesystem::path& path);

// A train file (docs/case-files.md, A gear train) read into a GearTrain: its [[bodies]] (by the
// rows of train_schema()), its [[meshes]], each the pair of the file's pair sections ([gears],
// [model], [modifications], [bearings], [[faults]]: every mesh's defaults) with the mesh's own
// sub-tables over them, key by key (its [[meshes.faults]] replacing the file's), read and checked
// as a pair file's, and its [[shafts]]; [integrator] is the train's. Problems name the key as
// written, under the body's or mesh's name (bodies.idler.inertia,
// meshes.idler-wheel.gears.backlash), each at its line, all at once. A file without [[bodies]]
// is a two-gear case: parse_case reads it, two_gear_train makes it a train. Throws
// CaseFileError.
//
// `sets`, "KEY=VALUE" each (the program's --set), are written into the file's tables before
// they are read, as if the file said so (a body's default inertia follows a mesh's gears):
// bodies.NAME.KEY, meshes.NAME.KEY, meshes.NAME.SECTION.KEY (a mesh's own pair key), or a key of
// the file itself, SECTION.KEY (integrator.end_time; gears.module: every mesh's default). The
// value is checked by its row; InputError names KEY, and NAME among the file's names.
GearTrain parse_train(std::string_view toml_text, std::string_view file_name,
                      const std::vector<std::string>& sets = {});
GearTrain read_train_file(const std::filesystem::path& path,
                          const std::vector<std::string>& sets = {});

// A stage file (docs/planetary.md, A stage file): [stage] (the rows of train_schema() of
// "stage"), [gears] and [model] (the meshes' keys; the tooth counts are the stage's) and
// [integrator], read into the nonlinear rotational stage of dynamics/planetary_train.hpp; --set
// as on a train file (stage.KEY too). is_stage_text: the TOML text has [stage]. Throws
// CaseFileError naming every key as written (stage.sun_torque.kind, gears.module) with its
// allowed range, and what planetary_train refuses (a ring that does not close), before any work.
bool is_stage_text(std::string_view toml_text, std::string_view file_name);
bool is_stage_file(const std::filesystem::path& path);
PlanetaryStage parse_stage(std::string_view toml_text, std::string_view file_name,
                           const std::vector<std::string>& sets = {});
PlanetaryStage read_stage_file(const std::filesystem::path& path,
                               const std::vector<std::string>& sets = {});

// How write_case_file writes quantities: in the units a person would choose
// (mm, deg, GPa, N*mm, us, ms) wherever that text reads back to exactly the
// same double, or all in SI units (m, rad, Pa, N*m, s).
enum class CaseUnits { readable, si };

// TOML text that parse_case reads back to the same case, field by field and
// bit for bit. A gear pair alone (run_keys_absent not empty) is written as a
// pair file, which parse_pair_or_run reads back alike. Throws InputError for a Torque::Kind::user
// torque, which has no text form.
std::string write_case_file(const SimulationCase& simulation_case,
                            CaseUnits units = CaseUnits::readable);

}  // namespace gearimpact
