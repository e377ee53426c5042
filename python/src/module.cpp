// gearimpact._core: the library's value types and functions for Python, numpy
// arrays in and out. The Python layer (python/gearimpact/__init__.py) adds the
// keyword-argument case editing, the coercions (a case number, a file name)
// and the docstrings users read; this file stays a thin mirror of the library.
//
// Long computations run with the GIL released and stop on Ctrl-C: the
// simulation through RunControl::should_stop, the stiffness samples point by
// point; either way the KeyboardInterrupt raised by Python's signal handler is
// what the caller gets.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "case_flags.hpp"
#include "gearimpact/gearimpact.hpp"
#include "gearimpact/io/sweep_files.hpp"
#include "program.hpp"

namespace py = pybind11;

namespace gearimpact::python {

namespace {

// The module's exception types, created once at import and kept for the life
// of the interpreter (never released, as the interpreter may outlive the
// module's static storage at exit).
PyObject* case_error = nullptr;
PyObject* convergence_error = nullptr;
PyObject* quadrature_error = nullptr;
PyObject* simulation_error = nullptr;

// CaseError(message) with .field (the key as section.key or the library's
// parameter name; may be empty) and .file (the case file, when there is one).
void set_case_error(const char* message, const std::string& field, const std::string& file) {
  py::object error = py::reinterpret_borrow<py::object>(case_error)(message);
  error.attr("field") = field;
  error.attr("file") = file;
  PyErr_SetObject(case_error, error.ptr());
}

void translate_exceptions(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const CaseFileError& e) {
    set_case_error(e.what(), e.field(), e.file());
  } catch (const InputError& e) {
    set_case_error(e.what(), e.field(), "");
  } catch (const QuadratureError& e) {
    PyErr_SetString(quadrature_error, e.what());
  } catch (const ShootingError& e) {
    PyErr_SetString(convergence_error, e.what());
  } catch (const SimulationError& e) {
    PyErr_SetString(simulation_error, e.what());
  } catch (const Error& e) {
    // The rest of the library's errors are about what it was given: a file or
    // folder it cannot read or write.
    set_case_error(e.what(), "", "");
  }
}

// Watches for Ctrl-C while the GIL is released. Python runs its signal
// handlers only in the main thread: the thread that made the call (when it is
// the main thread) takes the GIL and lets them run; a KeyboardInterrupt they
// raise is kept and raised again once the computation has stopped. Other
// threads (the friction sweep's workers) only read whether to stop.
class InterruptWatch {
 public:
  bool operator()() {
    if (stop_.load()) return true;
    if (std::this_thread::get_id() == caller_) {
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        error_.emplace();
        stop_.store(true);
      }
    }
    return stop_.load();
  }
  std::function<bool()> callback() {
    return [this] { return (*this)(); };
  }
  // With the GIL held: raises what the signal handler raised, if it did.
  void raise_if_interrupted() {
    if (error_) throw std::move(*error_);
  }

 private:
  std::thread::id caller_ = std::this_thread::get_id();
  std::atomic<bool> stop_{false};
  std::optional<py::error_already_set> error_;
};

// Runs f with the GIL released and Ctrl-C watched; f takes the stop callback.
// A Ctrl-C caught as f finished anyway is raised too, not lost.
template <typename F>
auto interruptible(F&& f) {
  InterruptWatch watch;
  try {
    auto result = [&] {
      py::gil_scoped_release release;
      return f(watch.callback());
    }();
    watch.raise_if_interrupted();
    return result;
  } catch (const SimulationStopped&) {
    watch.raise_if_interrupted();
    throw;
  }
}

template <typename T>
py::array_t<T> to_array(const std::vector<T>& values) {
  py::array_t<T> array(static_cast<py::ssize_t>(values.size()));
  T* data = array.mutable_data();
  for (std::size_t i = 0; i < values.size(); ++i) data[i] = values[i];
  return array;
}

// The signal layer's inputs as the keywords that give them.
std::vector<double> vector_of(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* name) {
  if (a.ndim() != 1) {
    throw InputError(name, std::to_string(a.ndim()) + "-dimensional array",
                     "a 1-dimensional array");
  }
  return std::vector<double>(a.data(), a.data() + a.size());
}

std::size_t count_of(long long value, const char* name) {
  if (value < 0) throw InputError(name, std::to_string(value), "a whole number >= 0");
  return static_cast<std::size_t>(value);
}

template <typename Run>
auto naming_keywords(Run run) {
  try {
    return run();
  } catch (const InputError& e) {
    static const std::vector<std::pair<std::string, std::string>> keywords{
        {"sample rate", "rate"},
        {"output rate", "rate_out"},
        {"samples per revolution", "samples_per_revolution"},
        {"shaft orders", "shaft_orders"},
        {"nb4 half width", "nb4_half_width"},
        {"band", "max_order"}};
    std::vector<Problem> problems;
    for (const Problem& p : e.problems()) {
      std::string field = p.field;
      for (const auto& [name, keyword] : keywords) {
        if (field == name) field = keyword;
      }
      problems.push_back(p.renamed(field, p.value));
    }
    throw InputError(problems);
  }
}

py::object optional_value(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

py::dict indicators_dict(const signals::Indicators& i) {
  py::dict d;
  d["rms"] = i.rms;
  d["peak"] = i.peak;
  d["crest_factor"] = optional_value(i.crest_factor);
  d["kurtosis"] = optional_value(i.kurtosis);
  d["tsa_rms"] = optional_value(i.tsa_rms);
  d["tsa_crest_factor"] = optional_value(i.tsa_crest_factor);
  d["tsa_kurtosis"] = optional_value(i.tsa_kurtosis);
  d["fm0"] = optional_value(i.fm0);
  d["fm4"] = optional_value(i.fm4);
  d["na4"] = optional_value(i.na4);
  d["nb4"] = optional_value(i.nb4);
  d["m6a"] = optional_value(i.m6a);
  d["m8a"] = optional_value(i.m8a);
  d["energy_ratio"] = optional_value(i.energy_ratio);
  d["sideband_level"] = optional_value(i.sideband_level);
  return d;
}

// One column of a vector of records, as a numpy array of the member's type.
template <typename Row, typename T>
py::array_t<T> column(const std::vector<Row>& rows, T Row::*member) {
  py::array_t<T> array(static_cast<py::ssize_t>(rows.size()));
  T* data = array.mutable_data();
  for (std::size_t i = 0; i < rows.size(); ++i) data[i] = rows[i].*member;
  return array;
}

// The arrays of an output's columns (io/results.hpp's tables, the CSV's names and order), one
// per column. A column that is a member of the row is a view into the rows themselves (a stride
// of one row), which the arrays keep alive: a copy would add as much time as the series takes to
// compute. A computed column is copied: into int64 when integral, else (or when a row may lack
// it, NaN there) into float64; a text column into a numpy str array.
template <typename Row>
py::dict table_arrays(const Columns<Row>& columns, std::vector<Row>&& rows) {
  auto* owned = new std::vector<Row>(std::move(rows));
  const py::capsule keeper(owned, [](void* p) { delete static_cast<std::vector<Row>*>(p); });
  const auto n = static_cast<py::ssize_t>(owned->size());
  const auto view = [&](auto Row::*member) {
    using T = std::remove_reference_t<decltype(std::declval<Row&>().*member)>;
    if (n == 0) return py::array_t<T>(0);
    return py::array_t<T>({n}, {static_cast<py::ssize_t>(sizeof(Row))}, &((*owned)[0].*member),
                          keeper);
  };
  const auto copy = [&](const Column<Row>& column, auto zero) {
    py::array_t<decltype(zero)> array(n);
    auto* data = array.mutable_data();
    for (py::ssize_t i = 0; i < n; ++i) {
      data[i] = static_cast<decltype(zero)>(column.value((*owned)[static_cast<std::size_t>(i)]));
    }
    return array;
  };
  py::dict table;
  for (const Column<Row>& column : columns) {
    if (column.text) {
      py::list texts;
      for (const Row& row : *owned) texts.append(column.text(row));
      table[column.name.c_str()] =
          py::module_::import("numpy").attr("array")(texts, py::arg("dtype") = "str");
    } else if (column.real_member != nullptr) {
      table[column.name.c_str()] = view(column.real_member);
    } else if (column.int_member != nullptr) {
      table[column.name.c_str()] = view(column.int_member);
    } else if (column.boolean) {
      table[column.name.c_str()] = copy(column, false);
    } else if (column.integral && !column.may_be_empty) {
      table[column.name.c_str()] = copy(column, std::int64_t{0});
    } else {
      table[column.name.c_str()] = copy(column, 0.0);
    }
  }
  return table;
}

py::object optional_number(const std::optional<double>& value) {
  return value ? py::object(py::float_(*value)) : py::object(py::none());
}

py::list impact_records(const std::vector<ImpactRecord>& impacts) {
  py::list records;
  for (const ImpactRecord& impact : impacts) {
    py::dict record;
    record["line"] = impact.line == Region::n1 ? "N1" : "N2";
    record["start_s"] = impact.start_s;
    record["impact_speed_m_s"] = impact.impact_speed_m_s;
    record["restitution"] = impact.restitution;
    record["end_s"] = optional_number(impact.end_s);
    record["end_speed_m_s"] = optional_number(impact.end_speed_m_s);
    records.append(record);
  }
  return records;
}

// summary_json's text (the program's JSON, parsed by the Python layer so that
// the keys and numbers are the program's), the series and the impacts.
py::tuple run_simulation(const SimulationCase& c, bool keep_series, long long max_rows,
                         std::optional<double> sample_rate_hz, const std::string& sample) {
  const SampleKind sample_kind = value_named(kSampleKinds, sample, "sample");
  SimulationResult result = interruptible([&](std::function<bool()> should_stop) {
    RunControl control;
    control.keep_series = keep_series;
    control.most_series_rows = max_rows;
    control.sample_rate_hz = sample_rate_hz;
    control.sample = sample_kind;
    control.should_stop = std::move(should_stop);
    return simulate(c, control);
  });
  // A planar run's series and samples are its own (the torsional columns would be empty).
  const bool planar = c.bearings.kind == BearingKind::elastic;
  const bool helical = c.gears.helix_angle_rad != 0.0;
  py::dict series =
      planar ? table_arrays(planar_series_columns(helical), std::move(result.planar_series))
             : table_arrays(series_columns(), std::move(result.series));
  py::dict samples = planar
                         ? table_arrays(planar_sample_columns(), std::move(result.planar_samples))
                         : table_arrays(sample_columns(), std::move(result.samples));
  py::list warnings;
  for (const std::string& w : result_warnings(c, result.summary)) warnings.append(w);
  return py::make_tuple(summary_json(result.summary), series, impact_records(result.impacts),
                        samples, to_array(result.tacho_times_s), warnings);
}

// A gear train's case file run as `gearimpact train` runs it: the summary's JSON
// (train_summary_json) and the series as arrays by train_series_columns, named by the file's
// bodies and meshes. `sets` as the command's --set.
// A stage file ([stage]) as the command runs it: the summary with the Willis residual, the
// ring sensor's y and the teeth at each mesh (mesh_teeth.csv) beside the series. Both need the
// whole series, so the run keeps it and keep_series only decides whether the arrays are returned.
py::tuple run_stage(const std::string& path, const std::vector<std::string>& sets,
                    bool keep_series) {
  const PlanetaryStage stage = read_stage_file(path, sets);
  const GearTrain train = planetary_train(stage);
  TrainResult result = interruptible([&](std::function<bool()> should_stop) {
    RunControl control;
    control.should_stop = std::move(should_stop);
    return simulate_train(train, control);
  });
  const std::string summary = stage_summary_json(train, result, planetary_willis(stage, result));
  std::vector<double> ring = planetary_ring_sensor(stage, result);
  std::vector<StageTeethRow> teeth = planetary_teeth_series(stage, result);
  std::vector<double> times;
  times.reserve(result.series.size());
  for (const TrainRow& row : result.series) times.push_back(row.t_s);
  if (!keep_series) {
    result.series.clear();
    ring.clear();
    times.clear();
    teeth.clear();
  }
  py::dict sensor;
  sensor["t_s"] = to_array(times);
  sensor["ring_sensor_y_N"] = to_array(ring);
  const std::size_t planets = train.bodies.size() - kFirstPlanetBody;
  return py::make_tuple(summary,
                        table_arrays(train_series_columns(train), std::move(result.series)), sensor,
                        table_arrays(stage_teeth_columns(planets), std::move(teeth)), py::none(),
                        py::none(), py::list());
}

// With sample_rate_hz, the sensor's samples as arrays by the same columns (the command's
// samples.csv), else None.
py::tuple run_train(const std::string& path, const std::vector<std::string>& sets, bool keep_series,
                    std::optional<double> sample_rate_hz, const std::string& sample) {
  const SampleKind sample_kind = value_named(kSampleKinds, sample, "sample");
  if (is_stage_file(path)) {
    if (sample_rate_hz) {
      throw InputError(std::vector<Problem>{refused_problem(
          "sample_rate", format_number(*sample_rate_hz) + " Hz",
          "not for a stage file: its ring sensor is returned at every step (ring_sensor)",
          "None for a stage file")});
    }
    return run_stage(path, sets, keep_series);
  }
  const GearTrain file = read_train_file(path, sets);
  TrainResult result = interruptible([&](std::function<bool()> should_stop) {
    RunControl control;
    control.keep_series = keep_series;
    control.sample_rate_hz = sample_rate_hz;
    control.sample = sample_kind;
    control.should_stop = std::move(should_stop);
    return simulate_train(file, control);
  });
  // Named by the meshes the run ran (a helical mesh by slices: one per slice).
  const GearTrain train = dynamics_train(file);
  const std::string summary = train_summary_json(train, result);
  py::object samples = py::none();
  if (sample_rate_hz) {
    samples = table_arrays(train_series_columns(train), std::move(result.samples));
  }
  // The tacho's true edge times, as simulate's (the emitted ones are tacho.csv's jittered column).
  py::object tacho = py::none();
  if (file.tacho_body >= 0) tacho = to_array(result.tacho_times_s);
  py::list warnings;
  for (const std::string& w : train_warnings(file, result)) {
    warnings.append(w);
  }
  return py::make_tuple(summary,
                        table_arrays(train_series_columns(train), std::move(result.series)),
                        py::none(), py::none(), samples, tacho, warnings);
}

// The stiffness columns of `gearimpact stiffness` at the contact positions xs.
py::dict stiffness_columns(const GearPair& pair, const StiffnessModel& model,
                           const std::vector<double>& xs) {
  std::vector<MeshStiffness> k(xs.size());
  interruptible([&](const std::function<bool()>& should_stop) {
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (should_stop()) throw SimulationStopped("stiffness samples stopped");
      k[i] = mesh_stiffness(pair, xs[i], model);
    }
    return 0;
  });
  std::vector<double> phi1(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) phi1[i] = contact_angle(pair, Gear::one, xs[i]);
  py::dict table;
  table["x_m"] = to_array(xs);
  table["phi1_rad"] = to_array(phi1);
  // The program's columns, in its order (io/results.hpp).
  for (const StiffnessColumn& c : gearimpact::stiffness_columns()) {
    std::vector<double> values(k.size());
    for (std::size_t i = 0; i < k.size(); ++i) values[i] = stiffness_column_value(c, k[i], model);
    table[c.name.c_str()] = to_array(values);
  }
  return table;
}

// A count of contact positions (the Python layer has checked that it is an
// integer, exact as a double): `name` = value unless in [2, kMostSamples].
int sample_count(const char* name, long long value) {
  if (value < 2 || value > cli::kMostSamples) {
    throw InputError(name, std::to_string(value),
                     "an integer in [2, " + std::to_string(cli::kMostSamples) + "]");
  }
  return static_cast<int>(value);
}

// `points` positions from X_start to X_end inclusive, spaced as the program's
// `stiffness` command spaces them (the last one exactly X_end), so that the
// two give the same numbers.
py::dict stiffness_samples(const GearPair& pair, const StiffnessModel& model, long long points) {
  const int n = sample_count("points", points);
  validate(pair);
  validate(model);
  return stiffness_columns(pair, model, contact_positions(pair, n));
}

py::dict stiffness_at(const GearPair& pair, const StiffnessModel& model,
                      const py::array_t<double, py::array::c_style | py::array::forcecast>& x) {
  if (x.ndim() != 1) {
    throw InputError("x", std::to_string(x.ndim()) + "-dimensional array", "a 1-dimensional array");
  }
  validate(pair);
  validate(model);
  // mesh_stiffness checks the range too, but names X1; this names the argument.
  const double lp = line_of_action_length(pair);
  std::vector<double> xs(x.data(), x.data() + x.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i]) || xs[i] <= 0.0 || xs[i] >= lp) {
      throw InputError("x[" + std::to_string(i) + "]", xs[i],
                       "(0, lp) m with lp = " + format_number(lp) +
                           " m: a contact position between the tangent points C1 and C2");
    }
  }
  return stiffness_columns(pair, model, xs);
}

// The columns of `gearimpact energy-ratios`, and x_m.
py::dict energy_ratio_columns(const GearPair& pair, const StiffnessModel& model, long long points) {
  const int n = sample_count("points", points);
  validate(pair);
  validate(model);
  std::vector<EnergyRatios> rows;
  {
    py::gil_scoped_release release;
    rows = energy_ratio_cycle(pair, n, model);
  }
  py::dict table;
  table["angle_deg"] = column(rows, &EnergyRatios::phi1_deg);
  table["pairs"] = column(rows, &EnergyRatios::pairs);
  table["hertz_over_bending_one_pair"] = column(rows, &EnergyRatios::hertz_over_bending_one_pair);
  table["axial_over_bending_one_pair"] = column(rows, &EnergyRatios::axial_over_bending_one_pair);
  table["hertz_over_bending_system"] = column(rows, &EnergyRatios::hertz_over_bending_system);
  table["axial_over_bending_system"] = column(rows, &EnergyRatios::axial_over_bending_system);
  table["x_m"] = column(rows, &EnergyRatios::x1_m);
  return table;
}

// The worker threads asked for: 0 (one per core) to the program's --threads bound.
unsigned thread_count(long long threads) {
  if (threads < 0 || threads > cli::kMostThreads) {
    throw InputError("threads", std::to_string(threads),
                     "an integer in [0, " + std::to_string(cli::kMostThreads) + "] (0: all cores)");
  }
  return static_cast<unsigned>(threads);
}

// Fig. 7: the friction values and the ratio friction loss / damping loss of
// each case (one column a case). The library names the first friction "from",
// which Python spells from_.
py::tuple run_sweep(const std::vector<SimulationCase>& cases, double from, double to, double step,
                    long long threads) {
  const unsigned workers = thread_count(threads);
  const std::vector<SweepRow> rows = interruptible([&](const std::function<bool()>& should_stop) {
    try {
      return sweep_friction(cases, from, to, step, workers, should_stop);
    } catch (const InputError& e) {
      if (e.field() != "from") throw;
      throw InputError("from_", e.value(), e.allowed());
    }
  });
  py::array_t<double> ratio(
      {static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(cases.size())});
  auto r = ratio.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < cases.size(); ++j) {
      r(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(j)) = rows[i].ratio[j];
    }
  }
  return py::make_tuple(column(rows, &SweepRow::friction_coefficient), ratio);
}

TorqueUnit torque_unit_named(const std::string& name) {
  return value_named(kTorqueUnits, name, "torque_unit");
}

std::string gear_pair_repr(const GearPair& g) {
  return "GearPair(teeth1=" + std::to_string(g.teeth1) + ", teeth2=" + std::to_string(g.teeth2) +
         ", module_m=" + shortest_decimal(g.module_m) +
         ", pressure_angle_rad=" + shortest_decimal(g.pressure_angle_rad) +
         ", face_width_m=" + shortest_decimal(g.face_width_m) +
         ", addendum_coefficient=" + shortest_decimal(g.addendum_coefficient) +
         ", youngs_modulus_pa=" + shortest_decimal(g.youngs_modulus_pa) +
         ", poisson_ratio=" + shortest_decimal(g.poisson_ratio) +
         ", density_kg_m3=" + shortest_decimal(g.density_kg_m3) +
         ", backlash_m=" + shortest_decimal(g.backlash_m) + ")";
}

// The pair and model the stiffness commands read: the case's, or the paper's pair with the
// default model; `model` (a name of model.stiffness_model) replaces the case's.
SimulationCase stiffness_case(const std::optional<SimulationCase>& c,
                              const std::optional<std::string>& model) {
  SimulationCase chosen;
  chosen.gears = paper_gear_pair();
  if (c) chosen = *c;
  if (model) set_field(chosen, "model.stiffness_model", *model, "model");
  validate(chosen.gears);
  return chosen;
}

// `gearimpact mesh-stiffness` and its --summary: the table as arrays of the CSV's columns (the
// library's table of them) and the summary's JSON.
py::tuple mesh_stiffness_of(const std::optional<SimulationCase>& c,
                            const std::optional<std::string>& model, long long samples) {
  const int n = sample_count("samples", samples);
  const SimulationCase chosen = stiffness_case(c, model);
  if (chosen.gears.helix_angle_rad != 0.0) {
    // A helical pair: one mesh period by both routes of the slice model (docs/helical.md).
    if (!chosen.faults.empty()) {
      // With faults: over the true period, by the tables a run reads.
      TruePeriodMeshStiffness tvms;
      {
        py::gil_scoped_release release;
        tvms = helical_true_period_mesh_stiffness(chosen.gears, chosen.model.stiffness,
                                                  chosen.faults, static_cast<std::size_t>(n));
      }
      const std::string summary = true_period_mesh_stiffness_summary_json(
          tvms, helical_geometry(chosen.gears).total_contact_ratio);
      const Columns<TruePeriodSample> columns =
          true_period_mesh_stiffness_columns(most_pairs_in_contact(tvms));
      return py::make_tuple(table_arrays(columns, std::move(tvms.samples)), summary);
    }
    HelicalMeshStiffnessCurve curve;
    {
      py::gil_scoped_release release;
      curve = helical_mesh_stiffness(chosen.gears, chosen.model.stiffness, n);
    }
    const std::string summary = helical_mesh_stiffness_summary_json(curve);
    return py::make_tuple(table_arrays(helical_mesh_stiffness_columns(), std::move(curve.samples)),
                          summary);
  }
  TruePeriodMeshStiffness tvms;
  {
    py::gil_scoped_release release;
    tvms = true_period_mesh_stiffness(chosen.gears, chosen.model.stiffness, chosen.faults,
                                      static_cast<std::size_t>(n));
  }
  const std::string summary =
      true_period_mesh_stiffness_summary_json(tvms, contact_ratio(chosen.gears));
  const Columns<TruePeriodSample> columns =
      true_period_mesh_stiffness_columns(most_pairs_in_contact(tvms));
  return py::make_tuple(table_arrays(columns, std::move(tvms.samples)), summary);
}

// `gearimpact ste`: ste.csv's and ste_unmodified.csv's columns as arrays (the library's table of
// them) and summary.json's text;
// `torque` a quantity with its unit ("100 N*m").
py::tuple ste_texts_of(const SimulationCase& c, const std::string& torque, long long points) {
  const double t = parse_quantity(torque, Dimension::torque, "torque");
  if (points < 2 || points > 100000) {
    throw InputError("points", std::to_string(points), "an integer in [2, 100000] per mesh period");
  }
  validate(c.gears);
  validate(c.model.stiffness);
  validate_modifications(c.gears, c.modifications);
  if (c.gears.helix_angle_rad != 0.0) {
    // A helical pair: the slice model's STE, as `ste` writes it (docs/helical.md).
    cli::check_helical_ste(c, t, static_cast<int>(points));
    cli::HelicalSteFiles ste;
    {
      py::gil_scoped_release release;
      ste = cli::helical_ste_of(c, t, static_cast<int>(points));
    }
    const Columns<HelicalStePoint> columns = helical_ste_columns();
    return py::make_tuple(table_arrays(columns, std::move(ste.modified.points)),
                          table_arrays(columns, std::move(ste.unmodified.points)),
                          ste.summary_json);
  }
  cli::SteTexts texts;
  {
    py::gil_scoped_release release;
    texts = cli::ste_texts(c, t, static_cast<int>(points));
  }
  const Columns<StePoint> columns = ste_columns();
  return py::make_tuple(table_arrays(columns, std::move(texts.modified.points)),
                        table_arrays(columns, std::move(texts.unmodified.points)),
                        texts.summary_json);
}

// `gearimpact modes` on a planetary file: modes.csv's columns as arrays (the library's table of
// them) and summary.json's text.
py::tuple planetary_modes_of(const std::string& path) {
  const PlanetaryCase stage = read_planetary_file(path);
  PlanetaryModes modes;
  {
    py::gil_scoped_release release;
    modes = planetary_modes(planetary_model(stage.parameters));
  }
  const std::string summary = stage_modes_summary_json(stage.name, modes);
  return py::make_tuple(table_arrays(stage_modes_columns(), stage_mode_rows(modes)), summary);
}

// `gearimpact modes` on a train file: modes.csv's columns as arrays (the library's table of them)
// and summary.json's text, the file read with `sets` as --set.
py::tuple train_modes_of(const std::string& path, const std::vector<std::string>& sets) {
  const GearTrain train = read_train_file(path, sets);
  TrainModes modes;
  {
    py::gil_scoped_release release;
    modes = train_modes(train);
  }
  const std::string summary =
      train_modes_summary_json(std::filesystem::path(path).stem().string(), train, modes);
  return py::make_tuple(table_arrays(train_modes_columns(train), train_mode_rows(modes)), summary);
}

// `gearimpact modes`: modes.csv's, campbell.csv's and mode_shapes.csv's columns as arrays (the
// library's tables of them) and summary.json's text;
// `max_speed` a quantity with its unit ("6000 rpm"), absent for the program's default.
py::tuple modes_texts_of(const SimulationCase& c, long long harmonics,
                         const std::optional<std::string>& max_speed) {
  if (harmonics < 1 || harmonics > cli::kMostHarmonics) {
    throw InputError("harmonics", std::to_string(harmonics),
                     "an integer in [1, " + std::to_string(cli::kMostHarmonics) + "]");
  }
  std::optional<double> speed;
  if (max_speed) {
    speed = parse_quantity(*max_speed, Dimension::angular_velocity, "max_speed");
    if (!(*speed > 0.0)) {
      throw InputError("max_speed", "\"" + *max_speed + "\"",
                       "a pinion speed > 0 (" + allowed_units(Dimension::angular_velocity) + ")");
    }
  }
  validate_fields(c);
  cli::ModesTexts texts;
  {
    py::gil_scoped_release release;
    texts = cli::modes_texts(c, static_cast<int>(harmonics), speed);
  }
  const std::vector<ModeRow> rows = mode_rows(texts.modes);
  return py::make_tuple(
      table_arrays(modes_columns(texts.modes.model), std::vector<ModeRow>(rows)),
      table_arrays(campbell_columns(), std::move(texts.crossings)),
      table_arrays(mode_shapes_columns(texts.modes.model), std::vector<ModeRow>(rows)),
      texts.summary_json);
}

// `gearimpact sweep` of a case with the command's options: (sweep.csv, poincare.csv,
// summary.json) as the program writes them.
py::tuple sweep_texts(const SimulationCase& c, const std::vector<std::string>& options) {
  SteadySweep sweep;
  {
    py::gil_scoped_release release;
    sweep = cli::sweep_with_options(c, options);
  }
  return py::make_tuple(sweep_csv(sweep.rows), poincare_csv(sweep.rows), sweep_summary_json(sweep));
}

bool is_boolean(const py::handle& value) {
  return PyBool_Check(value.ptr()) ||
         py::isinstance(value, py::module_::import("numpy").attr("bool_"));
}

// True or False (numpy's too), nothing else: Python would take any object's
// truth, "no" among them.
bool boolean(const char* name, const py::handle& value) {
  if (!is_boolean(value)) {
    throw InputError(name, py::repr(value).cast<std::string>(), "True or False");
  }
  return value.cast<bool>();
}

// Gear 1 or 2 of a pair, the pair checked first: the geometry of a pair
// outside its ranges (a field set to NaN through GearPair's attributes) is no
// number at all. True and False (numpy's too) are not gear numbers, though
// Python counts them as integers.
Gear gear_numbered(const GearPair& pair, const py::handle& gear) {
  validate(pair);
  const std::string written = py::repr(gear).cast<std::string>();
  if (is_boolean(gear) || !PyIndex_Check(gear.ptr())) {
    throw InputError("gear", written, "1 or 2");
  }
  const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(gear.ptr()));
  if (!index) throw py::error_already_set();
  int overflow = 0;
  const long long number = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow != 0 || (number != 1 && number != 2)) throw InputError("gear", written, "1 or 2");
  return number == 1 ? Gear::one : Gear::two;
}

// The pair after validate(): its geometry is finite.
const GearPair& checked(const GearPair& pair) {
  validate(pair);
  return pair;
}

// paper_case's W of case 3, read by the schema row that holds its range, as
// the program's --case3-frequency is.
double case3_frequency(double value) {
  check_value(*find_field("torque1.angular_frequency"), value, "case3_frequency_rad_s",
              format_number(value));
  return value;
}

// A row's kind by name: the Python layer writes a bool as "on"/"off" for an
// on_off row and a number in the SI unit for a quantity.
const char* field_kind_name(FieldKind kind) {
  switch (kind) {
    case FieldKind::quantity:
      return "quantity";
    case FieldKind::number:
      return "number";
    case FieldKind::integer:
      return "integer";
    case FieldKind::choice:
      return "choice";
    case FieldKind::on_off:
      return "on_off";
    case FieldKind::text:
      return "text";
    case FieldKind::quantity_list:
      return "quantity_list";
    case FieldKind::number_list:
      return "number_list";
  }
  return "";
}

// The schema's rows for the Python layer, which resolves bare keys, lists the
// keys a case needs and reads units from them: one dict a row, in case-file
// order. "si_unit" is the unit an SI number is written in (None for a key
// without a unit), "unit" the readable one.
py::list schema_rows() {
  py::list rows;
  for (const Field& field : case_schema()) {
    py::dict row;
    row["key"] = field.name();
    row["section"] = std::string(field.section);
    row["bare"] = std::string(field.key);
    row["kind"] = field_kind_name(field.kind);
    const bool has_unit =
        field.kind == FieldKind::quantity || field.kind == FieldKind::quantity_list;
    row["si_unit"] =
        has_unit ? py::object(py::str(std::string(units_of(field.dimension).front().symbol)))
                 : py::object(py::none());
    row["unit"] = has_unit ? py::object(py::str(std::string(field.unit))) : py::object(py::none());
    row["required"] = field.required;
    // A key of the pair (a pair file holds these sections only), or of a run.
    row["pair"] = field.section.empty() || is_pair_section(field.section);
    if (field.only_when) {
      py::list choices;
      for (const std::string_view choice : field.only_when->choices) {
        choices.append(std::string(choice));
      }
      row["only_when"] = py::make_tuple(
          std::string(field.section) + "." + std::string(field.only_when->key), choices);
    } else {
      row["only_when"] = py::none();
    }
    row["default"] = default_text(field);
    row["allowed"] = allowed_text(field);
    rows.append(row);
  }
  return rows;
}

// Whether speeds Rb1 w1 and Rb2 w2 differ beyond the rounding of typed values:
// the relative bound of require_balanced_mean_torques, applied to the pitch-line
// speeds.
bool rolling(double speed1_m_s, double speed2_m_s) {
  return std::fabs(speed1_m_s - speed2_m_s) <=
         1e-9 * std::max(std::fabs(speed1_m_s), std::fabs(speed2_m_s));
}

// What a case's user should hear about before running it, with the library's
// numbers: the foundation fit used outside its range, mean torques that do not
// balance (T1/Rb1 + T2/Rb2 != 0, by require_balanced_mean_torques' bound) and
// speeds that do not roll (Rb1 w1 != Rb2 w2).
py::dict case_conditions(const SimulationCase& c) {
  py::dict out;
  const GearPair& pair = c.gears;
  const std::vector<FoundationExtrapolation> extrapolations =
      foundation_extrapolations(pair, c.model.stiffness);
  out["foundation_extrapolated"] = !extrapolations.empty();
  out["foundation_warning"] = foundation_extrapolation_warning(extrapolations);
  const double rb1 = base_radius(pair, Gear::one);
  const double rb2 = base_radius(pair, Gear::two);
  out["rb1_m"] = rb1;
  out["rb2_m"] = rb2;
  out["friction"] =
      c.model.friction_law != FrictionLaw::constant || c.model.friction_coefficient > 0.0;
  // A user's callable, a kinematic driver and a drag have no mean known before the run.
  const auto known_mean = [](const Torque& t) {
    return t.kind == Torque::Kind::constant || t.kind == Torque::Kind::sinusoidal ||
           t.kind == Torque::Kind::harmonic;
  };
  const bool known_means = known_mean(c.torque1) && known_mean(c.torque2);
  if (known_means) {
    const double t1 = mean_torque_n_m(c.torque1, "torque1");
    const double t2 = mean_torque_n_m(c.torque2, "torque2");
    out["mean_torque1_n_m"] = t1;
    out["mean_torque2_n_m"] = t2;
    bool balanced = true;
    try {
      require_balanced_mean_torques(t1, t2, rb1, rb2);
    } catch (const InputError&) {
      balanced = false;
    }
    out["balanced"] = balanced;
    out["balancing_torque2_n_m"] = -t1 * rb2 / rb1;
  } else {
    out["balanced"] = py::none();
  }
  const double w1 = c.initial.w1_rad_per_s;
  const double w2 = c.initial.w2_rad_per_s;
  out["w1_rad_s"] = w1;
  out["w2_rad_s"] = w2;
  out["rolling"] = rolling(rb1 * w1, rb2 * w2);
  out["rolling_w2_rad_s"] = w1 * rb1 / rb2;
  return out;
}

}  // namespace

void define_module(py::module_& m) {
  m.doc() = "gearimpact's C++ library (the Python API is the package gearimpact)";
  m.attr("__version__") = GEARIMPACT_VERSION;

  case_error = PyErr_NewExceptionWithDoc(
      "gearimpact.CaseError",
      "A value outside its allowed range, in a case, a case file or an argument. The message "
      "names the key as written and what is allowed; .field is that key, .file the case file "
      "(empty when none).",
      PyExc_ValueError, nullptr);
  convergence_error = PyErr_NewExceptionWithDoc(
      "gearimpact.ConvergenceError",
      "A computation that did not converge (a valid input): an iteration or integral that did "
      "not reach its tolerance. A RuntimeError, never a CaseError.",
      PyExc_RuntimeError, nullptr);
  quadrature_error = PyErr_NewExceptionWithDoc(
      "gearimpact.QuadratureError",
      "A stiffness integral that did not reach its tolerance (a ConvergenceError).",
      convergence_error, nullptr);
  simulation_error = PyErr_NewExceptionWithDoc(
      "gearimpact.SimulationError",
      "A run that cannot continue: a non-finite state, or event location that stalls.",
      PyExc_RuntimeError, nullptr);
  m.attr("CaseError") = py::reinterpret_borrow<py::object>(case_error);
  m.attr("ConvergenceError") = py::reinterpret_borrow<py::object>(convergence_error);
  m.attr("QuadratureError") = py::reinterpret_borrow<py::object>(quadrature_error);
  m.attr("SimulationError") = py::reinterpret_borrow<py::object>(simulation_error);
  py::register_exception_translator(&translate_exceptions);

  py::class_<GearPair>(m, "GearPair",
                       "Two standard involute spur gears on their standard centre distance, in SI "
                       "units. GearPair() is the paper's pair (section 7).")
      .def(py::init([] { return paper_gear_pair(); }))
      .def_readwrite("teeth1", &GearPair::teeth1, "Z1, teeth of gear 1 (the pinion)")
      .def_readwrite("teeth2", &GearPair::teeth2, "Z2, teeth of gear 2")
      .def_readwrite("module_m", &GearPair::module_m, "module, m")
      .def_readwrite("pressure_angle_rad", &GearPair::pressure_angle_rad, "a0, rad")
      .def_readwrite("face_width_m", &GearPair::face_width_m, "L, m")
      .def_readwrite("addendum_coefficient", &GearPair::addendum_coefficient, "addendum / module")
      .def_readwrite("youngs_modulus_pa", &GearPair::youngs_modulus_pa, "E, Pa")
      .def_readwrite("poisson_ratio", &GearPair::poisson_ratio, "nu")
      .def_readwrite("density_kg_m3", &GearPair::density_kg_m3, "rho, kg/m^3")
      .def_readwrite("backlash_m", &GearPair::backlash_m, "B, m")
      .def(
          "validate", [](const GearPair& g) { validate(g); },
          "Raises CaseError naming the first field outside its range.")
      .def("__repr__", &gear_pair_repr);

  py::class_<StiffnessModel>(m, "StiffnessModel",
                             "How the bending and axial compliances are integrated.")
      .def(py::init<>())
      .def_property(
          "method", [](const StiffnessModel& s) { return method_name(s); },
          [](StiffnessModel& s, const std::string& name) { s = with_method(s, name, "method"); },
          "gsl, gsl-cquad, boost-gk, boost-ts (the tau-form with that rule) or xform")
      .def_property(
          "moment_sign", [](const StiffnessModel& s) { return to_string(s.moment_sign); },
          [](StiffnessModel& s, const std::string& sign) {
            s.moment_sign = parse_moment_sign(sign, "moment_sign");
          },
          "physical (M = Fb (l - x) - Fa h, as printed) or flipped")
      .def_property(
          "spall_reading", [](const StiffnessModel& s) { return to_string(s.spall_reading); },
          [](StiffnessModel& s, const std::string& reading) {
            s.spall_reading = parse_spall_reading(reading, "spall_reading");
          },
          "by-model (the default: effective-width with the rack-cut models, hertz-only with "
          "yang-lin-1987), hertz-only (Hertz over b - b_s) or effective-width (also each "
          "tooth's beam and foundation over the width the load spreads to; rack-cut models)")
      .def_readwrite("relative_tolerance", &StiffnessModel::relative_tolerance)
      .def(
          "term",
          [](const StiffnessModel& s, const std::string& id) {
            return s.terms.has(term_named(id));
          },
          "Whether the term (hertz, bending, axial, ...) enters Ke.")
      .def(
          "set_term",
          [](StiffnessModel& s, const std::string& id, const py::handle& on) {
            s.terms.set(term_named(id), boolean("on", on));
          },
          py::arg("term"), py::arg("on"), "Switches a term of (29) on (True) or off (False).")
      .def("__repr__", [](const StiffnessModel& s) {
        return "StiffnessModel(method='" + method_name(s) + "', moment_sign='" +
               to_string(s.moment_sign) +
               "', relative_tolerance=" + shortest_decimal(s.relative_tolerance) + ")";
      });

  py::class_<SimulationCase>(m, "Case",
                             "A simulation case: gear pair, torques, initial state, model options "
                             "and integrator, as a case file describes them.")
      .def_property_readonly("name", [](const SimulationCase& c) { return c.name; })
      .def_property_readonly(
          "gears", [](const SimulationCase& c) { return c.gears; }, "the GearPair (a copy)")
      .def_property_readonly(
          "stiffness_model", [](const SimulationCase& c) { return c.model.stiffness; },
          "the StiffnessModel (a copy)")
      .def_property_readonly(
          "run_keys_absent", [](const SimulationCase& c) { return c.run_keys_absent; },
          "the keys a run needs that the case leaves out (a gear pair alone: the torques' kinds "
          "and integrator.end_time), which every run names when it refuses the case; [] for a "
          "case a run can use")
      .def(
          "to_toml",
          [](const SimulationCase& c, const std::string& units) {
            if (units != "readable" && units != "si") {
              throw InputError("units", units, "\"readable\" or \"si\"");
            }
            return write_case_file(c, units == "si" ? CaseUnits::si : CaseUnits::readable);
          },
          py::arg("units") = "readable",
          "The case file's text (TOML), in readable units or all in SI; it reads back to the "
          "same case bit for bit.");

  m.def(
      "paper_case",
      [](int number, const std::string& torque_unit, double case3_frequency_rad_per_s) {
        const TorqueUnit unit = torque_unit_named(torque_unit);
        const double frequency = case3_frequency(case3_frequency_rad_per_s);
        try {
          return paper_case(number, unit, frequency);
        } catch (const InputError& e) {
          throw InputError("number", e.value(), e.allowed());
        }
      },
      py::arg("number"), py::arg("torque_unit") = "kgf-mm",
      py::arg("case3_frequency_rad_s") = 10000.0);
  m.def(
      "read_case_file", [](const std::string& path) { return read_case_file(path); },
      py::arg("path"));
  m.def("parse_case", &parse_case, py::arg("text"), py::arg("file_name"));
  m.def(
      "read_pair_or_run_file",
      [](const std::string& path) { return read_pair_or_run_file(path).simulation_case; },
      py::arg("path"));
  m.def(
      "parse_pair_or_run",
      [](const std::string& text, const std::string& file_name) {
        return parse_pair_or_run(text, file_name).simulation_case;
      },
      py::arg("text"), py::arg("file_name"));
  m.def("shortest_decimal", &shortest_decimal, py::arg("value"));
  m.def(
      "plain_speed_warning",
      [](const std::string& key, const std::string& text,
         const std::string& name) -> std::optional<std::string> {
        const Field* field = find_field(key);
        return field == nullptr ? std::nullopt : plain_speed_warning(*field, text, name);
      },
      py::arg("key"), py::arg("text"), py::arg("name"));
  m.def(
      "parse_frequency",
      [](const std::string& text, const std::string& name) {
        return parse_plain_or_quantity(text, Dimension::frequency, name);
      },
      py::arg("text"), py::arg("name"));
  m.def("schema_rows", &schema_rows);
  m.def("case_conditions", &case_conditions, py::arg("case"));
  m.def(
      "most_values",
      [](const std::string& key) {
        const Field* field = find_field(key);
        return field == nullptr ? std::size_t{0} : field->most_values;
      },
      py::arg("key"));

  m.def("simulate", &run_simulation, py::arg("case"), py::arg("keep_series"), py::arg("max_rows"),
        py::arg("sample_rate") = py::none(), py::arg("sample") = "interval-average");
  m.attr("most_series_rows") = kMostSeriesRows;
  m.def("stiffness_samples", &stiffness_samples, py::arg("pair"), py::arg("model"),
        py::arg("points"));
  m.def("stiffness_at", &stiffness_at, py::arg("pair"), py::arg("model"), py::arg("x"));
  m.def("energy_ratios", &energy_ratio_columns, py::arg("pair"), py::arg("model"),
        py::arg("points"));
  m.def("sweep_friction", &run_sweep, py::arg("cases"), py::arg("start"), py::arg("stop"),
        py::arg("step"), py::arg("threads"));

  m.def(
      "iso6336",
      [](const std::optional<SimulationCase>& c, double helix_angle_deg,
         const std::optional<std::string>& load) {
        const GearPair pair = stiffness_case(c, std::nullopt).gears;
        std::optional<double> specific_load;
        if (load) {
          try {
            specific_load = cli::specific_load_of(*load, pair);
          } catch (const InputError& e) {
            throw InputError("load", "\"" + *load + "\"", e.allowed());
          }
        }
        try {
          return cli::iso6336_text(pair, helix_angle_deg, specific_load);
        } catch (const InputError& e) {
          // The library checks the angle in rad under its own name.
          if (e.field() != "helix_angle") throw;
          throw InputError("helix_angle_deg", format_number(helix_angle_deg), e.allowed());
        }
      },
      py::arg("case"), py::arg("helix_angle_deg"), py::arg("load") = std::nullopt);
  m.def("mesh_stiffness", &mesh_stiffness_of, py::arg("case"), py::arg("model"),
        py::arg("samples"));
  m.def("sweep", &sweep_texts, py::arg("case"), py::arg("options"));
  // Data sets (docs/datasets.md): the library's dataset/ functions on a spec file.
  const auto dataset_bounds = [](double records, double samples, double bytes) {
    dataset::Bounds b;
    for (const auto& [value, name] :
         {std::pair{records, "max_records"}, std::pair{samples, "max_samples"},
          std::pair{bytes, "max_bytes"}}) {
      if (!(value >= 1.0) || !std::isfinite(value)) {
        throw InputError(name, format_number(value), "a finite number >= 1");
      }
    }
    b.max_records = records;
    b.max_samples = samples;
    b.max_bytes = bytes;
    return b;
  };
  m.def(
      "dataset_plan",
      [dataset_bounds](const std::string& spec, double records, double samples, double bytes) {
        const dataset::Plan plan =
            dataset::make_plan(dataset::read_spec(spec), dataset_bounds(records, samples, bytes));
        py::dict d;
        d["records"] = plan.records.size();
        d["conditions"] = plan.conditions.size();
        d["samples_per_record"] = plan.samples_per_record;
        d["bytes_estimate"] = static_cast<double>(plan.records.size()) * plan.bytes_per_record;
        d["spec_sha256"] = plan.spec.spec_sha256;
        d["code_version"] = dataset::code_version();
        return d;
      },
      py::arg("spec"), py::arg("max_records"), py::arg("max_samples"), py::arg("max_bytes"));
  m.def(
      "dataset_run",
      [dataset_bounds](const std::string& spec, const std::string& out, int k, int n,
                       unsigned threads, double records, double samples, double bytes) {
        const dataset::Plan plan =
            dataset::make_plan(dataset::read_spec(spec), dataset_bounds(records, samples, bytes));
        std::filesystem::create_directories(out);
        dataset::Progress p;
        {
          py::gil_scoped_release release;
          p = dataset::run_shard(plan, out, {k, n}, threads);
        }
        py::dict d;
        d["made"] = p.done;
        d["found_complete"] = p.skipped;
        d["records"] = p.total;
        d["signal_s"] = p.signal_s;
        d["cpu_s"] = p.cpu_s;
        return d;
      },
      py::arg("spec"), py::arg("out"), py::arg("k"), py::arg("n"), py::arg("threads"),
      py::arg("max_records"), py::arg("max_samples"), py::arg("max_bytes"));
  m.def(
      "dataset_merge",
      [](const std::vector<std::string>& folders, const std::string& out, bool overwrite) {
        py::gil_scoped_release release;
        dataset::merge(folders, out, overwrite);
      },
      py::arg("folders"), py::arg("out"), py::arg("overwrite"));
  m.def("train", &run_train, py::arg("case_file"), py::arg("sets"), py::arg("keep_series"),
        py::arg("sample_rate") = py::none(), py::arg("sample") = "interval-average");
  m.def("ste", &ste_texts_of, py::arg("case"), py::arg("torque"), py::arg("points"));
  m.def("modes", &modes_texts_of, py::arg("case"), py::arg("harmonics"), py::arg("max_speed"));
  m.def("planetary_modes", &planetary_modes_of, py::arg("case_file"));
  m.def("train_modes", &train_modes_of, py::arg("case_file"), py::arg("sets"));
  m.def(
      "reproduce",
      [](const std::string& out, const std::string& paper_data) {
        py::gil_scoped_release release;
        return cli::reproduce(out, paper_data).string();
      },
      py::arg("out"), py::arg("paper_data"));

  m.def(
      "contact_segment",
      [](const GearPair& g) {
        const ContactSegment s = contact_segment(checked(g));
        return py::make_tuple(s.start_m, s.end_m);
      },
      py::arg("pair"), "(X_start, X_end), m: the contact segment on the line of action from C1.");
  m.def(
      "contact_ratio", [](const GearPair& g) { return contact_ratio(checked(g)); }, py::arg("pair"),
      "(X_end - X_start) / t0");
  m.def(
      "base_pitch", [](const GearPair& g) { return base_pitch(checked(g)); }, py::arg("pair"),
      "(41) t0 = pi m cos a0, m");
  m.def(
      "line_of_action_length", [](const GearPair& g) { return line_of_action_length(checked(g)); },
      py::arg("pair"), "lp = (Rb1 + Rb2) tan a0, m: C1C2 along the line of action");
  m.def(
      "pitch_point_position", [](const GearPair& g) { return pitch_point_position(checked(g)); },
      py::arg("pair"), "X_pitch = Rb1 tan a0, m, from C1");
  m.def(
      "pitch_radius",
      [](const GearPair& g, const py::handle& gear) {
        return pitch_radius(g, gear_numbered(g, gear));
      },
      py::arg("pair"), py::arg("gear"), "r = m Z / 2 of gear 1 or 2, m");
  m.def(
      "base_radius",
      [](const GearPair& g, const py::handle& gear) {
        return base_radius(g, gear_numbered(g, gear));
      },
      py::arg("pair"), py::arg("gear"), "Rb = r cos a0 of gear 1 or 2, m");
  m.def(
      "tip_radius",
      [](const GearPair& g, const py::handle& gear) {
        return tip_radius(g, gear_numbered(g, gear));
      },
      py::arg("pair"), py::arg("gear"), "r + addendum of gear 1 or 2, m");
  m.def(
      "moment_of_inertia",
      [](const GearPair& g, const py::handle& gear) {
        return moment_of_inertia(g, gear_numbered(g, gear));
      },
      py::arg("pair"), py::arg("gear"), "J = rho pi r^4 L / 2 of gear 1 or 2 (solid disc), kg m^2");
  m.def(
      "contact_angle",
      [](const GearPair& g, const py::handle& gear, double x1_m) {
        const Gear which = gear_numbered(g, gear);
        if (!std::isfinite(x1_m)) throw InputError("x1_m", x1_m, "a finite position, m, from C1");
        return contact_angle(g, which, x1_m);
      },
      py::arg("pair"), py::arg("gear"), py::arg("x1_m"),
      "(12) phi1 or (25),(26) phi2, rad, of the contact at X1 (from C1, finite)");

  using ArrayIn = py::array_t<double, py::array::c_style | py::array::forcecast>;
  m.def(
      "amplitude_spectrum",
      [](const ArrayIn& x, double rate, const std::string& window) {
        const std::vector<double> values = vector_of(x, "signal");
        const signals::Window w = signals::parse_window(window, "window");
        const signals::Spectrum s =
            naming_keywords([&] { return signals::amplitude_spectrum(values, rate, w); });
        py::dict d;
        d["frequency"] = to_array(s.frequency);
        d["amplitude"] = to_array(s.amplitude);
        d["resolution"] = s.resolution;
        d["coherent_gain"] = s.coherent_gain;
        return d;
      },
      py::arg("signal"), py::arg("rate"), py::arg("window"));
  m.def(
      "low_pass",
      [](const ArrayIn& x, double rate, double cutoff) {
        const std::vector<double> values = vector_of(x, "signal");
        return to_array(naming_keywords([&] { return signals::low_pass(values, rate, cutoff); }));
      },
      py::arg("signal"), py::arg("rate"), py::arg("cutoff"));
  m.def(
      "anti_alias_resample",
      [](const ArrayIn& x, double rate, double rate_out, double start) {
        signals::UniformRecord r;
        r.values = vector_of(x, "signal");
        r.rate_hz = rate;
        r.start_s = start;
        const signals::UniformRecord out =
            naming_keywords([&] { return signals::anti_alias_resample(r, rate_out); });
        std::vector<double> t(out.values.size());
        for (std::size_t n = 0; n < t.size(); ++n) {
          t[n] = out.start_s + static_cast<double>(n) / out.rate_hz;
        }
        py::dict d;
        d["t"] = to_array(t);
        d["values"] = to_array(out.values);
        d["alias_free_band"] = signals::kAliasFreeFraction * rate_out;
        return d;
      },
      py::arg("signal"), py::arg("rate"), py::arg("rate_out"), py::arg("start"));
  m.def(
      "angle_from_pulses",
      [](const ArrayIn& pulses, long long per_revolution, const ArrayIn& t) {
        const std::vector<double> p = vector_of(pulses, "tacho");
        const std::vector<double> times = vector_of(t, "time");
        const std::size_t n = count_of(per_revolution, "pulses_per_revolution");
        return to_array(
            naming_keywords([&] { return signals::angle_from_pulses(p, n, times, "tacho"); }));
      },
      py::arg("tacho"), py::arg("pulses_per_revolution"), py::arg("time"));
  m.def(
      "tacho_jitter",
      [](const ArrayIn& pulses, double sigma, long long seed) {
        const std::vector<double> p = vector_of(pulses, "tacho");
        if (seed < 0) throw InputError("seed", std::to_string(seed), "an integer >= 0");
        return to_array(naming_keywords(
            [&] { return signals::tacho_jitter(p, sigma, static_cast<std::uint64_t>(seed)); }));
      },
      py::arg("tacho"), py::arg("jitter"), py::arg("seed"));
  m.def(
      "order_analysis",
      [](const ArrayIn& angle, const ArrayIn& x, long long per_revolution, long long teeth,
         long long shaft_orders, long long sidebands, const std::string& window,
         long long max_order, long long nb4_half_width) {
        const std::vector<double> a = vector_of(angle, "angle");
        const std::vector<double> values = vector_of(x, "signal");
        const signals::Window w = signals::parse_window(window, "window");
        std::optional<signals::OrderSets> sets;
        if (teeth != 0) {
          sets =
              signals::OrderSets{count_of(teeth, "teeth"), count_of(shaft_orders, "shaft_orders"),
                                 count_of(sidebands, "sidebands")};
          sets->nb4_half_width = count_of(nb4_half_width, "nb4_half_width");
        }
        // 0: from the record's band (tsa.hpp).
        const std::size_t p = count_of(per_revolution, "samples_per_revolution");
        std::optional<std::size_t> top;
        if (max_order >= 0) top = count_of(max_order, "max_order");
        const signals::OrderAnalysis r = naming_keywords(
            [&] { return signals::analyse_orders(a, values, p, w, sets, "angle", "signal", top); });
        py::dict d;
        d["grid"] = r.grid;
        d["revolutions"] = r.revolutions;
        d["start_angle"] = r.start_angle;
        d["order"] = to_array(r.orders.frequency);
        d["amplitude"] = to_array(r.orders.amplitude);
        d["tsa"] = to_array(r.tsa);
        d["samples_per_revolution"] = r.samples_per_revolution;
        d["max_order"] = r.max_order;
        d["indicator_grid"] = r.indicator_grid;
        if (r.parts) {
          d["regular"] = to_array(r.parts->regular);
          d["residual"] = to_array(r.parts->residual);
          d["difference"] = to_array(r.parts->difference);
          d["mesh_band"] = to_array(r.parts->mesh_band);
          d["mesh_band_envelope"] = to_array(r.parts->mesh_band_envelope);
          d["tsa_order_amplitude"] = to_array(r.parts->order_amplitude);
          d["nb4_harmonic"] = r.indicator_parts->nb4_harmonic;
          d["nb4_half_width"] = r.indicator_parts->nb4_half_width;
          // On the indicators' grid: independent of samples_per_revolution.
          d["indicators"] = indicators_dict(
              signals::gear_indicators(r.indicator_parts->tsa, *r.indicator_parts, *sets));
        }
        return d;
      },
      py::arg("angle"), py::arg("signal"), py::arg("samples_per_revolution"), py::arg("teeth"),
      py::arg("shaft_orders"), py::arg("sidebands"), py::arg("window"), py::arg("max_order"),
      py::arg("nb4_half_width"));
  m.def(
      "condition_indicators",
      [](const ArrayIn& x) {
        return indicators_dict(signals::record_indicators(vector_of(x, "record")));
      },
      py::arg("record"));
}

}  // namespace gearimpact::python

PYBIND11_MODULE(_core, m) {
  gearimpact::python::define_module(m);
}
