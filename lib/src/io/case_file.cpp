#include "gearimpact/io/case_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <toml.hpp>
#include <utility>
#include <vector>

#include "gearimpact/dynamics/step_bound.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/io/units.hpp"

namespace gearimpact {

CaseFileError::CaseFileError(std::string file, std::string field, const std::string& message)
    : std::invalid_argument(message), file_(std::move(file)), field_(std::move(field)) {}

namespace {

// Case files are a page of text; the cap keeps a wrong path (a log, a core
// file) from being read whole.
constexpr std::uintmax_t kLargestFileBytes = 1u << 20;
// A run of more steps than this is a mistake (days of computing), not a case.
constexpr double kMostSteps = 1e9;
// Nesting of arrays and inline tables deeper than this is never a case file;
// the TOML parser recurses on it, so it is refused before parsing.
constexpr int kDeepestNesting = 32;

// One of the names a key allows, and what it means.
template <typename T>
struct Choice {
  std::string_view name;
  T value;
};

constexpr std::array kDampingForms{
    Choice<DampingForm>{"herbert-mcwhannell", DampingForm::herbert_mcwhannell},
    Choice<DampingForm>{"hunt-crossley", DampingForm::hunt_crossley},
    Choice<DampingForm>{"lee-wang", DampingForm::lee_wang}};
constexpr std::array kDampingStiffnesses{
    Choice<DampingStiffness>{"current-pair", DampingStiffness::current_pair},
    Choice<DampingStiffness>{"pitch-pair-at-impact", DampingStiffness::pitch_pair_at_impact},
    Choice<DampingStiffness>{"hertz", DampingStiffness::hertz}};
constexpr std::array kCoastPhases{
    Choice<CoastPhase>{"half-base-pitch", CoastPhase::half_base_pitch},
    Choice<CoastPhase>{"in-phase", CoastPhase::in_phase}};
constexpr std::array kOnOff{Choice<bool>{"on", true}, Choice<bool>{"off", false}};
constexpr std::array kMomentSigns{Choice<AxialMomentSign>{"physical", AxialMomentSign::physical},
                                  Choice<AxialMomentSign>{"flipped", AxialMomentSign::flipped}};
// stiffness_method names the tau-form with a rule, or the x-form route;
// xform_rule names the rule of the x-form.
enum class MethodName { gsl, gsl_cquad, boost_gk, boost_ts, xform };
constexpr std::array kStiffnessMethods{Choice<MethodName>{"gsl", MethodName::gsl},
                                       Choice<MethodName>{"gsl-cquad", MethodName::gsl_cquad},
                                       Choice<MethodName>{"boost-gk", MethodName::boost_gk},
                                       Choice<MethodName>{"boost-ts", MethodName::boost_ts},
                                       Choice<MethodName>{"xform", MethodName::xform}};
constexpr std::array kStiffnessModels{
    Choice<StiffnessModelKind>{"yang-lin-1987", StiffnessModelKind::yang_lin_1987},
    Choice<StiffnessModelKind>{"potential-energy", StiffnessModelKind::potential_energy},
    Choice<StiffnessModelKind>{"ross-compatible", StiffnessModelKind::ross_compatible}};
constexpr std::array kXformRules{
    Choice<QuadratureRule>{"gsl", QuadratureRule::gsl_qag},
    Choice<QuadratureRule>{"gsl-cquad", QuadratureRule::gsl_cquad},
    Choice<QuadratureRule>{"boost-gk", QuadratureRule::boost_gauss_kronrod},
    Choice<QuadratureRule>{"boost-ts", QuadratureRule::boost_tanh_sinh}};

MethodName method_of(const StiffnessModel& m) {
  if (m.route == StiffnessRoute::x_form) return MethodName::xform;
  return static_cast<MethodName>(static_cast<int>(m.rule));
}
constexpr std::array kTorqueKinds{Choice<Torque::Kind>{"constant", Torque::Kind::constant},
                                  Choice<Torque::Kind>{"sinusoidal", Torque::Kind::sinusoidal}};
constexpr std::array kIntegratorKinds{Choice<IntegratorKind>{"rk4", IntegratorKind::rk4},
                                      Choice<IntegratorKind>{"adaptive", IntegratorKind::adaptive}};

template <typename T, std::size_t N>
std::string names_of(const std::array<Choice<T>, N>& choices) {
  std::string list;
  for (const auto& choice : choices) {
    if (!list.empty()) list += ", ";
    list += "\"" + std::string(choice.name) + "\"";
  }
  return list;
}

template <typename T, std::size_t N>
std::string_view name_of(const std::array<Choice<T>, N>& choices, T value) {
  for (const auto& choice : choices) {
    if (choice.value == value) return choice.name;
  }
  throw std::logic_error("a model option without a case-file name");
}

std::string type_name(const toml::value& value) {
  switch (value.type()) {
    case toml::value_t::boolean:
      return "a boolean";
    case toml::value_t::integer:
      return "an integer";
    case toml::value_t::floating:
      return "a float";
    case toml::value_t::string:
      return "a string";
    case toml::value_t::array:
      return "an array";
    case toml::value_t::table:
      return "a table";
    case toml::value_t::empty:
      return "nothing";
    default:
      return "a date or time";
  }
}

// The value as the file wrote it, for messages.
std::string written(const toml::value& value) {
  switch (value.type()) {
    case toml::value_t::string:
      return "\"" + value.as_string().str + "\"";
    case toml::value_t::integer:
      return std::to_string(value.as_integer());
    case toml::value_t::floating:
      return shortest_decimal(value.as_floating());
    case toml::value_t::boolean:
      return value.as_boolean() ? "true" : "false";
    default:
      return "(" + type_name(value) + ")";
  }
}

// The stem of a path without touching the file system.
std::string stem_of(std::string_view file_name) {
  const std::size_t slash = file_name.find_last_of('/');
  if (slash != std::string_view::npos) file_name.remove_prefix(slash + 1);
  const std::size_t dot = file_name.rfind('.');
  if (dot != std::string_view::npos && dot > 0) file_name = file_name.substr(0, dot);
  return std::string(file_name);
}

bool is_name_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

// The deepest nesting of [ and { outside strings and comments; table headers
// ([gears], [[x]]) count too, which only overestimates.
int nesting_depth(std::string_view text) {
  int depth = 0;
  int deepest = 0;
  char quote = 0;
  bool comment = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (comment) {
      if (c == '\n') comment = false;
    } else if (quote != 0) {
      if (c == '\\' && quote == '"') {
        ++i;
      } else if (c == quote) {
        quote = 0;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '#') {
      comment = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      depth = std::max(0, depth - 1);
    }
  }
  return deepest;
}

// The offset of the first byte that is not part of well-formed UTF-8 (RFC
// 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or npos.
// TOML documents are UTF-8, and toml11 3.7.1 (Debian 12) reads out of bounds
// when it reports invalid UTF-8 inside a literal string: its error path resets
// a location on one buffer to an iterator into another (found here by
// fuzz/fuzz_case_file; upstream ToruNiina/toml11 issue #199, fixed by pull
// request #208 after 3.7.1). Such text is refused before it reaches the parser.
std::size_t first_invalid_utf8(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t length = 0;
    unsigned char low = 0x80;
    unsigned char high = 0xBF;
    if (lead < 0x80) {
      length = 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) low = 0xA0;   // overlong
      if (lead == 0xED) high = 0x9F;  // surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) low = 0x90;   // overlong
      if (lead == 0xF4) high = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const unsigned char next = byte(i + k);
      if (next < (k == 1 ? low : 0x80) || next > (k == 1 ? high : 0xBF)) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  // "file:line: message", the line when the value came from the text.
  [[noreturn]] void fail(const std::string& field, const toml::value* at,
                         const std::string& message) const {
    std::string where = file_;
    if (at != nullptr) {
      const toml::source_location location = at->location();
      if (!location.line_str().empty()) where += ":" + std::to_string(location.line());
    }
    throw CaseFileError(file_, field, where + ": " + message);
  }

  [[noreturn]] void out_of_range(const std::string& field, const toml::value* at,
                                 const std::string& value, const std::string& allowed) const {
    fail(field, at, field + " = " + value + " is outside the allowed range: " + allowed);
  }

 private:
  std::string file_;
};

// One [section] of the file: its keys are checked against the allowed ones
// when it is opened, and every read names the field as section.key.
class Section {
 public:
  Section(const Reader& reader, const toml::value& root, std::string name,
          std::initializer_list<std::string_view> keys, bool required)
      : reader_(reader), name_(std::move(name)) {
    const auto& top = root.as_table();
    const auto found = top.find(name_);
    if (found == top.end()) {
      if (required) {
        reader_.fail(name_, nullptr,
                     "section [" + name_ + "] is missing (required; keys " + list(keys) + ")");
      }
      return;
    }
    table_ = &found->second;
    if (!table_->is_table()) {
      reader_.fail(name_, table_,
                   name_ + " = " + written(*table_) + " is " + type_name(*table_) +
                       ", not a section: write [" + name_ + "] with keys " + list(keys));
    }
    std::vector<std::string> unknown;
    for (const auto& [key, value] : table_->as_table()) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) unknown.push_back(key);
    }
    if (!unknown.empty()) {
      std::sort(unknown.begin(), unknown.end());
      const toml::value& first = table_->as_table().at(unknown.front());
      std::string names;
      for (const std::string& key : unknown) names += (names.empty() ? "" : ", ") + field(key);
      reader_.fail(field(unknown.front()), &first,
                   "unknown key " + names + "; the keys of [" + name_ + "] are " + list(keys));
    }
  }

  std::string field(std::string_view key) const { return name_ + "." + std::string(key); }

  const toml::value* find(std::string_view key) const {
    if (table_ == nullptr) return nullptr;
    const auto& table = table_->as_table();
    const auto found = table.find(std::string(key));
    return found == table.end() ? nullptr : &found->second;
  }

  // A quantity with a unit, "10 mm"; `fallback` when absent, else required.
  double quantity(std::string_view key, Dimension dimension,
                  std::optional<double> fallback = std::nullopt) const {
    const toml::value* value = find(key);
    const std::string expected = std::string(describe(dimension)) +
                                 " as a string with one of the units " + allowed_units(dimension);
    if (value == nullptr) {
      if (fallback) return *fallback;
      missing(key, expected);
    }
    if (!value->is_string()) {
      const std::string why = value->is_integer() || value->is_floating()
                                  ? "a number without a unit; expected "
                                  : type_name(*value) + "; expected ";
      reader_.out_of_range(field(key), value, written(*value), why + expected);
    }
    try {
      return parse_quantity(value->as_string().str, dimension, field(key));
    } catch (const InputError& e) {
      reader_.fail(field(key), value, e.what());
    }
  }

  // A plain number (no unit), integer or float, finite, within [lower, upper]
  // or (lower, upper) as `allowed` says.
  double number(std::string_view key, std::optional<double> fallback, bool (*in_range)(double),
                const std::string& allowed) const {
    const toml::value* value = find(key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      missing(key, "a number in " + allowed);
    }
    double x = 0.0;
    if (value->is_floating()) {
      x = value->as_floating();
    } else if (value->is_integer()) {
      x = static_cast<double>(value->as_integer());
    } else {
      reader_.out_of_range(field(key), value, written(*value),
                           type_name(*value) + "; expected a plain number (no unit) in " + allowed);
    }
    if (!std::isfinite(x) || !in_range(x)) {
      reader_.out_of_range(field(key), value, written(*value), allowed);
    }
    return x;
  }

  int integer(std::string_view key, std::optional<int> fallback, int lower, int upper) const {
    const toml::value* value = find(key);
    const std::string allowed =
        "an integer in [" + std::to_string(lower) + ", " + std::to_string(upper) + "]";
    if (value == nullptr) {
      if (fallback) return *fallback;
      missing(key, allowed);
    }
    if (!value->is_integer()) {
      reader_.out_of_range(field(key), value, written(*value),
                           type_name(*value) + "; expected " + allowed);
    }
    const std::int64_t x = value->as_integer();
    if (x < lower || x > upper) reader_.out_of_range(field(key), value, written(*value), allowed);
    return static_cast<int>(x);
  }

  template <typename T, std::size_t N>
  T choice(std::string_view key, const std::array<Choice<T>, N>& choices,
           std::optional<T> fallback = std::nullopt) const {
    const toml::value* value = find(key);
    if (value == nullptr) {
      if (fallback) return *fallback;
      missing(key, "one of " + names_of(choices));
    }
    if (value->is_string()) {
      for (const auto& c : choices) {
        if (value->as_string().str == c.name) return c.value;
      }
    }
    reader_.out_of_range(field(key), value, written(*value), "one of " + names_of(choices));
  }

  // Refuses a key the rest of the section makes meaningless.
  void forbid(std::string_view key, const std::string& because) const {
    if (const toml::value* value = find(key)) {
      reader_.fail(field(key), value,
                   field(key) + " = " + written(*value) + " is not used " + because);
    }
  }

 private:
  [[noreturn]] void missing(std::string_view key, const std::string& expected) const {
    reader_.fail(field(key), table_, field(key) + " is missing (required: " + expected + ")");
  }

  static std::string list(std::initializer_list<std::string_view> keys) {
    std::string names;
    for (std::string_view key : keys) names += (names.empty() ? "" : ", ") + std::string(key);
    return names;
  }

  const Reader& reader_;
  std::string name_;
  const toml::value* table_ = nullptr;
};

bool any_value(double) {
  return true;
}
bool non_negative(double x) {
  return x >= 0.0;
}
bool positive(double x) {
  return x > 0.0;
}
// Quadrature and adaptive-step tolerances a double can meet and that still
// mean something: 1e-14 is a few ulps of the compliances, 1e-2 a rough run.
bool tolerance_range(double x) {
  return x >= 1e-14 && x <= 1e-2;
}

Torque read_torque(const Reader& reader, const toml::value& root, const std::string& name) {
  const Section section(reader, root, name,
                        {"kind", "value", "amplitude", "angular_frequency", "phase"}, true);
  Torque torque;
  torque.kind = section.choice("kind", kTorqueKinds);
  if (torque.kind == Torque::Kind::constant) {
    const std::string because = "by kind = \"constant\" (T = value)";
    section.forbid("amplitude", because);
    section.forbid("angular_frequency", because);
    section.forbid("phase", because);
    torque.constant_n_m = section.quantity("value", Dimension::torque);
  } else {
    section.forbid("value",
                   "by kind = \"sinusoidal\" (T = amplitude sin(angular_frequency t + phase))");
    torque.amplitude_n_m = section.quantity("amplitude", Dimension::torque);
    torque.angular_frequency_rad_s =
        section.quantity("angular_frequency", Dimension::angular_frequency);
    if (torque.angular_frequency_rad_s < 0.0) {
      reader.out_of_range(section.field("angular_frequency"), section.find("angular_frequency"),
                          written(*section.find("angular_frequency")), ">= 0 rad/s");
    }
    torque.phase_rad = section.quantity("phase", Dimension::angle, 0.0);
  }
  return torque;
}

GearPair read_gears(const Reader& reader, const toml::value& root) {
  const Section section(
      reader, root, "gears",
      {"teeth1", "teeth2", "module", "pressure_angle", "face_width", "addendum_coefficient",
       "youngs_modulus", "poisson_ratio", "density", "backlash", "dedendum_coefficient",
       "profile_shift1", "profile_shift2", "rack_tip_radius_coefficient", "bore_diameter1",
       "bore_diameter2", "youngs_modulus2", "poisson_ratio2"},
      true);
  // The range checks of the pair are validate(GearPair)'s; here only types,
  // units and finiteness, and counts small enough to be gears.
  constexpr int kMostTeeth = 100000;
  GearPair gears;
  gears.teeth1 = section.integer("teeth1", std::nullopt, 4, kMostTeeth);
  gears.teeth2 = section.integer("teeth2", std::nullopt, 4, kMostTeeth);
  gears.module_m = section.quantity("module", Dimension::length);
  gears.pressure_angle_rad = section.quantity("pressure_angle", Dimension::angle);
  gears.face_width_m = section.quantity("face_width", Dimension::length);
  gears.addendum_coefficient =
      section.number("addendum_coefficient", 1.0, any_value, "(0, inf): addendum / module");
  gears.youngs_modulus_pa = section.quantity("youngs_modulus", Dimension::pressure);
  gears.poisson_ratio =
      section.number("poisson_ratio", std::nullopt, any_value, "(-1, 0.5), both ends excluded");
  gears.density_kg_m3 = section.quantity("density", Dimension::density);
  gears.backlash_m = section.quantity("backlash", Dimension::length);
  const GearPair defaults;
  gears.dedendum_coefficient = section.number("dedendum_coefficient", defaults.dedendum_coefficient,
                                              any_value, "(addendum, inf): dedendum / module");
  gears.profile_shift1 =
      section.number("profile_shift1", defaults.profile_shift1, any_value, "a finite number");
  gears.profile_shift2 =
      section.number("profile_shift2", defaults.profile_shift2, any_value, "a finite number");
  // Optional keys: absent means derived (rack tip radius, gear 2's material)
  // or not needed (the bores, for the foundation term only).
  if (section.find("rack_tip_radius_coefficient") != nullptr) {
    gears.rack_tip_radius_coefficient = section.number("rack_tip_radius_coefficient", std::nullopt,
                                                       any_value, "(0, inf): rho / module");
  }
  if (section.find("bore_diameter1") != nullptr) {
    gears.bore_diameter1_m = section.quantity("bore_diameter1", Dimension::length);
  }
  if (section.find("bore_diameter2") != nullptr) {
    gears.bore_diameter2_m = section.quantity("bore_diameter2", Dimension::length);
  }
  if (section.find("youngs_modulus2") != nullptr) {
    gears.youngs_modulus2_pa = section.quantity("youngs_modulus2", Dimension::pressure);
  }
  if (section.find("poisson_ratio2") != nullptr) {
    gears.poisson_ratio2 =
        section.number("poisson_ratio2", std::nullopt, any_value, "(-1, 0.5), both ends excluded");
  }
  try {
    validate(gears);
  } catch (const InputError& e) {
    // validate names the gear-pair fields as the file's keys do.
    const toml::value* at = section.find(e.field());
    std::string message = "gears." + std::string(e.what());
    if (at != nullptr && at->is_string()) message += " (written " + written(*at) + ")";
    reader.fail("gears." + e.field(), at, message);
  }
  return gears;
}

SimulationCase read_case(const Reader& reader, const toml::value& root,
                         std::string_view file_name) {
  SimulationCase result;
  {
    const auto& top = root.as_table();
    std::vector<std::string> unknown;
    for (const auto& [key, value] : top) {
      if (key != "name" && key != "gears" && key != "torque1" && key != "torque2" &&
          key != "initial" && key != "model" && key != "integrator") {
        unknown.push_back(key);
      }
    }
    if (!unknown.empty()) {
      std::sort(unknown.begin(), unknown.end());
      reader.fail(unknown.front(), &top.at(unknown.front()),
                  "unknown key or section \"" + unknown.front() +
                      "\"; a case file has name and the sections [gears], [torque1], "
                      "[torque2], [initial], [model], [integrator]");
    }
    const auto name = top.find("name");
    result.name = stem_of(file_name);
    if (name != top.end()) {
      if (!name->second.is_string()) {
        reader.out_of_range("name", &name->second, written(name->second),
                            "a string of letters, digits, '_', '-', '.'");
      }
      result.name = name->second.as_string().str;
    }
    constexpr std::size_t kLongestName = 100;
    if (result.name.empty() || result.name.size() > kLongestName ||
        !std::all_of(result.name.begin(), result.name.end(), is_name_character)) {
      reader.out_of_range("name", name == top.end() ? nullptr : &name->second,
                          "\"" + result.name + "\"",
                          "1 to 100 letters, digits, '_', '-', '.' (it names output files)");
    }
  }

  result.gears = read_gears(reader, root);
  result.torque1 = read_torque(reader, root, "torque1");
  result.torque2 = read_torque(reader, root, "torque2");

  {
    const Section section(reader, root, "initial", {"theta1", "theta2", "w1", "w2"}, false);
    result.initial.theta1_rad = section.quantity("theta1", Dimension::angle, 0.0);
    result.initial.theta2_rad = section.quantity("theta2", Dimension::angle, 0.0);
    result.initial.w1_rad_s = section.quantity("w1", Dimension::angular_velocity, 0.0);
    result.initial.w2_rad_s = section.quantity("w2", Dimension::angular_velocity, 0.0);
  }

  {
    const Section section(
        reader, root, "model",
        {"friction_coefficient", "damping_form", "damping_stiffness", "restitution_coefficient",
         "restitution_exponent", "restitution_speed_unit", "coast_phase", "moment_sign",
         "stiffness_method", "xform_rule", "stiffness_tolerance", "hertz_term", "bending_term",
         "axial_term", "shear_term", "foundation_term", "stiffness_model"},
        false);
    const ModelOptions defaults;
    ModelOptions& model = result.model;
    model.friction_coefficient = section.number(
        "friction_coefficient", defaults.friction_coefficient, non_negative, "[0, inf)");
    model.damping_form =
        section.choice("damping_form", kDampingForms, std::optional(defaults.damping_form));
    model.damping_stiffness = section.choice("damping_stiffness", kDampingStiffnesses,
                                             std::optional(defaults.damping_stiffness));
    model.restitution.coefficient =
        section.number("restitution_coefficient", defaults.restitution.coefficient, non_negative,
                       "[0, inf): c of (33) e = 1 - c (Vi/unit)^p");
    model.restitution.exponent = section.number(
        "restitution_exponent", defaults.restitution.exponent, positive, "(0, inf): p of (33)");
    model.restitution.speed_unit_m_s = section.quantity("restitution_speed_unit", Dimension::speed,
                                                        defaults.restitution.speed_unit_m_s);
    if (model.restitution.speed_unit_m_s <= 0.0) {
      reader.out_of_range(
          section.field("restitution_speed_unit"), section.find("restitution_speed_unit"),
          written(*section.find("restitution_speed_unit")), "a speed > 0, e.g. \"1 mm/s\"");
    }
    model.coast_phase =
        section.choice("coast_phase", kCoastPhases, std::optional(defaults.coast_phase));
    model.stiffness.moment_sign =
        section.choice("moment_sign", kMomentSigns, std::optional(defaults.stiffness.moment_sign));
    model.stiffness.kind =
        section.choice("stiffness_model", kStiffnessModels, std::optional(defaults.stiffness.kind));
    const MethodName method = section.choice("stiffness_method", kStiffnessMethods,
                                             std::optional(method_of(defaults.stiffness)));
    const QuadratureRule xform_rule =
        section.choice("xform_rule", kXformRules, std::optional(defaults.stiffness.rule));
    model.stiffness.route =
        method == MethodName::xform ? StiffnessRoute::x_form : StiffnessRoute::tau_form;
    model.stiffness.rule = method == MethodName::xform
                               ? xform_rule
                               : static_cast<QuadratureRule>(static_cast<int>(method));
    for (const TermInfo& t : kTerms) {
      const std::string key = std::string(t.id) + "_term";
      model.stiffness.terms.set(
          t.term, section.choice(key, kOnOff, std::optional(defaults.stiffness.terms.has(t.term))));
    }
    bool any_term = false;
    for (const TermInfo& t : kTerms) {
      any_term =
          any_term || (provides(model.stiffness.kind, t.term) && model.stiffness.terms.has(t.term));
    }
    if (!any_term) {
      reader.fail("model.hertz_term", section.find("hertz_term"),
                  "model.hertz_term, bending_term and axial_term" +
                      std::string(model.stiffness.kind == StiffnessModelKind::yang_lin_1987
                                      ? ""
                                      : ", shear_term and foundation_term") +
                      " are all \"off\": at least one term of (29) must stay \"on\"");
    }
    model.stiffness.relative_tolerance =
        section.number("stiffness_tolerance", defaults.stiffness.relative_tolerance,
                       tolerance_range, "[1e-14, 1e-2]");
  }

  {
    const Section section(reader, root, "integrator",
                          {"kind", "step", "end_time", "relative_tolerance", "output_every"}, true);
    const IntegratorSettings defaults;
    IntegratorSettings& integrator = result.integrator;
    integrator.kind = section.choice("kind", kIntegratorKinds, std::optional(defaults.kind));
    integrator.step_s = section.quantity("step", Dimension::time, defaults.step_s);
    if (integrator.step_s <= 0.0) {
      reader.out_of_range(section.field("step"), section.find("step"),
                          written(*section.find("step")), "a time > 0 s");
    }
    // The dynamics refuses a step that cannot resolve the contact; the file
    // says so here, at the step's line, before any work starts.
    double largest_step_s = 0.0;
    try {
      largest_step_s = largest_resolving_step_s(result);
    } catch (const QuadratureError& e) {
      reader.fail("model.stiffness_tolerance", nullptr,
                  "model.stiffness_tolerance = " +
                      shortest_decimal(result.model.stiffness.relative_tolerance) +
                      " with stiffness_method = " + method_name(result.model.stiffness) +
                      ": the mesh stiffness cannot be computed to it (" + e.what() +
                      "); 1e-12 is within reach of every method");
    }
    if (integrator.step_s > largest_step_s) {
      const toml::value* at = section.find("step");
      reader.out_of_range(
          section.field("step"), at,
          at != nullptr ? written(*at) : shortest_decimal(integrator.step_s) + " s (the default)",
          "(0, " + shortest_decimal(largest_step_s) +
              "] s: a larger step takes fewer than 20 steps per period of the "
              "stiffest contact and does not resolve it");
    }
    integrator.end_time_s = section.quantity("end_time", Dimension::time);
    if (integrator.end_time_s <= 0.0) {
      reader.out_of_range(section.field("end_time"), section.find("end_time"),
                          written(*section.find("end_time")), "a time > 0 s");
    }
    if (integrator.end_time_s / integrator.step_s > kMostSteps) {
      reader.out_of_range(
          section.field("end_time"), section.find("end_time"), written(*section.find("end_time")),
          "at most 1e9 steps of integrator.step = " + shortest_decimal(integrator.step_s) +
              " s, i.e. end_time <= " + shortest_decimal(kMostSteps * integrator.step_s) + " s");
    }
    integrator.adaptive_relative_tolerance =
        section.number("relative_tolerance", defaults.adaptive_relative_tolerance, tolerance_range,
                       "[1e-14, 1e-2]");
    integrator.output_every =
        section.integer("output_every", defaults.output_every, 1, std::numeric_limits<int>::max());
  }
  return result;
}

}  // namespace

SimulationCase parse_case(std::string_view toml_text, std::string_view file_name) {
  const Reader reader{std::string(file_name)};
  if (nesting_depth(toml_text) > kDeepestNesting) {
    reader.fail("", nullptr,
                "not a case file: arrays or tables nested deeper than " +
                    std::to_string(kDeepestNesting) + " levels");
  }
  if (const std::size_t bad = first_invalid_utf8(toml_text); bad != std::string_view::npos) {
    const auto line =
        std::count(toml_text.begin(), toml_text.begin() + static_cast<long>(bad), '\n');
    reader.fail("", nullptr,
                "not valid TOML: byte " + std::to_string(bad + 1) + " (line " +
                    std::to_string(line + 1) + ") is not part of well-formed UTF-8");
  }
  toml::value root;
  try {
    std::istringstream stream{std::string(toml_text)};
    root = toml::parse(stream, std::string(file_name));
  } catch (const std::exception& e) {
    reader.fail("", nullptr, std::string("not valid TOML: ") + e.what());
  }
  return read_case(reader, root, file_name);
}

SimulationCase read_case_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw CaseFileError(file, "", file + ": cannot be read: " + error.message());
  if (size > kLargestFileBytes) {
    throw CaseFileError(
        file, "",
        file + ": is " + std::to_string(size) + " bytes; a case file is at most 1 MiB of TOML");
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw CaseFileError(file, "", file + ": cannot be opened");
  const std::string text{std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
  return parse_case(text, file);
}

namespace {

// Writes one key = value line.
class Writer {
 public:
  explicit Writer(CaseUnits units) : units_(units) {}

  void section(std::string_view name) {
    if (!text_.empty()) text_ += "\n";
    text_ += "[" + std::string(name) + "]\n";
  }
  void line(std::string_view key, const std::string& value) {
    text_ += std::string(key) + " = " + value + "\n";
  }
  void quantity(std::string_view key, double si_value, Dimension dimension,
                std::string_view readable_unit) {
    const std::string_view unit =
        units_ == CaseUnits::si ? units_of(dimension).front().symbol : readable_unit;
    line(key, "\"" + format_quantity(si_value, dimension, unit) + "\"");
  }
  void number(std::string_view key, double value) {
    // TOML needs a point or an exponent to read a float back as one.
    std::string text = shortest_decimal(value);
    if (text.find_first_of(".e") == std::string::npos) text += ".0";
    line(key, text);
  }
  void integer(std::string_view key, int value) { line(key, std::to_string(value)); }
  void word(std::string_view key, std::string_view value) {
    line(key, "\"" + std::string(value) + "\"");
  }
  void raw(const std::string& text) { text_ += text; }

  const std::string& text() const { return text_; }

 private:
  CaseUnits units_;
  std::string text_;
};

void write_torque(Writer& out, std::string_view name, const Torque& torque) {
  out.section(name);
  switch (torque.kind) {
    case Torque::Kind::constant:
      out.word("kind", "constant");
      out.quantity("value", torque.constant_n_m, Dimension::torque, "N*mm");
      return;
    case Torque::Kind::sinusoidal:
      out.word("kind", "sinusoidal");
      out.quantity("amplitude", torque.amplitude_n_m, Dimension::torque, "N*mm");
      out.quantity("angular_frequency", torque.angular_frequency_rad_s,
                   Dimension::angular_frequency, "rad/s");
      out.quantity("phase", torque.phase_rad, Dimension::angle, "deg");
      return;
    case Torque::Kind::user:
      break;
  }
  throw InputError(std::string(name) + ".kind", "user",
                   "constant or sinusoidal: a torque given as a function has no case-file form");
}

}  // namespace

std::string write_case_file(const SimulationCase& c, CaseUnits units) {
  Writer out(units);
  out.raw("# gearimpact case file (see docs/case-files.md)\n");
  out.word("name", c.name);
  out.section("gears");
  out.integer("teeth1", c.gears.teeth1);
  out.integer("teeth2", c.gears.teeth2);
  out.quantity("module", c.gears.module_m, Dimension::length, "mm");
  out.quantity("pressure_angle", c.gears.pressure_angle_rad, Dimension::angle, "deg");
  out.quantity("face_width", c.gears.face_width_m, Dimension::length, "mm");
  out.number("addendum_coefficient", c.gears.addendum_coefficient);
  out.quantity("youngs_modulus", c.gears.youngs_modulus_pa, Dimension::pressure, "GPa");
  out.number("poisson_ratio", c.gears.poisson_ratio);
  out.quantity("density", c.gears.density_kg_m3, Dimension::density, "kg/m^3");
  out.quantity("backlash", c.gears.backlash_m, Dimension::length, "mm");
  out.number("dedendum_coefficient", c.gears.dedendum_coefficient);
  out.number("profile_shift1", c.gears.profile_shift1);
  out.number("profile_shift2", c.gears.profile_shift2);
  if (c.gears.rack_tip_radius_coefficient) {
    out.number("rack_tip_radius_coefficient", *c.gears.rack_tip_radius_coefficient);
  }
  if (c.gears.bore_diameter1_m) {
    out.quantity("bore_diameter1", *c.gears.bore_diameter1_m, Dimension::length, "mm");
  }
  if (c.gears.bore_diameter2_m) {
    out.quantity("bore_diameter2", *c.gears.bore_diameter2_m, Dimension::length, "mm");
  }
  if (c.gears.youngs_modulus2_pa) {
    out.quantity("youngs_modulus2", *c.gears.youngs_modulus2_pa, Dimension::pressure, "GPa");
  }
  if (c.gears.poisson_ratio2) out.number("poisson_ratio2", *c.gears.poisson_ratio2);

  write_torque(out, "torque1", c.torque1);
  write_torque(out, "torque2", c.torque2);

  out.section("initial");
  out.quantity("theta1", c.initial.theta1_rad, Dimension::angle, "deg");
  out.quantity("theta2", c.initial.theta2_rad, Dimension::angle, "deg");
  out.quantity("w1", c.initial.w1_rad_s, Dimension::angular_velocity, "rad/s");
  out.quantity("w2", c.initial.w2_rad_s, Dimension::angular_velocity, "rad/s");

  const ModelOptions& m = c.model;
  out.section("model");
  out.number("friction_coefficient", m.friction_coefficient);
  out.word("damping_form", name_of(kDampingForms, m.damping_form));
  out.word("damping_stiffness", name_of(kDampingStiffnesses, m.damping_stiffness));
  out.number("restitution_coefficient", m.restitution.coefficient);
  out.number("restitution_exponent", m.restitution.exponent);
  out.quantity("restitution_speed_unit", m.restitution.speed_unit_m_s, Dimension::speed, "mm/s");
  out.word("coast_phase", name_of(kCoastPhases, m.coast_phase));
  out.word("moment_sign", name_of(kMomentSigns, m.stiffness.moment_sign));
  out.word("stiffness_model", to_string(m.stiffness.kind));
  out.word("stiffness_method", name_of(kStiffnessMethods, method_of(m.stiffness)));
  out.word("xform_rule", name_of(kXformRules, m.stiffness.route == StiffnessRoute::x_form
                                                  ? m.stiffness.rule
                                                  : QuadratureRule::gsl_qag));
  out.number("stiffness_tolerance", m.stiffness.relative_tolerance);
  for (const TermInfo& t : kTerms) {
    out.word(std::string(t.id) + "_term", name_of(kOnOff, m.stiffness.terms.has(t.term)));
  }

  const IntegratorSettings& i = c.integrator;
  out.section("integrator");
  out.word("kind", name_of(kIntegratorKinds, i.kind));
  out.quantity("step", i.step_s, Dimension::time, "us");
  out.quantity("end_time", i.end_time_s, Dimension::time, "ms");
  out.number("relative_tolerance", i.adaptive_relative_tolerance);
  out.integer("output_every", i.output_every);
  return out.text();
}

}  // namespace gearimpact
