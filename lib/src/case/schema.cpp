#include "gearimpact/case/schema.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/modifications.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/named_values.hpp"
#include "gearimpact/numerics/quadrature.hpp"
#include "gearimpact/stiffness/model.hpp"
#include "gearimpact/stiffness/surface_faults.hpp"

namespace gearimpact {

namespace {

// A name is written into output file names: at most this many characters.
constexpr std::size_t kLongestName = 100;
// Tooth counts beyond this are not gears but typing slips; the geometry
// needs at least 4 (the teeth rows), the undercut limit more (validate_geometry).
constexpr double kMostTeeth = 100000.0;

constexpr Bound open(double value) {
  return {value, false};
}
constexpr Bound closed(double value) {
  return {value, true};
}

bool is_name_character(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

// One significant digit as 1e-14 or 2e9, the rest as the shortest decimal.
std::string bound_text(double value) {
  std::array<char, 64> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                          std::chars_format::scientific);
  const std::string scientific(buffer.data(), error == std::errc{} ? end : buffer.data());
  const std::size_t e = scientific.find('e');
  if (e != std::string::npos && scientific.find('.') == std::string::npos) {
    const int exponent = std::stoi(scientific.substr(e + 1));
    if (exponent <= -2 || exponent >= 2) {
      return scientific.substr(0, e) + "e" + std::to_string(exponent);
    }
  }
  return shortest_decimal(value);
}

// get/set of a field of SimulationCase reached by `slot`, a generic lambda
// returning a reference to it (const or not), whatever its type: double, int,
// bool (on/off) or an enumeration (a choice's code).
template <typename Slot>
void bind(Field& field, Slot slot) {
  field.get = [slot](const SimulationCase& c) {
    using T = std::decay_t<decltype(slot(c))>;
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      return slot(c).value_or(std::numeric_limits<double>::quiet_NaN());
    } else if constexpr (std::is_enum_v<T>) {
      return static_cast<double>(static_cast<int>(slot(c)));
    } else if constexpr (std::is_same_v<T, bool>) {
      return slot(c) ? 1.0 : 0.0;
    } else {
      return static_cast<double>(slot(c));
    }
  };
  field.set = [slot](SimulationCase& c, double value) {
    using T = std::decay_t<decltype(slot(c))>;
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      slot(c) = value;
    } else if constexpr (std::is_enum_v<T>) {
      slot(c) = static_cast<T>(static_cast<int>(value));
    } else if constexpr (std::is_same_v<T, bool>) {
      slot(c) = value != 0.0;
    } else if constexpr (std::is_integral_v<T>) {
      slot(c) = static_cast<T>(value);
    } else {
      slot(c) = value;
    }
  };
}

template <typename E>
ChoiceName choice(std::string_view name, E value, std::string_view meaning, bool has_text = true) {
  return {name, static_cast<int>(value), meaning, has_text};
}

// The choices of a row from the table of its enumeration.
template <typename E, std::size_t N>
std::vector<ChoiceName> choices_of(const std::array<NamedValue<E>, N>& table) {
  std::vector<ChoiceName> choices;
  for (const NamedValue<E>& entry : table) {
    choices.push_back(choice(entry.name, entry.value, entry.meaning));
  }
  return choices;
}

// The rows of one section, added in the order they are written.
class Rows {
 public:
  explicit Rows(std::vector<Field>& rows, std::string_view section)
      : rows_(rows), section_(section) {}

  template <typename Slot>
  Field& quantity(std::string_view key, Dimension dimension, std::string_view unit, Range range,
                  bool required, const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::quantity, required, help, slot);
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& number(std::string_view key, Range range, bool required, const std::string& help,
                Slot slot) {
    Field& f = add(key, FieldKind::number, required, help, slot);
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& integer(std::string_view key, Range range, bool required, const std::string& help,
                 Slot slot) {
    // The row's range must fit its slot's type: a value past it would wrap when set (a tooth
    // of 2^31 read as -2^31), so every integer row is bounded on both sides.
    using T = std::decay_t<decltype(slot(std::declval<SimulationCase&>()))>;
    if (!range.lower || !range.upper ||
        range.lower->value < static_cast<double>(std::numeric_limits<T>::lowest()) ||
        range.upper->value > static_cast<double>(std::numeric_limits<T>::max())) {
      throw std::logic_error("the integer row " + std::string(key) +
                             " has a range its slot's type cannot hold");
    }
    Field& f = add(key, FieldKind::integer, required, help, slot);
    f.range = range;
    return f;
  }
  template <typename Slot>
  Field& choice(std::string_view key, std::vector<ChoiceName> choices, bool required,
                const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::choice, required, help, slot);
    f.choices = std::move(choices);
    return f;
  }
  // A list of quantities, each in `range`; `slot` returns the std::vector<double>.
  template <typename Slot>
  Field& quantity_list(std::string_view key, Dimension dimension, std::string_view unit,
                       Range range, std::size_t most_values, bool required, const std::string& help,
                       Slot slot) {
    Field f;
    f.section = section_;
    f.key = key;
    f.kind = FieldKind::quantity_list;
    f.required = required;
    f.help = help;
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    f.most_values = most_values;
    f.get_list = [slot](const SimulationCase& c) { return slot(c); };
    f.set_list = [slot](SimulationCase& c, const std::vector<double>& values) { slot(c) = values; };
    rows_.push_back(std::move(f));
    return rows_.back();
  }
  // A list of plain numbers, each in `range`; `slot` returns the std::vector<double>.
  template <typename Slot>
  Field& number_list(std::string_view key, Range range, std::size_t most_values, bool required,
                     const std::string& help, Slot slot) {
    Field& f = quantity_list(key, Dimension::length, "", range, most_values, required, help, slot);
    f.kind = FieldKind::number_list;
    return f;
  }
  template <typename Slot>
  Field& on_off(std::string_view key, const std::string& help, Slot slot) {
    Field& f = add(key, FieldKind::on_off, false, help, slot);
    f.choices = {{"on", 1, "included", true}, {"off", 0, "left out", true}};
    return f;
  }

 private:
  template <typename Slot>
  Field& add(std::string_view key, FieldKind kind, bool required, const std::string& help,
             Slot slot) {
    Field f;
    f.section = section_;
    f.key = key;
    f.kind = kind;
    f.required = required;
    f.help = help;
    bind(f, slot);
    rows_.push_back(std::move(f));
    return rows_.back();
  }

  std::vector<Field>& rows_;
  std::string_view section_;
};

// The rows of [torque1] (gear = 1, which may be a kinematic driver) or
// [torque2] (gear = 2, which may be a drag on a loose gear).
template <typename TorqueSlot>
void add_torque(std::vector<Field>& rows, std::string_view section, int gear, TorqueSlot torque) {
  Rows r(rows, section);
  std::vector<ChoiceName> kinds{
      choice("constant", Torque::Kind::constant, "T = value"),
      choice("sinusoidal", Torque::Kind::sinusoidal,
             "T = amplitude sin(angular_frequency t + phase)"),
      choice("harmonic", Torque::Kind::harmonic,
             "T = mean + sum_i amplitudes[i] sin(angular_frequencies[i] t + phases[i])"),
      choice("user", Torque::Kind::user,
             "T(t) given as a function: through the library only, it has no text form", false)};
  if (gear == 1) {
    kinds.push_back(choice("prescribed-speed", Torque::Kind::prescribed_speed,
                           "a kinematic driver: w1 = mean_speed + sum_i speed_amplitudes[i] "
                           "sin(orders[i] mean_speed t + phases[i]), theta1(0) = initial.theta1; "
                           "the torque it needs is computed and its work booked"));
    kinds.push_back(choice("speed-controlled", Torque::Kind::speed_controlled,
                           "a motor with a PI speed controller: T = T_ff + K_p e + K_i Int e dt, "
                           "e = mean_speed (or the speed profile) - w of the driven body, gains "
                           "from bandwidth, damping_ratio and the train's inertia"));
    kinds.push_back(choice("induction-motor", Torque::Kind::induction_motor,
                           "Kloss's law T = 2 breakdown_torque / (s / breakdown_slip + "
                           "breakdown_slip / s), s = 1 - w / synchronous_speed"));
  } else {
    kinds.push_back(choice("drag", Torque::Kind::drag,
                           "T = -(drag_constant tanh(w2 / drag_speed_scale) + drag_viscous w2), "
                           "opposing the rotation of a loose gear"));
  }
  kinds.push_back(choice("profile", Torque::Kind::profile,
                         "T(t) linear between the points (profile_times[i], profile_torques[i]), "
                         "held beyond the ends; a time given twice is a step"));
  r.choice(
      "kind", std::move(kinds), true,
      "form of the external torque T(t) on the gear", [torque](auto& c) -> auto& {
        return torque(c).kind;
      });
  r.quantity(
       "value", Dimension::torque, "N*mm", {}, true,
       "T of a constant torque", [torque](auto& c) -> auto& { return torque(c).constant_n_m; })
      .only_when = FieldCondition{"kind", {"constant"}};
  Field& mean = r.quantity(
      "mean", Dimension::torque, "N*mm", {}, false,
      "T_m, the mean the fluctuation is added to: T = mean + A sin(W t + phase) or mean + "
      "the harmonics; a case file leaves it out while it is 0",
      [torque](auto& c) -> auto& { return torque(c).mean_n_m; });
  mean.only_when = FieldCondition{"kind", {"sinusoidal", "harmonic"}};
  mean.written_at_default = false;
  r.quantity(
       "amplitude", Dimension::torque, "N*mm", {}, true, "A of T = A sin(W t + phase)",
       [torque](auto& c) -> auto& { return torque(c).amplitude_n_m; })
      .only_when = FieldCondition{"kind", {"sinusoidal"}};
  r.quantity(
       "angular_frequency", Dimension::angular_frequency, "rad/s", {closed(0.0), {}, {}}, true,
       "W of T = A sin(W t + phase); Hz counts cycles (W = 2 pi f). Not negative: "
       "-W is the same sinusoid as W with the phase pi - phase",
       [torque](auto& c) -> auto& { return torque(c).angular_frequency_rad_per_s; })
      .only_when = FieldCondition{"kind", {"sinusoidal"}};
  r.quantity(
       "phase", Dimension::angle, "deg", {}, false, "phase of T = A sin(W t + phase)",
       [torque](auto& c) -> auto& { return torque(c).phase_rad; })
      .only_when = FieldCondition{"kind", {"sinusoidal"}};
  // The three lists of a harmonic torque, one element per harmonic, of one
  // length (validate_relations). Each harmonic costs a sine per right-hand
  // side evaluation; a thousand is more than an engine's orders or a
  // measured spectrum needs.
  constexpr std::size_t kMostHarmonics = 1000;
  r.quantity_list(
       "amplitudes", Dimension::torque, "N*mm", {}, kMostHarmonics, true,
       "A_i of T = mean + sum_i A_i sin(w_i t + phi_i); as many as angular_frequencies and phases",
       [torque](auto& c) -> auto& { return torque(c).harmonic_amplitudes_n_m; })
      .only_when = FieldCondition{"kind", {"harmonic"}};
  r.quantity_list(
       "angular_frequencies", Dimension::angular_frequency, "rad/s", {closed(0.0), {}, {}},
       kMostHarmonics, true, "w_i of the harmonics; not negative, as angular_frequency",
       [torque](auto& c) -> auto& { return torque(c).harmonic_angular_frequencies_rad_per_s; })
      .only_when = FieldCondition{"kind", {"harmonic"}};
  std::vector<std::string_view> with_phases{"harmonic"};
  if (gear == 1) with_phases.push_back("prescribed-speed");
  r.quantity_list(
       "phases", Dimension::angle, "deg", {}, kMostHarmonics, true,
       "phi_i of the harmonics (of the torque, or of the driver's speed)",
       [torque](auto& c) -> auto& { return torque(c).harmonic_phases_rad; })
      .only_when = FieldCondition{"kind", std::move(with_phases)};
  if (gear == 1) {
    // The engine orders count harmonics of the mean speed: the driver's
    // period is 2 pi / (W times the orders' greatest common divisor).
    r.quantity(
         "mean_speed", Dimension::angular_velocity, "rpm", {open(0.0), {}, {}}, true,
         "W, the driver's mean speed; positive (the loose gear's drag opposes the rotation it "
         "takes from it)",
         [torque](auto& c) -> auto& { return torque(c).mean_speed_rad_per_s; })
        .only_when = FieldCondition{"kind", {"prescribed-speed", "speed-controlled"}};
    r.number_list(
         "orders", {open(0.0), {}, {}}, kMostHarmonics, true,
         "n_i, the orders of the speed harmonics: the i-th turns at n_i W (2 for a four-stroke "
         "four-cylinder engine's firing order on the crankshaft); as many as speed_amplitudes "
         "and phases",
         [torque](auto& c) -> auto& { return torque(c).driver_orders; })
        .only_when = FieldCondition{"kind", {"prescribed-speed"}};
    r.quantity_list(
         "speed_amplitudes", Dimension::angular_velocity, "rad/s", {closed(0.0), {}, {}},
         kMostHarmonics, true,
         "a_i, the speed fluctuation of each order: w1 = W + sum_i a_i sin(n_i W t + phi_i); "
         "an angle amplitude A_i is a_i = A_i n_i W",
         [torque](auto& c) -> auto& { return torque(c).driver_speed_amplitudes_rad_per_s; })
        .only_when = FieldCondition{"kind", {"prescribed-speed"}};
    // A speed profile: a few segments (hold, ramp, step); each point costs
    // a little at each right-hand side evaluation.
    constexpr std::size_t kMostProfilePoints = 1000;
    Field& times = r.quantity_list(
        "speed_profile_times", Dimension::time, "s", {closed(0.0), {}, {}}, kMostProfilePoints,
        false,
        "t_i of the speed profile W(t), linear between the points (t_i, W_i) and held beyond "
        "them, in place of mean_speed; non-decreasing, a time given twice a step (refused for "
        "prescribed-speed); as many as speed_profile_speeds",
        [torque](auto& c) -> auto& { return torque(c).speed_profile_times_s; });
    times.only_when = FieldCondition{"kind", {"prescribed-speed", "speed-controlled"}};
    times.written_at_default = false;
    Field& speeds = r.quantity_list(
        "speed_profile_speeds", Dimension::angular_velocity, "rpm", {open(0.0), {}, {}},
        kMostProfilePoints, false,
        "W_i of the speed profile, positive", [torque](auto& c) -> auto& {
          return torque(c).speed_profile_speeds_rad_per_s;
        });
    speeds.only_when = FieldCondition{"kind", {"prescribed-speed", "speed-controlled"}};
    speeds.written_at_default = false;
    r.quantity(
         "bandwidth", Dimension::angular_frequency, "Hz", {open(0.0), {}, {}}, false,
         "f_c of the speed loop: K_p = 2 damping_ratio w_c J_eq, K_i = w_c^2 J_eq with w_c = "
         "2 pi f_c and J_eq the train's inertia reflected to the pinion",
         [torque](auto& c) -> auto& { return torque(c).controller_bandwidth_rad_per_s; })
        .only_when = FieldCondition{"kind", {"speed-controlled"}};
    r.number(
         "damping_ratio", {open(0.0), {}, {}}, false,
         "zeta_c of the speed loop: a rigid train's error obeys e'' + 2 zeta_c w_c e' + w_c^2 e = "
         "0",
         [torque](auto& c) -> auto& { return torque(c).controller_damping_ratio; })
        .only_when = FieldCondition{"kind", {"speed-controlled"}};
    r.quantity(
         "synchronous_speed", Dimension::angular_velocity, "rpm", {open(0.0), {}, {}}, true,
         "w_s, the induction motor's synchronous speed (slip s = 1 - w / w_s)",
         [torque](auto& c) -> auto& { return torque(c).synchronous_speed_rad_per_s; })
        .only_when = FieldCondition{"kind", {"induction-motor"}};
    r.quantity(
         "breakdown_torque", Dimension::torque, "N*m", {open(0.0), {}, {}}, true,
         "T_b, the induction motor's largest (breakdown) torque",
         [torque](auto& c) -> auto& { return torque(c).breakdown_torque_n_m; })
        .only_when = FieldCondition{"kind", {"induction-motor"}};
    r.number(
         "breakdown_slip", {open(0.0), closed(1.0), "a slip between standstill and synchronism"},
         true, "s_b, the slip of the breakdown torque",
         [torque](auto& c) -> auto& { return torque(c).breakdown_slip; })
        .only_when = FieldCondition{"kind", {"induction-motor"}};
  } else {
    r.quantity(
         "drag_constant", Dimension::torque, "N*m", {closed(0.0), {}, {}}, true,
         "T_c, the constant part of the drag (churning, seals), against the rotation",
         [torque](auto& c) -> auto& { return torque(c).drag_constant_n_m; })
        .only_when = FieldCondition{"kind", {"drag"}};
    r.quantity(
         "drag_viscous", Dimension::rotational_damping, "N*m*s/rad", {closed(0.0), {}, {}}, true,
         "c, the viscous part of the drag, c w2 against the rotation",
         [torque](auto& c) -> auto& { return torque(c).drag_viscous_n_m_s; })
        .only_when = FieldCondition{"kind", {"drag"}};
    r.quantity(
         "drag_speed_scale", Dimension::angular_velocity, "rad/s", {open(0.0), {}, {}}, false,
         "w_s of tanh(w2 / w_s), the smoothed sign of the constant drag: within a few w_s of "
         "w2 = 0 the drag fades to 0 (a loose gear that stops is not held by it)",
         [torque](auto& c) -> auto& { return torque(c).drag_speed_scale_rad_per_s; })
        .only_when = FieldCondition{"kind", {"drag"}};
  }
  constexpr std::size_t kMostProfilePoints = 1000;
  r.quantity_list(
       "profile_times", Dimension::time, "s", {closed(0.0), {}, {}}, kMostProfilePoints, true,
       "t_i of T(t), linear between the points (t_i, T_i) and held beyond them; non-decreasing, "
       "a time given twice a step (a load step); as many as profile_torques",
       [torque](auto& c) -> auto& { return torque(c).profile_times_s; })
      .only_when = FieldCondition{"kind", {"profile"}};
  r.quantity_list(
       "profile_torques", Dimension::torque, "N*m", {}, kMostProfilePoints, true,
       "T_i of T(t)", [torque](auto& c) -> auto& { return torque(c).profile_torques_n_m; })
      .only_when = FieldCondition{"kind", {"profile"}};
}

// The keys of one gear's modifications in [modifications] (their names end in
// the gear's number). Every row is left out of a case file at its default, so
// that files written before these keys existed keep their bytes.
template <typename GearSlot>
void add_modifications(std::vector<Field>& rows, int gear, GearSlot of) {
  Rows r(rows, "modifications");
  const bool one = gear == 1;
  const std::string n = one ? "1" : "2";
  // A relief or an error is micrometres; a millimetre is a typing slip.
  const Range amount{closed(0.0), closed(1e-3), "at most 1 mm: reliefs are micrometres"};
  const Range deviation{closed(-1e-3), closed(1e-3), "within 1 mm: tooth errors are micrometres"};
  const Range diameter{closed(0.0), {}, {}};
  r.quantity(
       one ? "tip_relief1" : "tip_relief2", Dimension::length, "um", amount, false,
       "C_a, the tip relief of gear " + n +
           ": material removed at the tip of both flanks of every tooth, along the line of "
           "action; 0: none",
       [of](auto& c) -> auto& { return of(c).tip.amount_m; })
      .written_at_default = false;
  r.quantity(
       one ? "tip_relief_start1" : "tip_relief_start2", Dimension::length, "mm", diameter, false,
       "d_Ca, the diameter where the tip relief of gear " + n + " starts; with tip_relief" + n +
           " > 0 it lies in the active profile, [d_SAP, d_a) (check-case names the limits)",
       [of](auto& c) -> auto& { return of(c).tip.diameter_m; })
      .written_at_default = false;
  r.choice(
       one ? "tip_relief_shape1" : "tip_relief_shape2", choices_of(kReliefShapes), false,
       "the shape of the tip relief of gear " + n +
           " over its roll length: C_a u^p, u from 0 at d_Ca to 1 at the tip",
       [of](auto& c) -> auto& { return of(c).tip.shape; })
      .written_at_default = false;
  r.quantity(
       one ? "root_relief1" : "root_relief2", Dimension::length, "um", amount, false,
       "C_f, the root relief of gear " + n +
           ": material removed at the start of its active profile (where the mating tip "
           "meets it), both flanks; 0: none",
       [of](auto& c) -> auto& { return of(c).root.amount_m; })
      .written_at_default = false;
  r.quantity(
       one ? "root_relief_end1" : "root_relief_end2", Dimension::length, "mm", diameter, false,
       "d_Cf, the diameter where the root relief of gear " + n + " ends; with root_relief" + n +
           " > 0 it lies in (d_SAP, d_a], at most d_Ca",
       [of](auto& c) -> auto& { return of(c).root.diameter_m; })
      .written_at_default = false;
  r.choice(
       one ? "root_relief_shape1" : "root_relief_shape2", choices_of(kReliefShapes), false,
       "the shape of the root relief of gear " + n + ": C_f u^p, u from 0 at d_Cf to 1 at d_SAP",
       [of](auto& c) -> auto& { return of(c).root.shape; })
      .written_at_default = false;
  // One value per tooth. A case file's lists together bound the TOML parser's work, so the
  // lists of one tooth each stop at 1000 teeth, more than a gear measured tooth by tooth has.
  constexpr std::size_t most = 1000;
  r.quantity_list(
       one ? "pitch_deviations1" : "pitch_deviations2", Dimension::length, "um", deviation, most,
       false,
       "f_p of each tooth of gear " + n +
           ", tooth 0 first (none, or one per tooth): a positive f makes the tooth "
           "meet later on the drive flanks (gap +f) and earlier on the coast flanks "
           "(gap -f)",
       [of](auto& c) -> auto& { return of(c).pitch_m; })
      .written_at_default = false;
  r.quantity_list(
       one ? "thickness_deviations1" : "thickness_deviations2", Dimension::length, "um", deviation,
       most, false,
       "material removed from each flank of each tooth of gear " + n +
           " (the tooth 2 f thinner along the base tangent; negative: thicker), "
           "tooth 0 first",
       [of](auto& c) -> auto& { return of(c).thickness_m; })
      .written_at_default = false;
  r.quantity_list(
       one ? "profile_slope_deviations1" : "profile_slope_deviations2", Dimension::length, "um",
       deviation, most, false,
       "f_Ha of each tooth of gear " + n +
           ", tooth 0 first: a gap rising linearly along the active profile from "
           "-f_Ha/2 at d_SAP to +f_Ha/2 at the tip (0 at the middle of its roll length)",
       [of](auto& c) -> auto& { return of(c).profile_slope_m; })
      .written_at_default = false;
  r.integer(
       one ? "iso1328_class1" : "iso1328_class2",
       {closed(0.0), closed(11.0), "0: none; ISO 1328-1:2013 has the classes 1 to 11"}, false,
       "A, the flank tolerance class of gear " + n +
           " (ISO 1328-1:2013, 1 the finest): draws its pitch and profile slope deviations "
           "within the class's f_pT and f_HalphaT with error_seed, in place of their lists "
           "(docs/faults.md, \"Errors drawn from a tolerance class\"); 0: none",
       [of](auto& c) -> auto& { return of(c).iso1328_class; })
      .written_at_default = false;
}

// The rows of one gear's bearing in [bearings] (their names end in the
// gear's number), each only with kind = "elastic".
template <typename BearingSlot>
void add_bearing(std::vector<Field>& rows, int gear, BearingSlot of) {
  Rows r(rows, "bearings");
  const std::string n = gear == 1 ? "1" : "2";
  // Stiffer than any rolling or journal bearing (1e8 to 1e10 N/m) by five
  // orders and more. The eigenproblem's rounding grows as eps k / m: at 1e16
  // it is still below 1e-8 of a mesh mode's w^2 (the paper's pair meets the
  // torsional limit to 2e-8 there); stiffer only loses digits, and
  // kind = "rigid" is that limit exactly.
  // Softer than 1e-3 N/m is no bearing (the centres then move freely to rounding, and the
  // modes call near-zero modes elastic). A damper past 1e6 N*s/m is past any bearing or
  // squeeze-film damper (1e2 to 1e5) and made a run's state NaN mid-run.
  const Range stiffness{closed(1e-3), closed(1e16),
                        "softer is no bearing; stiffer is kind = \"rigid\""};
  const Range damping{closed(0.0), closed(1e6), "more is past any bearing or squeeze-film damper"};
  const FieldCondition elastic{"kind", {"elastic"}};
  // A row's key is a string_view: the names live in static storage.
  static const std::array<std::array<const char*, 5>, 2> names{{
      {"stiffness_x1", "stiffness_y1", "damping_x1", "damping_y1", "mass1"},
      {"stiffness_x2", "stiffness_y2", "damping_x2", "damping_y2", "mass2"},
  }};
  const auto& name = names[static_cast<std::size_t>(gear - 1)];
  r.quantity(
       name[0], Dimension::stiffness, "N/um", stiffness, true,
       "k_x of gear " + n + "'s bearing, along the centre line O1 -> O2",
       [of](auto& c) -> auto& { return of(c).stiffness_x_n_per_m; })
      .only_when = elastic;
  Field& ky = r.quantity(
      name[1], Dimension::stiffness, "N/um", stiffness, false,
      "k_y of gear " + n + "'s bearing, across the centre line", [of](auto& c) -> auto& {
        return of(c).stiffness_y_n_per_m;
      });
  ky.only_when = elastic;
  ky.when_absent = gear == 1 ? "stiffness_x1 (isotropic)" : "stiffness_x2 (isotropic)";
  r.quantity(
       name[2], Dimension::damping, "N*s/m", damping, false,
       "c_x of gear " + n +
           "'s bearing; 0: none (simulate uses it; the modes are those of the undamped "
           "system)",
       [of](auto& c) -> auto& { return of(c).damping_x_n_s_per_m; })
      .only_when = elastic;
  Field& cy = r.quantity(
      name[3], Dimension::damping, "N*s/m", damping, false,
      "c_y of gear " + n + "'s bearing", [of](auto& c) -> auto& {
        return of(c).damping_y_n_s_per_m;
      });
  cy.only_when = elastic;
  cy.when_absent = gear == 1 ? "damping_x1 (isotropic)" : "damping_x2 (isotropic)";
  Field& mass = r.quantity(
      name[4], Dimension::mass, "kg",
      {closed(1e-4), closed(1e6), "a tenth of a gram (a watch's gear) to a thousand tonnes"}, false,
      "m, the mass of gear " + n + " with what moves with its centre", [of](auto& c) -> auto& {
        return of(c).mass_kg;
      });
  mass.only_when = elastic;
  mass.when_absent = "the disc whose J the torsional model uses, rho pi r^2 L";
}

std::vector<Field> make_schema() {
  std::vector<Field> rows;
  {
    Field name;
    name.key = "name";
    name.kind = FieldKind::text;
    name.help =
        "names the case in outputs; a case file without it takes the file's stem, a library "
        "case may stay unnamed";
    name.get_text = [](const SimulationCase& c) { return c.name; };
    name.set_text = [](SimulationCase& c, const std::string& value) { c.name = value; };
    rows.push_back(std::move(name));
  }
  {
    Rows r(rows, "gears");
    const Range teeth{closed(4.0), closed(kMostTeeth), {}};
    r.integer(
        "teeth1", teeth, true,
        "Z1, teeth of gear 1 (the driver in the paper); at least 2 ha / sin^2(a0), "
        "below which rack generation undercuts the involute",
        [](auto& c) -> auto& { return c.gears.teeth1; });
    r.integer(
        "teeth2", teeth, true, "Z2, teeth of gear 2; the same limits as teeth1",
        [](auto& c) -> auto& { return c.gears.teeth2; });
    r.quantity(
        "module", Dimension::length, "mm",
        {closed(1e-6), closed(1.0), "1 um (a micro gear) to 1 m (a mill's ring gear is 0.05 m)"},
        true, "m: pitch radius r_i = m Z_i / 2", [](auto& c) -> auto& { return c.gears.module_m; });
    r.quantity(
        "pressure_angle", Dimension::angle, "deg", {open(0.0), closed(pi / 4.0), {}}, true,
        "a0 of the generating rack and of the mesh (standard centre distance)",
        [](auto& c) -> auto& { return c.gears.pressure_angle_rad; });
    r.quantity(
        "face_width", Dimension::length, "mm", {open(0.0), {}, {}}, true,
        "L, the face width (\"thickness of gears\" in the paper)",
        [](auto& c) -> auto& { return c.gears.face_width_m; });
    r.number(
        "addendum_coefficient", {open(0.0), {}, {}}, false,
        "addendum / module, both gears; the pair must also keep its teeth unpointed, "
        "be free of interference and have a contact ratio in [1, 3)",
        [](auto& c) -> auto& { return c.gears.addendum_coefficient; });
    r.quantity(
        "youngs_modulus", Dimension::pressure, "GPa", {open(0.0), {}, {}}, true, "E of both gears",
        [](auto& c) -> auto& { return c.gears.youngs_modulus_pa; });
    r.number(
        "poisson_ratio", {open(-1.0), open(0.5), "both ends excluded"}, true,
        "nu of both gears; (-1, 0.5) is the range of a stable isotropic solid",
        [](auto& c) -> auto& { return c.gears.poisson_ratio; });
    r.quantity(
        "density", Dimension::density, "kg/m^3", {open(0.0), {}, {}}, true,
        "rho of both gears (solid discs on the pitch circle give J1, J2)",
        [](auto& c) -> auto& { return c.gears.density_kg_m3; });
    r.quantity(
        "backlash", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
        "B of (31), along the line of action: half the total play 2B, the teeth touching at "
        "s = +B (drive flank, N1) and s = -B (coast flank, N2); s and the DTE columns of a "
        "sweep (dte_mean_m, s_min_m, s_max_m) include it, the deflection is s - B on N1",
        [](auto& c) -> auto& { return c.gears.backlash_m; });
    r.number(
        "dedendum_coefficient", {open(0.0), {}, {}}, false,
        "the rack's dedendum / module, ha + c: the root radius is r - (ha + c - x) m; only the "
        "models that start the tooth at the root circle see it; above the addendum coefficient",
        [](auto& c) -> auto& { return c.gears.dedendum_coefficient; });
    r.number(
        "profile_shift1", {}, false,
        "x1: the rack's datum line moved out by x1 m (the pair then meshes at its operating "
        "pressure angle); limited by a pointed tip and by undercut, both named when met",
        [](auto& c) -> auto& { return c.gears.profile_shift1; });
    r.number(
        "profile_shift2", {}, false, "x2, as profile_shift1 for gear 2",
        [](auto& c) -> auto& { return c.gears.profile_shift2; });
    r.number(
         "rack_tip_radius_coefficient", {closed(0.0), {}, {}}, false,
         "rho / m of the rack's tip round; it must fit the clearance and the rack's tip land",
         [](auto& c) -> auto& { return c.gears.rack_tip_radius_coefficient; })
        .when_absent = "the full round c / (1 - sin a0), or the largest that fits the tip land";
    r.quantity(
         "bore_diameter1", Dimension::length, "mm", {open(0.0), {}, {}}, false,
         "bore of gear 1, below its root diameter; needed by the fillet-foundation term only",
         [](auto& c) -> auto& { return c.gears.bore_diameter1_m; })
        .when_absent = "no bore given (the foundation term then refuses to run)";
    r.quantity(
         "bore_diameter2", Dimension::length, "mm", {open(0.0), {}, {}}, false,
         "bore of gear 2, as bore_diameter1",
         [](auto& c) -> auto& { return c.gears.bore_diameter2_m; })
        .when_absent = "no bore given (the foundation term then refuses to run)";
    r.quantity(
         "youngs_modulus2", Dimension::pressure, "GPa", {open(0.0), {}, {}}, false,
         "E of gear 2 (Hertz for two materials)",
         [](auto& c) -> auto& { return c.gears.youngs_modulus2_pa; })
        .when_absent = "gear 1's";
    r.number(
         "poisson_ratio2", {open(-1.0), open(0.5), "both ends excluded"}, false, "nu of gear 2",
         [](auto& c) -> auto& { return c.gears.poisson_ratio2; })
        .when_absent = "gear 1's";
  }
  add_torque(
      rows, "torque1", 1, [](auto& c) -> auto& { return c.torque1; });
  add_torque(
      rows, "torque2", 2, [](auto& c) -> auto& { return c.torque2; });
  {
    Rows r(rows, "initial");
    // s = Rb1 theta1 - Rb2 theta2 is a difference of angles times radii: at
    // 1e6 rad a double holds Rb theta to about 1e-11 m, a millionth of a
    // micrometre deflection; far beyond it the contact is lost in rounding
    // (at 1e17 rad one ulp is 16 rad) and event location cannot converge.
    const Range kInitialAngles{closed(-1e6), closed(1e6),
                               "|theta| <= 1e6 rad keeps s resolved to 1e-11 m"};
    r.quantity(
        "theta1", Dimension::angle, "deg", kInitialAngles, false,
        "theta1(0); theta1 = theta2 = 0 centres the teeth in the backlash",
        [](auto& c) -> auto& { return c.initial.theta1_rad; });
    r.quantity(
        "theta2", Dimension::angle, "deg", kInitialAngles, false, "theta2(0)",
        [](auto& c) -> auto& { return c.initial.theta2_rad; });
    r.quantity(
        "w1", Dimension::angular_velocity, "rad/s", {}, false, "w1(0)",
        [](auto& c) -> auto& { return c.initial.w1_rad_per_s; });
    r.quantity(
        "w2", Dimension::angular_velocity, "rad/s", {}, false, "w2(0)",
        [](auto& c) -> auto& { return c.initial.w2_rad_per_s; });
  }
  {
    Rows r(rows, "model");
    r.number(
        "friction_coefficient", {closed(0.0), closed(1.0), {}}, false,
        "f of (35): Ff = f N against the sliding speed; at most 1: dry steel on steel stays "
        "below about 0.8, lubricated teeth below 0.1, and a larger f is no tooth contact; the f of "
        "friction_law = \"constant\"",
        [](auto& c) -> auto& { return c.model.friction_coefficient; });
    // The friction laws. Case files written before they existed hold the
    // constant law, so the writer leaves the keys out at their defaults.
    r.choice(
         "friction_law", choices_of(kFrictionLaws), false,
         "where f of (35) comes from: friction_coefficient, or the Benedict and Kelley (1961) "
         "coefficient at each pair's load and speeds (docs/model.md, section Contact, damping, "
         "friction)",
         [](auto& c) -> auto& { return c.model.friction_law; })
        .written_at_default = false;
    r.quantity(
         "lubricant_viscosity", Dimension::viscosity, "cP", {open(0.0), {}, {}}, true,
         "nu0, the lubricant's dynamic viscosity at the teeth, in Benedict and Kelley's (1961) "
         "f = 0.0127 C_R log10(3.17e8 (W/F) / (nu0 Vs Ve^2)) (He, Gunda and Singh, J. Sound "
         "Vib. 2007)",
         [](auto& c) -> auto& { return c.model.benedict_kelley.viscosity_pa_s; })
        .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
    r.quantity(
         "surface_roughness", Dimension::length, "um",
         {closed(0.0), open(1.27e-6),
          "C_R = 50 / (50 - S) of Benedict and Kelley diverges at S = 50 micro-inches"},
         true,
         "S, the mean surface roughness of the flanks, in C_R = 50 / (50 - S) of Benedict "
         "and Kelley (1961)",
         [](auto& c) -> auto& { return c.model.benedict_kelley.roughness_m; })
        .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
    r.number(
         "friction_coefficient_max", {open(0.0), closed(1.0), {}}, false,
         "f_max: Benedict and Kelley's f is clipped to [0, f_max], since it diverges at the "
         "pitch point (Vs -> 0) and is negative where its log argument falls below 1; "
         "default 0.1, the top of lubricated teeth",
         [](auto& c) -> auto& { return c.model.benedict_kelley.most_coefficient; })
        .only_when = FieldCondition{"friction_law", {"benedict-kelley"}};
    // The table law's two lists, one entry per point, of one length
    // (validate_relations). A lookup is a binary search, so the bound is on
    // the case file's size (its lists together bound the values a case file
    // holds), not on the run's cost: a measured friction curve has tens of points.
    constexpr std::size_t kMostFrictionTableEntries = 1000;
    r.number_list(
         "friction_table_slide_to_roll", {}, kMostFrictionTableEntries, true,
         "the slide-to-roll ratios 2 Vs / Ve of the friction table, strictly increasing (0 at the "
         "pitch point when the gears roll, negative where the pinion's flank slides slower); f "
         "is linear between them and constant beyond the first and the last",
         [](auto& c) -> auto& { return c.model.friction_table.slide_to_roll; })
        .only_when = FieldCondition{"friction_law", {"table"}};
    r.number_list(
         "friction_table_coefficients", {closed(0.0), closed(1.0), {}}, kMostFrictionTableEntries,
         true,
         "f at each of friction_table_slide_to_roll, as many; at most 1, as friction_coefficient",
         [](auto& c) -> auto& { return c.model.friction_table.coefficient; })
        .only_when = FieldCondition{"friction_law", {"table"}};
    r.quantity(
         "friction_smoothing_speed", Dimension::speed, "m/s",
         {closed(0.0), closed(0.1),
          "at most 0.1 m/s: a band a small part of the sliding speeds (tenths of m/s and "
          "more on a flank); a wider one turns the friction into a weak viscous f N Vs / v_s "
          "and removes most of it"},
         false,
         "v_s of Ff = f N tanh(Vs / v_s), which replaces sign(Vs) of (35) and so the "
         "friction-reversal event; 0 keeps the exact switch (the paper's). A fixed step h "
         "needs v_s >= 10 h Rb1 |w1| (|w1| + |w2|): 20 steps across the band 2 v_s",
         [](auto& c) -> auto& { return c.model.friction_smoothing_speed_m_s; })
        .written_at_default = false;
    r.choice(
        "damping_form", choices_of(kDampingForms), false, "form of the damping factor D of (32)",
        [](auto& c) -> auto& { return c.model.damping_form; });
    r.choice(
        "damping_stiffness", choices_of(kDampingStiffnesses), false, "the stiffness K in (32)",
        [](auto& c) -> auto& { return c.model.damping_stiffness; });
    r.number(
        "restitution_coefficient", {closed(0.0), closed(1.0), {}}, false,
        "c of (33) e = 1 - c (Vi / speed unit)^p; at most 1: above it e < 0 at every impact "
        "faster than the speed unit. e is held at 0 (a fully plastic impact) for Vi above "
        "speed unit c^(-1/p), where (33) would give e < 0",
        [](auto& c) -> auto& { return c.model.restitution.coefficient; });
    r.number(
        "restitution_exponent", {open(0.0), closed(1.0), {}}, false,
        "p of (33): above 0 so that e falls as Vi grows; the published laws lie in "
        "(0, 1], from 1/5 (Hertzian viscoelastic contact) to 1 (Hunt and Crossley's "
        "linear e); the paper reads 3/8 or 0.36",
        [](auto& c) -> auto& { return c.model.restitution.exponent; });
    r.quantity(
        "restitution_speed_unit", Dimension::speed, "mm/s", {open(0.0), {}, {}}, false,
        "the unit Vi is measured in for (33): mm/s, the paper's length unit, or 1 in/s, "
        "1 m/s",
        [](auto& c) -> auto& { return c.model.restitution.speed_unit_m_s; });
    r.choice(
        "coast_phase", choices_of(kCoastPhases), false, "where the coast-flank contacts sit",
        [](auto& c) -> auto& { return c.model.coast_phase; });
    r.choice(
        "stiffness_model", choices_of(kStiffnessModels), false,
        "the mesh-stiffness model (docs/stiffness-models.md, section 3)",
        [](auto& c) -> auto& { return c.model.stiffness.kind; });
    r.choice(
        "moment_sign", choices_of(kMomentSigns), false,
        "sign of the axial-force moment in the bending stiffness",
        [](auto& c) -> auto& { return c.model.stiffness.moment_sign; });
    r.choice(
         "spall_reading", choices_of(kSpallReadings), false,
         "how a partial-width spall's contact loads the teeth (docs/faults.md)",
         [](auto& c) -> auto& { return c.model.stiffness.spall_reading; })
        .written_at_default = false;
    // stiffness_method names the tau-form with a quadrature rule, or the
    // x-form route; xform_rule the rule of the x-form route (used only then).
    // The tau-form's methods have their rule's code, the x-form one past them.
    constexpr int xform_code = static_cast<int>(kQuadratureRules.size());
    std::vector<ChoiceName> rules;
    std::vector<ChoiceName> methods;
    for (const StiffnessMethod& m : kStiffnessMethods) {
      if (m.route == StiffnessRoute::tau_form) {
        rules.push_back(choice(m.name, m.rule, m.meaning));
        methods.push_back(rules.back());
      } else {
        methods.push_back({m.name, xform_code, m.meaning, true});
      }
    }
    Field& method = r.choice(
        "stiffness_method", methods, false, "how the per-tooth terms are integrated",
        [](auto& c) -> auto& { return c.model.stiffness.route; });
    method.get = [](const SimulationCase& c) {
      const StiffnessModel& k = c.model.stiffness;
      return static_cast<double>(k.route == StiffnessRoute::x_form ? xform_code
                                                                   : static_cast<int>(k.rule));
    };
    method.set = [](SimulationCase& c, double code) {
      StiffnessModel& k = c.model.stiffness;
      if (static_cast<int>(code) == xform_code) {
        k.route = StiffnessRoute::x_form;
      } else {
        k.route = StiffnessRoute::tau_form;
        k.rule = static_cast<QuadratureRule>(static_cast<int>(code));
      }
    };
    Field& xform_rule = r.choice(
        "xform_rule", rules, false,
        "the rule the x-form route integrates with (one of the tau-form rules); used only "
        "with stiffness_method = \"xform\"",
        [](auto& c) -> auto& { return c.model.stiffness.rule; });
    xform_rule.set = [](SimulationCase& c, double code) {
      StiffnessModel& k = c.model.stiffness;
      if (k.route == StiffnessRoute::x_form)
        k.rule = static_cast<QuadratureRule>(static_cast<int>(code));
    };
    r.number(
        "stiffness_tolerance", {closed(1e-14), closed(1e-2), {}}, false,
        "relative tolerance of every quadrature of Ke: 1e-14 is a few ulps of the "
        "compliances, 1e-2 a rough run",
        [](auto& c) -> auto& { return c.model.stiffness.relative_tolerance; });
    for (const TermInfo& t : kTerms) {
      r.on_off(
          t.switch_key, std::string(t.description) + " of (29) in Ke (at least one term stays on)",
          [index = index_of(t.term)](auto& c) -> auto& {
            return c.model.stiffness.terms.on[index];
          });
    }
    // The steady-state model's options. Case files written before they
    // existed hold their defaults, so the writer leaves them out at those.
    r.choice(
         "mesh_stiffness", choices_of(kMeshStiffnessModes), false,
         "the mesh stiffness of the dynamics",
         [](auto& c) -> auto& { return c.model.mesh_stiffness; })
        .written_at_default = false;
    r.quantity(
         "constant_mesh_stiffness", Dimension::stiffness, "N/um", {open(0.0), {}, {}}, true,
         "k, the total mesh stiffness along the line of action",
         [](auto& c) -> auto& { return c.model.constant_mesh_stiffness_n_per_m; })
        .only_when = FieldCondition{"mesh_stiffness", {"constant"}};
    r.choice(
         "mesh_force", choices_of(kMeshForces), false,
         "how the mesh force follows from the time-varying stiffness (docs/model.md, section "
         "Energies)",
         [](auto& c) -> auto& { return c.model.mesh_force; })
        .written_at_default = false;
    r.number(
         "mesh_damping_ratio", {closed(0.0), closed(1.0), {}}, false,
         "zeta of the viscous mesh damper c = 2 zeta sqrt(k_mean m_e) on s', in contact and in "
         "the backlash; 0 leaves it out. At most 1 (critical damping): the RK4 step, set by the "
         "stiffness alone, resolves the damper's time constant only up to a few times critical",
         [](auto& c) -> auto& { return c.model.mesh_damping_ratio; })
        .written_at_default = false;
    r.choice(
         "damping_update", choices_of(kDampingUpdates), false,
         "when the Hertzian damping factor D of (32) is set",
         [](auto& c) -> auto& { return c.model.damping_update; })
        .written_at_default = false;
    Field& reference = r.quantity(
        "damping_reference_speed", Dimension::speed, "m/s", {open(0.0), {}, {}}, false,
        "V_ref: the impact speed of the frozen D (damping_update = \"frozen\", or \"auto\" "
        "with elastic bearings)",
        [](auto& c) -> auto& { return c.model.damping_reference_speed_m_s; });
    reference.only_when = FieldCondition{"damping_update", {"frozen", "auto"}};
    // Left out at its default, so that a case written under "auto" keeps the
    // bytes it had when the row applied under "frozen" only.
    reference.written_at_default = false;
  }
  {
    Rows r(rows, "integrator");
    r.choice(
        "kind", choices_of(kIntegratorKinds), false, "the integrator",
        [](auto& c) -> auto& { return c.integrator.kind; });
    r.quantity(
        "step", Dimension::time, "us", {open(0.0), {}, {}}, false,
        "the fixed RK4 step (the adaptive integrator's first step); the dynamics also "
        "requires at least " +
            shortest_decimal(kStepsPerContactPeriod) +
            " steps per period of the stiffest contact (" +
            shortest_decimal(kDopri5StepsPerContactPeriod) + " with kind = \"dopri5\")",
        [](auto& c) -> auto& { return c.integrator.step_s; });
    r.quantity(
        "end_time", Dimension::time, "ms", {open(0.0), {}, {}}, true,
        "run length; at most " + bound_text(static_cast<double>(kMostSteps)) +
            " steps of integrator.step: a longer run is a mistake (days of computing)",
        [](auto& c) -> auto& { return c.integrator.end_time_s; });
    r.number(
        "relative_tolerance", {closed(1e-14), closed(1e-3), {}}, false,
        "of the adaptive integrator, the cross-check of RK4: 1e-14 is a few ulps of the "
        "state; looser than 1e-3 it no longer sets the step, the largest step that "
        "resolves the contact does (cases 1-3 over 10 ms: the same steps, impacts and "
        "losses at 1e-3 and 1e-2)",
        [](auto& c) -> auto& { return c.integrator.adaptive_relative_tolerance; });
    r.integer(
        "output_every", {closed(1.0), closed(static_cast<double>(INT_MAX)), {}}, false,
        "keep every n-th row of the time series",
        [](auto& c) -> auto& { return c.integrator.output_every; });
  }
  Rows(rows, "drive")
      .number(
          "speed_tolerance", {open(0.0), {}, {}}, false,
          "the largest relative drift of the pinion's mean speed over a whole revolution "
          "from its reference (speed_drift_max_rel) before a planar run warns; 1e-3: over a "
          "1 s record of the rig example the mesh line moves by one bin at 1.5e-3",
          [](auto& c) -> auto& { return c.drive.speed_tolerance; })
      .written_at_default = false;
  {
    Rows r(rows, "tacho");
    r.integer(
         "pulses_per_revolution", {closed(0.0), closed(1048576.0), "0: no tacho"}, false,
         "the tacho's edges a revolution of its shaft, each located as an event on the "
         "true angle (planar runs; simulate --tacho-out writes their times)",
         [](auto& c) -> auto& { return c.tacho.pulses_per_revolution; })
        .written_at_default = false;
    r.choice(
         "shaft", choices_of(kTachoShafts), false, "the shaft the tacho reads",
         [](auto& c) -> auto& { return c.tacho.shaft; })
        .written_at_default = false;
    r.quantity(
         "offset", Dimension::angle, "deg", {}, false,
         "the angle of edge 0: edges where the shaft's angle crosses offset + 2 pi k / "
         "pulses_per_revolution upward",
         [](auto& c) -> auto& { return c.tacho.offset_rad; })
        .written_at_default = false;
    r.quantity(
         "jitter", Dimension::time, "s", {closed(0.0), {}, {}}, false,
         "the standard deviation of a Gaussian jitter of the emitted edge times (the true "
         "times stay jitter-free)",
         [](auto& c) -> auto& { return c.tacho.jitter_s; })
        .written_at_default = false;
    r.integer(
         "seed", {closed(0.0), closed(4294967295.0), "a 32-bit unsigned integer"}, false,
         "the seed of the jitter: the same seed, the same times, bit for bit",
         [](auto& c) -> auto& { return c.tacho.seed; })
        .written_at_default = false;
  }
  Rows(rows, "drive")
      .quantity(
          "settle", Dimension::time, "s", {closed(0.0), {}, {}}, false,
          "the start of the drift check: revolutions that begin earlier are the start's "
          "transient, not drift (a 10 Hz speed loop's error falls by e^-6.3 in 0.1 s)",
          [](auto& c) -> auto& { return c.drive.settle_s; })
      .written_at_default = false;
  add_modifications(
      rows, 1, [](auto& c) -> auto& { return c.modifications.gear1; });
  add_modifications(
      rows, 2, [](auto& c) -> auto& { return c.modifications.gear2; });
  Rows(rows, "modifications")
      .integer(
          "error_seed", {closed(0.0), closed(4294967295.0), "a 32-bit unsigned integer"}, false,
          "the seed of the tooth errors iso1328_class1 and iso1328_class2 draw: the same seed, "
          "the same teeth, bit for bit",
          [](auto& c) -> auto& { return c.modifications.error_seed; })
      .written_at_default = false;
  {
    // The planar model's keys (docs/vibration.md). Every row is left out of
    // a case file at its default, so that files written before they existed
    // keep their bytes.
    Rows r(rows, "bearings");
    r.choice(
         "kind", choices_of(kBearingKinds), false, "how the gears' centres are held",
         [](auto& c) -> auto& { return c.bearings.kind; })
        .written_at_default = false;
    add_bearing(
        rows, 1, [](auto& c) -> auto& { return c.bearings.gear1; });
    add_bearing(
        rows, 2, [](auto& c) -> auto& { return c.bearings.gear2; });
    const FieldCondition elastic{"kind", {"elastic"}};
    Field& gear = r.integer(
        "sensor_gear", {closed(1.0), closed(2.0), "1: the pinion, 2: the wheel"}, false,
        "the gear on whose bearing the accelerometer of the samples sits "
        "(sensor_acceleration_m_per_s2 of the planar samples, simulate --sample-rate)",
        [](auto& c) -> auto& { return c.bearings.sensor_gear; });
    gear.only_when = elastic;
    gear.written_at_default = false;
    // A full turn either way: an angle as a user measures it, clockwise or not.
    Field& angle = r.quantity(
        "sensor_angle", Dimension::angle, "deg", {closed(-2.0 * pi), closed(2.0 * pi), {}}, false,
        "the accelerometer's direction, from x (O1 -> O2) towards y; 90 deg: across the centre "
        "line",
        [](auto& c) -> auto& { return c.bearings.sensor_angle_rad; });
    angle.only_when = elastic;
    angle.written_at_default = false;
  }
  {
    Rows r(rows, "shafts");
    r.choice(
         "kind", choices_of(kShaftKinds), false,
         "whether the torques act on the gears or on a motor and a load behind torsional shafts",
         [](auto& c) -> auto& { return c.shafts.kind; })
        .written_at_default = false;
    // A watch's wheel to a mill's drive; a shaft from nearly free to stiffer than any (the
    // modes lost their order past it), a damper past any shaft's.
    const Range inertia{closed(1e-12), closed(1e6), {}};
    const Range stiffness{closed(1e-3), closed(1e12), {}};
    const Range damping{closed(0.0), closed(1e6), {}};
    const FieldCondition elastic{"kind", {"elastic"}};
    r.quantity(
         "motor_inertia", Dimension::moment_of_inertia, "kg*m^2", inertia, true,
         "J_m, the motor's moment of inertia on the pinion's shaft",
         [](auto& c) -> auto& { return c.shafts.motor_inertia_kg_m2; })
        .only_when = elastic;
    r.quantity(
         "motor_stiffness", Dimension::torsional_stiffness, "N*m/rad", stiffness, true,
         "k_t of the pinion's shaft, between the motor and the pinion",
         [](auto& c) -> auto& { return c.shafts.motor_stiffness_n_m_per_rad; })
        .only_when = elastic;
    r.quantity(
         "motor_damping", Dimension::rotational_damping, "N*m*s/rad", damping, false,
         "c_t of the pinion's shaft; 0: none (simulate uses it; the modes are undamped)",
         [](auto& c) -> auto& { return c.shafts.motor_damping_n_m_s_per_rad; })
        .only_when = elastic;
    r.quantity(
         "load_inertia", Dimension::moment_of_inertia, "kg*m^2", inertia, true,
         "J_L, the load's moment of inertia on the wheel's shaft",
         [](auto& c) -> auto& { return c.shafts.load_inertia_kg_m2; })
        .only_when = elastic;
    r.quantity(
         "load_stiffness", Dimension::torsional_stiffness, "N*m/rad", stiffness, true,
         "k_t of the wheel's shaft, between the wheel and the load",
         [](auto& c) -> auto& { return c.shafts.load_stiffness_n_m_per_rad; })
        .only_when = elastic;
    r.quantity(
         "load_damping", Dimension::rotational_damping, "N*m*s/rad", damping, false,
         "c_t of the wheel's shaft; 0: none (simulate uses it; the modes are undamped)",
         [](auto& c) -> auto& { return c.shafts.load_damping_n_m_s_per_rad; })
        .only_when = elastic;
  }
  return rows;
}

// "(0, 45]" with both bounds, "> 0" with one; empty without.
template <typename Format>
std::string interval(const Range& range, Format format, bool infinite_bounds) {
  const auto& lower = range.lower;
  const auto& upper = range.upper;
  if (!lower && !upper) return {};
  if ((lower && upper) || infinite_bounds) {
    std::string text = lower ? (lower->closed ? "[" : "(") + format(lower->value) : "(-inf";
    text += ", ";
    text += upper ? format(upper->value) + (upper->closed ? "]" : ")") : "inf)";
    return text;
  }
  if (lower) return (lower->closed ? ">= " : "> ") + format(lower->value);
  return (upper->closed ? "<= " : "< ") + format(upper->value);
}

std::string choice_names(const Field& field) {
  std::string list;
  for (const ChoiceName& c : field.choices) {
    if (!c.has_text) continue;
    if (!list.empty()) list += ", ";
    list += "\"" + std::string(c.name) + "\"";
  }
  return list;
}

const ChoiceName* choice_of(const Field& field, double code) {
  for (const ChoiceName& c : field.choices) {
    if (c.code == code) return &c;
  }
  return nullptr;
}

bool in_range(const Range& range, double value) {
  if (!std::isfinite(value)) return false;
  if (range.lower &&
      (range.lower->closed ? value < range.lower->value : value <= range.lower->value)) {
    return false;
  }
  if (range.upper &&
      (range.upper->closed ? value > range.upper->value : value >= range.upper->value)) {
    return false;
  }
  return true;
}

// The value in SI as a library user set it, for messages.
std::string si_text(const Field& field, double value) {
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::quantity_list:
      return shortest_decimal(value) + " " + std::string(units_of(field.dimension).front().symbol);
    case FieldKind::choice:
    case FieldKind::on_off:
      if (const ChoiceName* c = choice_of(field, value)) return "\"" + std::string(c->name) + "\"";
      return "code " + shortest_decimal(value);
    default:
      return shortest_decimal(value);
  }
}

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

// A whole-text decimal number, or nothing.
std::optional<double> plain_number(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

const Field& field_or_throw(std::string_view key, std::string_view name) {
  if (const Field* field = find_field(key)) return *field;
  const std::optional<std::string> nearest = nearest_key(key);
  throw InputError(std::string(name.empty() ? "section.key" : name), std::string(key),
                   "a key of the case schema, as section.key (`gearimpact schema` lists them)",
                   nearest ? "did you mean " + *nearest + "?" : std::string());
}

// The rows of one [[faults]] table. Their slots read the first fault of a
// case: the reader and the writer pass each fault in a case of its own.
std::vector<Field> make_fault_schema() {
  std::vector<Field> rows;
  Rows r(rows, "faults");
  const auto fault = [](auto& c) -> auto& {
    return c.faults.front();
  };
  r.choice(
      "gear",
      {choice("pinion", Gear::one, "gear 1, the driving pinion"),
       choice("wheel", Gear::two, "gear 2")},
      true,
      "the gear the faulted tooth belongs to", [fault](auto& c) -> auto& { return fault(c).gear; });
  r.integer(
      "tooth", {closed(0.0), closed(kMostTeeth - 1.0), "and below the gear's number of teeth"},
      true,
      "the tooth's number in mesh order, 0 ... z-1 (docs/faults.md, Tooth identity); "
      "one fault per tooth",
      [fault](auto& c) -> auto& { return fault(c).tooth; });
  r.choice(
      "kind",
      {choice("root-crack", ToothKind::root_crack,
              "a crack from the root (Tian 2004; Chen & Shao 2011 across the face)"),
       choice("missing", ToothKind::missing, "the tooth is gone: its pair carries nothing"),
       choice("spall", ToothKind::spall,
              "a pit on one flank over part of the active profile and of the face"),
       choice("tip-chip", ToothKind::tip_chip,
              "the tooth above a radius gone over part of the face, from one edge")},
      true, "the tooth's fault", [fault](auto& c) -> auto& { return fault(c).state.kind; });
  const auto crack = [fault](auto& c) -> auto& {
    return fault(c).state.crack;
  };
  r.quantity(
       "depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "q of a uniform crack, q0 (at the start edge) of the width profiles; q sin nu < h_c, "
       "the half thickness where the crack starts",
       [crack](auto& c) -> auto& { return crack(c).depth_m; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.quantity(
       "angle", Dimension::angle, "deg", {open(0.0), closed(0.5 * pi), {}}, true,
       "nu, between the crack and the tooth centre line",
       [crack](auto& c) -> auto& { return crack(c).angle_rad; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.choice(
       "profile",
       {choice("uniform", CrackProfile::uniform, "q across the whole face"),
        choice("partial-width", CrackProfile::partial_width,
               "q0 sqrt((W_c - z) / W_c) up to width W_c"),
        choice("full-width", CrackProfile::full_width,
               "sqrt((q2^2 - q0^2) z / b + q0^2), q2 the end_depth")},
       false,
       "how the depth runs across the face", [crack](auto& c) -> auto& { return crack(c).profile; })
      .only_when = FieldCondition{"kind", {"root-crack"}};
  r.quantity(
       "end_depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "q2, the depth at the far edge of the face",
       [crack](auto& c) -> auto& { return crack(c).end_depth_m; })
      .only_when = FieldCondition{"profile", {"full-width"}};
  r.quantity(
       "width", Dimension::length, "mm", {open(0.0), {}, "and at most the face width"}, true,
       "W_c, how far across the face the crack runs",
       [crack](auto& c) -> auto& { return crack(c).width_m; })
      .only_when = FieldCondition{"profile", {"partial-width"}};
  Field& start = r.quantity(
      "start_radius", Dimension::length, "mm", {open(0.0), {}, {}}, false,
      "r_s, where the crack starts on the flank; potential-energy and ross-compatible only",
      [crack](auto& c) -> auto& { return crack(c).start_radius_m; });
  start.only_when = FieldCondition{"kind", {"root-crack"}};
  start.when_absent =
      "the fillet point whose tangent makes 30 deg with the centre line (potential-energy, "
      "ross-compatible); the base circle (yang-lin-1987)";
  // A spall and a chip (surface_faults.hpp). depth, width and start_radius
  // share their keys with the crack's rows: one row of a key applies to a
  // fault, by its kind (fault_row_applies).
  const auto spall = [fault](auto& c) -> auto& {
    return fault(c).state.spall;
  };
  r.quantity(
       "depth", Dimension::length, "mm", {closed(0.0), {}, {}}, true,
       "d_s, how deep the pit reaches into the tooth, normal to its centre line; below the "
       "half thickness of the tooth at the thinner end of the spall",
       [spall](auto& c) -> auto& { return spall(c).depth_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "width", Dimension::length, "mm", {open(0.0), {}, "and at most the face width"}, true,
       "b_s of a spall, b_k of a chip: how far across the face it runs, up to the face width "
       "(docs/faults.md: across the whole face its pair has no contact over the spall's band, "
       "or above the chip's radius)",
       [fault](auto& c) -> auto& {
         return fault(c).state.kind == ToothKind::tip_chip ? fault(c).state.chip.width_m
                                                           : fault(c).state.spall.width_m;
       })
      .only_when = FieldCondition{"kind", {"spall", "tip-chip"}};
  r.quantity(
       "start_radius", Dimension::length, "mm", {open(0.0), {}, "and on the active profile"}, true,
       "where the spall begins: the radius of its lower edge on the flank, on the active "
       "profile (from where the mating tip meets the flank to below the tip)",
       [spall](auto& c) -> auto& { return spall(c).start_radius_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "end_radius", Dimension::length, "mm", {open(0.0), {}, "above start_radius, up to the tip"},
       true, "where the spall ends: the radius of its upper edge on the flank",
       [spall](auto& c) -> auto& { return spall(c).end_radius_m; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.choice(
       "flank",
       {choice("drive", CrackFlank::loaded,
               "the flank that carries the load when the pinion drives (line of action N1)"),
        choice("coast", CrackFlank::unloaded, "the other flank (line of action N2)")},
       false,
       "the flank the pit is on: a contact on the other flank keeps its whole length, the "
       "sections lose the pit all the same",
       [spall](auto& c) -> auto& { return spall(c).flank; })
      .only_when = FieldCondition{"kind", {"spall"}};
  r.quantity(
       "radius", Dimension::length, "mm", {open(0.0), {}, "above the root, up to the tip"}, true,
       "r_k: the tooth above this radius is gone over the chip's width, on both flanks",
       [fault](auto& c) -> auto& { return fault(c).state.chip.radius_m; })
      .only_when = FieldCondition{"kind", {"tip-chip"}};
  return rows;
}

}  // namespace

namespace {

// The rows of train_schema(): plain Fields without a slot of SimulationCase.
std::vector<Field> make_train_schema() {
  std::vector<Field> rows;
  const auto row = [&rows](std::string_view section, std::string_view key, FieldKind kind,
                           bool required, std::string help) -> Field& {
    Field f;
    f.section = section;
    f.key = key;
    f.kind = kind;
    f.required = required;
    f.help = std::move(help);
    f.get = [](const SimulationCase&) { return std::numeric_limits<double>::quiet_NaN(); };
    f.set = [](SimulationCase&, double) {
      throw std::logic_error("a train row has no slot in SimulationCase");
    };
    rows.push_back(std::move(f));
    return rows.back();
  };
  const auto quantity = [&row](std::string_view section, std::string_view key, Dimension dimension,
                               std::string_view unit, Range range, std::string_view when_absent,
                               std::string help) -> Field& {
    Field& f = row(section, key, FieldKind::quantity, false, std::move(help));
    f.dimension = dimension;
    f.unit = unit;
    f.range = range;
    f.when_absent = when_absent;
    return f;
  };
  // A name addresses its table's keys (bodies.NAME.inertia): a dot would split it.
  constexpr std::string_view no_dot = "and no '.' (it addresses the table's keys)";
  row("bodies", "name", FieldKind::text, true, "the body's name, one no other body has")
      .range.note = no_dot;
  // The range of [shafts] motor_inertia: a watch's wheel to a mill's drive.
  quantity("bodies", "inertia", Dimension::moment_of_inertia, "kg*m^2",
           {closed(1e-12), closed(1e6), {}},
           "the disc of its gear in the first mesh that names it (required for a body no "
           "mesh names)",
           "J, the body's moment of inertia about its axis");
  quantity("bodies", "torque", Dimension::torque, "N*m", {}, "0",
           "a constant torque on the body, positive in the sense the body turns when the train "
           "runs forward (a load is negative)");
  quantity("bodies", "theta", Dimension::angle, "deg", {}, "0", "the body's initial angle");
  quantity("bodies", "w", Dimension::angular_velocity, "rad/s", {}, "0",
           "the body's initial speed, positive forward");
  row("meshes", "name", FieldKind::text, true, "the mesh's name, one no other mesh has")
      .range.note = no_dot;
  row("meshes", "body_a", FieldKind::text, true,
      "the name of the body that is the pair's gear 1 (its pinion: [gears] teeth1, faults' gear "
      "= \"pinion\")");
  row("meshes", "body_b", FieldKind::text, true,
      "the name of the body that is the pair's gear 2 (teeth2, gear = \"wheel\"); it turns "
      "forward when body_a does");
  Field& kind = row("shafts", "kind", FieldKind::choice, true,
                    "a rigid shaft makes its two bodies one (their inertias summed); a torsional "
                    "one is a spring T = k (theta_a - theta_b) on body_b");
  // The codes are the reader's (the case folder comes before the dynamics' TrainShaft).
  kind.choices = {{"rigid", 0, "the two bodies turn as one", true},
                  {"torsional", 1, "a torsional spring of the shaft's stiffness", true}};
  row("shafts", "body_a", FieldKind::text, true, "the name of one body on the shaft");
  row("shafts", "body_b", FieldKind::text, true, "the name of the other body on the shaft");
  // The range of [shafts] motor_stiffness: from nearly free to stiffer than any shaft.
  Field& stiffness =
      quantity("shafts", "stiffness", Dimension::torsional_stiffness, "N*m/rad",
               {closed(1e-3), closed(1e12), {}}, {}, "k, the torsional shaft's stiffness");
  stiffness.required = true;
  stiffness.only_when = FieldCondition{"kind", {"torsional"}};
  return rows;
}

}  // namespace

const std::vector<Field>& train_schema() {
  static const std::vector<Field> rows = make_train_schema();
  return rows;
}

const Field* find_train_field(std::string_view section_dot_key) {
  for (const Field& field : train_schema()) {
    if (field.name() == section_dot_key) return &field;
  }
  return nullptr;
}

const std::vector<Field>& fault_schema() {
  static const std::vector<Field> rows = make_fault_schema();
  return rows;
}

bool fault_row_applies(const Field& field, const SimulationCase& one_fault) {
  if (!field.only_when) return true;
  for (const Field& selector : fault_schema()) {
    if (selector.key != field.only_when->key) continue;
    if (!fault_row_applies(selector, one_fault)) return false;
    const double code = selector.get(one_fault);
    for (const ChoiceName& c : selector.choices) {
      if (c.code != code) continue;
      const auto& choices = field.only_when->choices;
      return std::find(choices.begin(), choices.end(), c.name) != choices.end();
    }
  }
  return false;
}

std::string FieldCondition::text() const {
  std::string list;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) list += i + 1 == choices.size() ? " or " : ", ";
    list += "\"" + std::string(choices[i]) + "\"";
  }
  return std::string(key) + " = " + list;
}

std::string Field::name() const {
  if (section.empty()) return std::string(key);
  return std::string(section) + "." + std::string(key);
}

const std::vector<Field>& case_schema() {
  static const std::vector<Field> rows = make_schema();
  return rows;
}

const Field* find_field(std::string_view section_dot_key) {
  const std::size_t dot = section_dot_key.find('.');
  const std::string_view section =
      dot == std::string_view::npos ? std::string_view() : section_dot_key.substr(0, dot);
  const std::string_view key =
      dot == std::string_view::npos ? section_dot_key : section_dot_key.substr(dot + 1);
  for (const Field& field : case_schema()) {
    if (field.section == section && field.key == key) return &field;
  }
  return nullptr;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Rows of the dynamic programme: the previous two and the current.
  std::vector<std::size_t> before(b.size() + 1);
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
        current[j] = std::min(current[j], before[j - 2] + 1);
      }
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::optional<std::string> nearest_key(std::string_view written) {
  const std::size_t dot = written.find('.');
  const std::string_view bare = dot == std::string_view::npos ? written : written.substr(dot + 1);
  std::optional<std::string> best;
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  for (const Field& field : case_schema()) {
    const std::string name = field.name();
    // A key under the wrong section costs one edit more than its own typos.
    const std::size_t d =
        std::min(edit_distance(written, name), edit_distance(bare, field.key) + 1);
    if (d < fewest) {
      fewest = d;
      best = name;
    }
  }
  if (!best || fewest == 0 || 3 * fewest > std::max<std::size_t>(written.size(), 3)) return {};
  return best;
}

std::vector<std::string_view> schema_sections() {
  std::vector<std::string_view> sections;
  for (const Field& field : case_schema()) {
    if (!field.section.empty() &&
        std::find(sections.begin(), sections.end(), field.section) == sections.end()) {
      sections.push_back(field.section);
    }
  }
  return sections;
}

bool absent(const Field& field, const SimulationCase& c) {
  return !field.when_absent.empty() && field.kind != FieldKind::text && std::isnan(field.get(c));
}

bool applies(const Field& field, const SimulationCase& c) {
  if (!field.only_when) return true;
  for (const Field& selector : case_schema()) {
    if (selector.section == field.section && selector.key == field.only_when->key) {
      const ChoiceName* chosen = choice_of(selector, selector.get(c));
      const auto& choices = field.only_when->choices;
      return chosen != nullptr &&
             std::find(choices.begin(), choices.end(), chosen->name) != choices.end();
    }
  }
  return false;
}

std::string allowed_text(const Field& field) {
  std::string text;
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::quantity_list: {
      const std::string si(units_of(field.dimension).front().symbol);
      if (field.kind == FieldKind::quantity_list) {
        text = "a list of at most " + std::to_string(field.most_values) + " values, each ";
      }
      const std::string bounds = interval(
          field.range, [](double x) { return shortest_decimal(x); }, false);
      text += std::string(describe(field.dimension));
      if (bounds.empty()) {
        text += ", any finite value";
        break;
      }
      text += (field.range.lower && field.range.upper ? " in " : " ") + bounds + " " + si;
      // The same bounds in the unit files are written in, where that differs
      // and says more than 0.
      const bool telling = (field.range.lower && field.range.lower->value != 0.0) ||
                           (field.range.upper && field.range.upper->value != 0.0);
      if (field.unit != si && telling) {
        bool exact = true;
        const std::string suffix = " " + std::string(field.unit);
        const std::string readable = interval(
            field.range,
            [&](double x) {
              std::string q = format_quantity(x, field.dimension, field.unit);
              if (q.size() < suffix.size() ||
                  q.compare(q.size() - suffix.size(), suffix.size(), suffix) != 0) {
                exact = false;
                return q;
              }
              return q.substr(0, q.size() - suffix.size());
            },
            false);
        if (exact) text += ", i.e. " + readable + suffix;
      }
      break;
    }
    case FieldKind::number: {
      const std::string bounds = interval(field.range, bound_text, true);
      text = bounds.empty() ? "any finite number" : bounds;
      break;
    }
    case FieldKind::number_list: {
      const std::string bounds = interval(field.range, bound_text, true);
      text = "a list of at most " + std::to_string(field.most_values) + " plain numbers, each " +
             (bounds.empty() ? "finite" : "in " + bounds);
      break;
    }
    case FieldKind::integer:
      text = "an integer in " +
             interval(
                 field.range, [](double x) { return std::to_string(static_cast<long long>(x)); },
                 true);
      break;
    case FieldKind::choice:
    case FieldKind::on_off:
      text = "one of " + choice_names(field);
      break;
    case FieldKind::text:
      text = "at most " + std::to_string(kLongestName) +
             " letters, digits, '_', '-', '.' (it names output files)";
      break;
  }
  if (!field.range.note.empty()) text += ", " + std::string(field.range.note);
  return text;
}

std::string value_text(const Field& field, const SimulationCase& c, bool readable_unit) {
  if (field.kind == FieldKind::text) return "\"" + field.get_text(c) + "\"";
  if (field.kind == FieldKind::quantity_list) {
    const std::string_view unit =
        readable_unit ? field.unit : units_of(field.dimension).front().symbol;
    std::string text = "[";
    for (double value : field.get_list(c)) {
      if (text.size() > 1) text += ", ";
      text += "\"" + format_quantity(value, field.dimension, unit) + "\"";
    }
    return text + "]";
  }
  if (field.kind == FieldKind::number_list) {
    std::string text = "[";
    for (double value : field.get_list(c)) {
      if (text.size() > 1) text += ", ";
      // TOML needs a point or an exponent to read a float back as one.
      std::string number = shortest_decimal(value);
      if (number.find_first_of(".e") == std::string::npos) number += ".0";
      text += number;
    }
    return text + "]";
  }
  const double value = field.get(c);
  switch (field.kind) {
    case FieldKind::quantity: {
      const std::string_view unit =
          readable_unit ? field.unit : units_of(field.dimension).front().symbol;
      return "\"" + format_quantity(value, field.dimension, unit) + "\"";
    }
    case FieldKind::number: {
      // TOML needs a point or an exponent to read a float back as one.
      std::string text = shortest_decimal(value);
      if (std::isfinite(value) && text.find_first_of(".e") == std::string::npos) text += ".0";
      return text;
    }
    case FieldKind::integer:
      return std::to_string(static_cast<long long>(value));
    default: {
      const ChoiceName* chosen = choice_of(field, value);
      if (chosen == nullptr || !chosen->has_text) {
        throw InputError(
            field.name(), chosen != nullptr ? std::string(chosen->name) : si_text(field, value),
            "one of " + choice_names(field) + " in a case file" +
                (chosen != nullptr ? " (" + std::string(chosen->meaning) + ")" : std::string()));
      }
      return "\"" + std::string(chosen->name) + "\"";
    }
  }
}

std::string default_text(const Field& field) {
  if (field.required) return "required";
  if (field.kind == FieldKind::text) return "the file's stem";
  // A [[faults]] row reads the case's first fault: a default one.
  SimulationCase defaults;
  if (field.section == "faults") defaults.faults.resize(1);
  if (absent(field, defaults)) return "absent: " + std::string(field.when_absent);
  return value_text(field, defaults);
}

void check_value(const Field& field, double value, std::string_view name,
                 std::string_view written) {
  bool ok = false;
  switch (field.kind) {
    case FieldKind::quantity:
    case FieldKind::number:
      ok = in_range(field.range, value);
      break;
    case FieldKind::integer:
      ok = in_range(field.range, value) && value == std::floor(value);
      break;
    case FieldKind::choice:
    case FieldKind::on_off:
      ok = choice_of(field, value) != nullptr;
      break;
    case FieldKind::text:
    case FieldKind::quantity_list:
    case FieldKind::number_list:
      break;
  }
  if (!ok) throw InputError(std::string(name), std::string(written), allowed_text(field));
}

void check_text(const Field& field, const std::string& value, std::string_view name) {
  if (value.size() > kLongestName || !std::all_of(value.begin(), value.end(), is_name_character)) {
    throw InputError(std::string(name), "\"" + value + "\"", allowed_text(field));
  }
}

std::optional<std::string> plain_speed_warning(const Field& field, std::string_view value_text,
                                               std::string_view name) {
  if (field.kind != FieldKind::quantity || field.dimension != Dimension::angular_velocity) {
    return std::nullopt;
  }
  const std::optional<double> value = plain_number(value_text);
  if (!value || *value == 0.0 || !std::isfinite(*value)) return std::nullopt;
  const std::string written(trim(value_text));
  const UnitList units = units_of(Dimension::angular_velocity);
  const auto rpm =
      std::find_if(units.begin(), units.end(), [](const Unit& u) { return u.symbol == "rpm"; });
  // A speed near the largest double has no finite value in rpm: said without it.
  const double in_rpm = *value / rpm->factor;
  char rpm_text[48] = "";
  if (std::isfinite(in_rpm)) std::snprintf(rpm_text, sizeof rpm_text, " (%.6g rpm)", in_rpm);
  return std::string(name) + " = " + written + " is read as " + written + " rad/s" + rpm_text +
         "; write \"" + written + " rad/s\" or \"" + written + " rpm\" to say which";
}

double parse_value(const Field& field, std::string_view value_text, std::string_view name) {
  const std::string written(value_text);
  double value = 0.0;
  switch (field.kind) {
    case FieldKind::quantity:
      if (const std::optional<double> si = plain_number(value_text)) {
        value = *si;
      } else {
        value = parse_quantity(value_text, field.dimension, name);
      }
      break;
    case FieldKind::number:
    case FieldKind::integer: {
      const std::optional<double> number = plain_number(value_text);
      if (!number) {
        throw InputError(std::string(name), written,
                         "a plain number (no unit) in " + allowed_text(field));
      }
      value = *number;
      break;
    }
    case FieldKind::choice:
    case FieldKind::on_off: {
      const auto chosen = std::find_if(
          field.choices.begin(), field.choices.end(),
          [&](const ChoiceName& c) { return c.has_text && c.name == trim(value_text); });
      if (chosen == field.choices.end()) {
        throw InputError(std::string(name), written, allowed_text(field));
      }
      value = chosen->code;
      break;
    }
    case FieldKind::text:
      throw InputError(std::string(name), written, "a name: set it with set_field");
    case FieldKind::quantity_list:
    case FieldKind::number_list:
      throw InputError(std::string(name), written, "a list: read it with parse_list");
  }
  // A plain number of a quantity is in SI; where files write another unit
  // (an angle in deg), a refused one that the range takes in that unit was
  // most likely meant in it: the message says how to write it.
  if (field.kind == FieldKind::quantity && plain_number(value_text) &&
      !in_range(field.range, value)) {
    const UnitList units = units_of(field.dimension);
    const auto readable = std::find_if(units.begin(), units.end(),
                                       [&](const Unit& u) { return u.symbol == field.unit; });
    if (readable != units.begin() && readable != units.end() &&
        in_range(field.range, value * readable->factor)) {
      throw InputError(std::string(name), written,
                       allowed_text(field) + "; a plain number is read in " +
                           std::string(units.front().symbol) + ": \"" +
                           std::string(trim(value_text)) + " " + std::string(field.unit) +
                           "\" gives it in " + std::string(field.unit));
    }
  }
  check_value(field, value, name, written);
  return value;
}

void check_list(const Field& field, const std::vector<double>& values, std::string_view name) {
  if (values.size() > field.most_values) {
    throw InputError(std::string(name), std::to_string(values.size()) + " values",
                     allowed_text(field));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!in_range(field.range, values[i])) {
      throw InputError(std::string(name) + "[" + std::to_string(i) + "]", si_text(field, values[i]),
                       allowed_text(field));
    }
  }
}

std::vector<double> parse_list(const Field& field, std::string_view value_text,
                               std::string_view name) {
  std::vector<double> values;
  if (trim(value_text).empty()) return values;
  std::string_view rest = value_text;
  for (;;) {
    const std::size_t comma = rest.find(',');
    const std::string_view item = trim(rest.substr(0, comma));
    const std::string item_name = std::string(name) + "[" + std::to_string(values.size()) + "]";
    double value = 0.0;
    if (const std::optional<double> si = plain_number(item)) {
      value = *si;
    } else if (field.kind == FieldKind::number_list) {
      throw InputError(item_name, std::string(item),
                       "a plain number (no unit): " + allowed_text(field));
    } else {
      value = parse_quantity(item, field.dimension, item_name);
    }
    if (!in_range(field.range, value)) {
      throw InputError(item_name, std::string(item), allowed_text(field));
    }
    values.push_back(value);
    if (values.size() > field.most_values) {
      throw InputError(std::string(name),
                       "more than " + std::to_string(field.most_values) + " values",
                       allowed_text(field));
    }
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return values;
}

void set_field(SimulationCase& c, std::string_view section_dot_key, std::string_view value_text,
               std::string_view name_in_messages) {
  const Field& field = field_or_throw(section_dot_key, name_in_messages);
  const std::string name = name_in_messages.empty() ? field.name() : std::string(name_in_messages);
  if (field.kind == FieldKind::text) {
    const std::string value(trim(value_text));
    check_text(field, value, name);
    field.set_text(c, value);
    return;
  }
  if (!applies(field, c)) {
    throw InputError(name, std::string(value_text),
                     "nothing: " + field.name() + " is used only with " +
                         std::string(field.section) + "." + field.only_when->text() +
                         " (set that first)");
  }
  if (is_list(field.kind)) {
    field.set_list(c, parse_list(field, value_text, name));
    return;
  }
  field.set(c, parse_value(field, value_text, name));
}

double get_numeric_field(const SimulationCase& c, std::string_view section_dot_key) {
  const Field& field = field_or_throw(section_dot_key, {});
  if (field.kind != FieldKind::quantity && field.kind != FieldKind::number &&
      field.kind != FieldKind::integer) {
    const char* what = field.kind == FieldKind::text ? "name"
                       : is_list(field.kind)         ? "list"
                                                     : "choice";
    throw InputError(field.name(), "(a " + std::string(what) + ")",
                     "a quantity, number or integer key for get_numeric_field");
  }
  return field.get(c);
}

namespace {

// The rows of `section` that `holds` accepts, checked in `c`; errors name
// the key alone, as the library's types name their fields.
template <typename Holds>
void check_rows(const SimulationCase& c, std::string_view section, Holds holds,
                Problems& problems) {
  for (const Field& field : case_schema()) {
    if (field.section != section || !holds(field) || absent(field, c)) continue;
    const double value = field.get(c);
    problems.collect([&] { check_value(field, value, field.key, si_text(field, value)); });
  }
}

// The [model] rows that describe the StiffnessModel.
bool is_stiffness_row(const Field& field) {
  for (std::string_view key : {"stiffness_model", "moment_sign", "stiffness_method", "xform_rule",
                               "stiffness_tolerance", "spall_reading"}) {
    if (field.key == key) return true;
  }
  for (const TermInfo& t : kTerms) {
    if (field.key == t.switch_key) return true;
  }
  return false;
}

}  // namespace

void validate(const GearPair& pair) {
  SimulationCase c;
  c.gears = pair;
  Problems problems;
  check_rows(
      c, "gears", [](const Field&) { return true; }, problems);
  // The relations only between values in their ranges.
  if (problems.empty()) problems.collect([&] { validate_geometry(pair); });
  problems.throw_if_any();
}

void validate(const StiffnessModel& model) {
  SimulationCase c;
  c.model.stiffness = model;
  Problems problems;
  check_rows(c, "model", is_stiffness_row, problems);
  if (problems.empty()) problems.collect([&] { validate_terms(model); });
  if (problems.empty()) problems.collect([&] { check_spall_reading(model); });
  problems.throw_if_any();
}

namespace {

// True when a key of `failed` starts with `prefix` ("gears." or "gears.module").
bool any_failed(const std::vector<std::string>& failed, std::string_view prefix) {
  return std::any_of(failed.begin(), failed.end(), [&](const std::string& key) {
    return key.compare(0, prefix.size(), prefix) == 0;
  });
}

// At most kMostSteps steps over the run, unless its end time or step is refused already.
void most_steps_problem(const IntegratorSettings& s, const std::vector<std::string>& failed,
                        Problems& problems) {
  const double most_steps = static_cast<double>(kMostSteps);
  if (!any_failed(failed, "integrator.end_time") && !any_failed(failed, "integrator.step") &&
      s.end_time_s / s.step_s > most_steps) {
    problems.add(range_problem("integrator.end_time", format_number(s.end_time_s) + " s",
                               "at most " + bound_text(most_steps) +
                                   " steps of integrator.step = " + format_number(s.step_s) +
                                   " s, i.e. end_time <= " + format_number(most_steps * s.step_s) +
                                   " s"));
  }
}

}  // namespace

void validate(const IntegratorSettings& integrator) {
  SimulationCase c;
  c.integrator = integrator;
  Problems problems;
  std::vector<std::string> failed;
  for (const Field& field : case_schema()) {
    if (field.section != "integrator" || !applies(field, c) || absent(field, c)) continue;
    const bool ok = problems.collect([&] {
      const double value = field.get(c);
      check_value(field, value, field.name(), si_text(field, value));
    });
    if (!ok) failed.push_back(field.name());
  }
  most_steps_problem(integrator, failed, problems);
  problems.throw_if_any();
}

namespace {

// The [[faults]] key a crack's refusal by the library names (root_crack.hpp).
std::string fault_key_of(const std::string& library_name) {
  if (library_name == "crack end depth q2") return "end_depth";
  if (library_name == "crack width W_c") return "width";
  if (library_name == "crack angle nu") return "angle";
  if (library_name == "crack start radius r_s") return "start_radius";
  return "depth";
}

// A length as the [[faults]] rows write it.
std::string in_mm(double length_m) {
  return format_quantity(length_m, Dimension::length, "mm");
}

// The [[faults]] key a spall's or a chip's refusal by the library names
// (surface_faults.hpp).
std::string surface_fault_key_of(const std::string& library_name) {
  if (library_name == "spall start radius") return "start_radius";
  if (library_name == "spall end radius") return "end_radius";
  if (library_name == "chip radius r_k") return "radius";
  if (library_name == "spall depth d_s") return "depth";
  return "width";
}

// The checks of a spall or a chip that need the gears and the model, each
// naming its key with the limit in mm: the spall's edges on the active
// profile of its tooth (where the mating tip meets the flank up to the tip),
// its depth below the half thickness at its thinner end, the chip's radius
// above the root (the base circle of the paper's tooth) up to the tip, and a
// width up to the face width. Then the library's own checks (place_spall,
// place_chip), should they find more.
void surface_fault_problems(const SimulationCase& c, const ToothFault& f, const std::string& name,
                            Problems& problems) {
  const GearPair& pair = c.gears;
  const StiffnessModelKind kind = c.model.stiffness.kind;
  const std::string gear = f.gear == Gear::one ? "pinion" : "wheel";
  const std::size_t before = problems.list().size();
  const double b = pair.face_width_m;
  const double width =
      f.state.kind == ToothKind::spall ? f.state.spall.width_m : f.state.chip.width_m;
  if (!(width <= b)) {
    problems.add(range_problem(name + ".width", in_mm(width),
                               "at most the face width b = " + in_mm(b) +
                                   " (gears.face_width): a fault runs across the face at most"));
  }
  const double rb = base_radius(pair, f.gear);
  const double tip = tip_radius(pair, f.gear);
  if (f.state.kind == ToothKind::spall) {
    const Spall& spall = f.state.spall;
    // The active profile: the roll distances of the contact segment's ends on
    // this tooth (the wheel's measured from C2).
    const ContactSegment segment = contact_segment(pair);
    const double lp = line_of_action_length(pair);
    const double sap =
        radius_at_roll_distance(rb, f.gear == Gear::one ? segment.start_m : lp - segment.end_m);
    const std::string where =
        "on the active profile of the " + gear + " tooth, from r = " + in_mm(sap) +
        " (where the mating tip meets the flank) to the tip r = " + in_mm(tip);
    bool edges = true;
    if (!(spall.start_radius_m >= sap && spall.start_radius_m < tip)) {
      edges = false;
      problems.add(range_problem(name + ".start_radius", in_mm(spall.start_radius_m),
                                 "[" + in_mm(sap) + ", " + in_mm(tip) + "): " + where));
    } else if (!(spall.end_radius_m > spall.start_radius_m && spall.end_radius_m <= tip)) {
      edges = false;
      problems.add(range_problem(name + ".end_radius", in_mm(spall.end_radius_m),
                                 "(" + in_mm(spall.start_radius_m) + ", " + in_mm(tip) +
                                     "]: above start_radius, " + where));
    }
    if (edges) {
      const double x1 = flank_half_thickness(pair, f.gear, kind, spall.start_radius_m);
      const double x2 = flank_half_thickness(pair, f.gear, kind, spall.end_radius_m);
      const double x = std::min(x1, x2);
      const double r = x1 <= x2 ? spall.start_radius_m : spall.end_radius_m;
      if (!(spall.depth_m < x)) {
        problems.add(range_problem(name + ".depth", in_mm(spall.depth_m),
                                   "below x = " + in_mm(x) + ", the half thickness of the " + gear +
                                       " tooth at r = " + in_mm(r) +
                                       ", the thinner end of the spall: the pit may not reach "
                                       "the tooth's centre line"));
      }
    }
  } else {
    const bool paper = kind == StiffnessModelKind::yang_lin_1987;
    double root = rb;
    if (!paper) {
      const RackGearPairGeometry geometry = rack_gear_pair_geometry(pair);
      root = (f.gear == Gear::one ? geometry.gear1 : geometry.gear2).root_radius_m;
    }
    const double r_k = f.state.chip.radius_m;
    if (!(r_k > root && r_k <= tip)) {
      problems.add(range_problem(
          name + ".radius", in_mm(r_k),
          "(" + in_mm(root) + ", " + in_mm(tip) + "]: above the " +
              (paper ? "base circle (the paper's tooth starts there)" : "root circle") +
              ", up to the tip of the " + gear + " tooth"));
    }
  }
  if (problems.list().size() != before) return;
  try {
    check_tooth_faults(pair, c.model.stiffness, {f});
  } catch (const InputError& e) {
    for (const Problem& p : e.problems()) {
      problems.add(p.renamed(name + "." + surface_fault_key_of(p.field), p.value));
    }
  }
}

// The checks of [[faults]] that need the gears and the model: a constant
// stiffness has no teeth, a tooth number below the gear's teeth, one fault per
// tooth, and a crack that fits its tooth (place_crack).
void fault_problems(const SimulationCase& c, const std::vector<std::string>& failed,
                    Problems& problems) {
  if (c.faults.empty() || any_failed(failed, "faults")) return;
  if (c.model.mesh_stiffness == MeshStiffnessMode::constant) {
    if (!any_failed(failed, "model.mesh_stiffness")) {
      problems.add(range_problem("model.mesh_stiffness", "\"constant\"",
                                 "\"time-varying\" in a case with [[faults]]: a constant "
                                 "stiffness has no teeth to fault"));
    }
    return;
  }
  if (any_failed(failed, "gears.") || any_failed(failed, "model.")) return;
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    const ToothFault& f = c.faults[i];
    const std::string name = "faults[" + std::to_string(i) + "]";
    const int z = teeth(c.gears, f.gear);
    const std::string gear = f.gear == Gear::one ? "pinion" : "wheel";
    if (f.tooth >= z) {
      problems.add(range_problem(name + ".tooth", std::to_string(f.tooth),
                                 "0 ... " + std::to_string(z - 1) + ", the " + std::to_string(z) +
                                     " teeth of the " + gear + " (gears.teeth" +
                                     (f.gear == Gear::one ? "1" : "2") + ")"));
      continue;
    }
    bool repeated = false;
    for (std::size_t j = 0; j < i && !repeated; ++j) {
      if (c.faults[j].gear == f.gear && c.faults[j].tooth == f.tooth) {
        repeated = true;
        problems.add(range_problem(name + ".tooth", std::to_string(f.tooth),
                                   "a " + gear + " tooth without a fault: faults[" +
                                       std::to_string(j) + "] is on it already (one per tooth)"));
      }
    }
    if (repeated) continue;
    if (f.state.kind == ToothKind::spall || f.state.kind == ToothKind::tip_chip) {
      surface_fault_problems(c, f, name, problems);
      continue;
    }
    if (f.state.kind != ToothKind::root_crack) continue;
    try {
      check_tooth_faults(c.gears, c.model.stiffness, {f});
    } catch (const InputError& e) {
      for (const Problem& p : e.problems()) {
        problems.add(p.renamed(name + "." + fault_key_of(p.field), p.value));
      }
    }
  }
  // A gear with every tooth missing has no tooth left to carry the load: no
  // pair is ever loaded, so a run would only drift and the STE is undefined.
  for (const Gear gear : {Gear::one, Gear::two}) {
    const int z = teeth(c.gears, gear);
    std::vector<bool> missing(static_cast<std::size_t>(std::max(z, 0)), false);
    for (const ToothFault& f : c.faults) {
      if (f.gear == gear && f.state.kind == ToothKind::missing && f.tooth >= 0 && f.tooth < z) {
        missing[static_cast<std::size_t>(f.tooth)] = true;
      }
    }
    if (z > 0 && std::all_of(missing.begin(), missing.end(), [](bool m) { return m; })) {
      const std::string which = gear == Gear::one ? "pinion" : "wheel";
      problems.add(range_problem("faults",
                                 "all " + std::to_string(z) + " " + which + " teeth missing",
                                 "at least one " + which +
                                     " tooth not missing: with every tooth missing no tooth is "
                                     "left to carry the load"));
    }
  }
}

}  // namespace

void relation_problems(const SimulationCase& c, const std::vector<std::string>& failed,
                       Problems& problems) {
  bool geometry_valid = false;
  if (!any_failed(failed, "gears.")) {
    try {
      validate_geometry(c.gears);
      geometry_valid = true;
    } catch (const InputError& e) {
      for (const Problem& p : e.problems()) problems.add(p.renamed("gears." + p.field, p.value));
    }
    // B is half the total play, and the play 2B fits in a tooth space: half
    // the circular pitch, pi m / 2, for teeth of standard thickness.
    if (const double most = pi * c.gears.module_m / 4.0; c.gears.backlash_m > most) {
      problems.add(range_problem("gears.backlash", format_number(c.gears.backlash_m) + " m",
                                 "at most pi m / 4 = " + format_number(most) +
                                     " m: B is half the play, and the play fits in a tooth space "
                                     "of half the circular pitch"));
    }
  }
  if (!any_failed(failed, "model.")) {
    problems.collect([&] { validate_terms(c.model.stiffness, "model"); });
    problems.collect([&] { check_spall_reading(c.model.stiffness, "model"); });
  }
  // The diameters of a relief against the active profile need a valid pair.
  if (geometry_valid && !any_failed(failed, "modifications.")) {
    problems.collect([&] { validate_modifications(c.gears, c.modifications); });
  }
  const std::array<std::pair<const char*, const Torque*>, 2> torques{
      {{"torque1", &c.torque1}, {"torque2", &c.torque2}}};
  for (const auto& [name, torque] : torques) {
    if (any_failed(failed, std::string(name) + ".")) continue;
    if (torque->kind == Torque::Kind::user && !torque->user) {
      problems.add(range_problem(std::string(name) + ".user", "empty", "a callable T(t_s) in N m"));
    }
    if (torque->kind == Torque::Kind::harmonic) {
      // One harmonic is one element of each list.
      const std::size_t n = torque->harmonic_amplitudes_n_m.size();
      const std::array<std::pair<const char*, std::size_t>, 2> others{
          {{"angular_frequencies", torque->harmonic_angular_frequencies_rad_per_s.size()},
           {"phases", torque->harmonic_phases_rad.size()}}};
      for (const auto& [key, size] : others) {
        if (size != n) {
          problems.add(range_problem(std::string(name) + "." + key,
                                     std::to_string(size) + " values",
                                     "as many values as " + std::string(name) + ".amplitudes (" +
                                         std::to_string(n) + ")"));
        }
      }
    }
    // The section's name as a copy: a lambda may not capture a structured binding in C++17.
    const std::string section = std::string(name) + ".";
    const auto check_profile = [&](const char* times_key, const std::vector<double>& times,
                                   const char* values_key, const std::size_t values,
                                   bool steps_allowed) {
      if (times.size() != values) {
        problems.add(range_problem(section + values_key, std::to_string(values) + " values",
                                   "as many values as " + section + times_key + " (" +
                                       std::to_string(times.size()) + ")"));
        return false;
      }
      for (std::size_t i = 1; i < times.size(); ++i) {
        const bool ok = steps_allowed ? times[i] >= times[i - 1] : times[i] > times[i - 1];
        if (ok) continue;
        problems.add(range_problem(
            section + times_key + "[" + std::to_string(i) + "]", format_number(times[i]) + " s",
            (steps_allowed ? "at least the time before it, " : "more than the time before it, ") +
                format_number(times[i - 1]) + " s" +
                (steps_allowed ? std::string()
                               : std::string(": a kinematic driver cannot step its speed (it "
                                             "would need an infinite torque); "
                                             "kind = \"speed-controlled\" may step its "
                                             "reference"))));
        return false;
      }
      return true;
    };
    if (torque->kind == Torque::Kind::profile) {
      if (torque->profile_times_s.empty()) {
        problems.add(range_problem(std::string(name) + ".profile_times", "0 values",
                                   "at least one point (one point is a constant torque)"));
      } else {
        check_profile("profile_times", torque->profile_times_s, "profile_torques",
                      torque->profile_torques_n_m.size(), true);
      }
    }
    bool profile_valid = true;
    if (has_speed_reference(*torque) && (!torque->speed_profile_speeds_rad_per_s.empty() ||
                                         !torque->speed_profile_times_s.empty())) {
      profile_valid =
          check_profile("speed_profile_times", torque->speed_profile_times_s,
                        "speed_profile_speeds", torque->speed_profile_speeds_rad_per_s.size(),
                        torque->kind == Torque::Kind::speed_controlled);
    }
    if (torque->kind == Torque::Kind::prescribed_speed) {
      // One order is one element of each list.
      const std::size_t n = torque->driver_speed_amplitudes_rad_per_s.size();
      const std::array<std::pair<const char*, std::size_t>, 2> others{
          {{"orders", torque->driver_orders.size()},
           {"phases", torque->harmonic_phases_rad.size()}}};
      bool lists_agree = true;
      for (const auto& [key, size] : others) {
        if (size != n) {
          lists_agree = false;
          problems.add(range_problem(std::string(name) + "." + key,
                                     std::to_string(size) + " values",
                                     "as many values as " + std::string(name) +
                                         ".speed_amplitudes (" + std::to_string(n) + ")"));
        }
      }
      // The driver sets w1(0); a different initial.w1 would be ignored.
      if (lists_agree && profile_valid && !any_failed(failed, "initial.w1")) {
        const double w0 = driver_speed_at(*torque, 0.0);
        const double written = c.initial.w1_rad_per_s;
        if (std::fabs(written - w0) > 1e-9 * std::fabs(w0)) {
          problems.add(range_problem(
              "initial.w1", format_number(written) + " rad/s",
              "the driver's w1(0) = mean_speed + sum_i speed_amplitudes[i] sin(phases[i]) = " +
                  format_number(w0) +
                  " rad/s (to 1e-9 of it), as [torque1] kind = \"prescribed-speed\" prescribes "
                  "w1",
              "initial.w1 = \"" + format_number(w0) + " rad/s\""));
        }
      }
    }
  }
  fault_problems(c, failed, problems);
  if (c.model.friction_law == FrictionLaw::table &&
      !any_failed(failed, "model.friction_table_slide_to_roll") &&
      !any_failed(failed, "model.friction_table_coefficients")) {
    problems.collect([&] {
      const FrictionTable& table = c.model.friction_table;
      if (table.slide_to_roll.empty()) {
        throw InputError("model.friction_table_slide_to_roll", "0 values",
                         "at least one slide-to-roll ratio (one entry is a constant f)");
      }
      if (table.coefficient.size() != table.slide_to_roll.size()) {
        throw InputError("model.friction_table_coefficients",
                         std::to_string(table.coefficient.size()) + " values",
                         "as many values as model.friction_table_slide_to_roll (" +
                             std::to_string(table.slide_to_roll.size()) + ")");
      }
      for (std::size_t i = 1; i < table.slide_to_roll.size(); ++i) {
        if (!(table.slide_to_roll[i] > table.slide_to_roll[i - 1])) {
          throw InputError("model.friction_table_slide_to_roll[" + std::to_string(i) + "]",
                           shortest_decimal(table.slide_to_roll[i]),
                           "a value above the one before it, " +
                               shortest_decimal(table.slide_to_roll[i - 1]) +
                               ": the ratios are strictly increasing");
        }
      }
    });
  }
  most_steps_problem(c.integrator, failed, problems);
}

void validate_relations(const SimulationCase& c) {
  Problems problems;
  relation_problems(c, {}, problems);
  problems.throw_if_any();
}

void validate_run_keys(const SimulationCase& c) {
  Problems problems;
  for (const std::string& key : c.run_keys_absent) {
    const Field* field = find_field(key);
    problems.add(refused_problem(
        key, "absent",
        "a run needs it, and this case is a gear pair alone (the stiffness, STE, ISO 6336, modes "
        "and report need no more)",
        field != nullptr ? allowed_text(*field) : std::string("a value"),
        "give " + key + " (and the other keys of a run: the torques and integrator.end_time)"));
  }
  problems.throw_if_any();
}

void validate_fields(const SimulationCase& c) {
  Problems problems;
  std::vector<std::string> failed;
  for (const Field& field : case_schema()) {
    const bool ok = problems.collect([&] {
      if (field.kind == FieldKind::text) {
        check_text(field, field.get_text(c), field.name());
      } else if (is_list(field.kind)) {
        if (applies(field, c)) check_list(field, field.get_list(c), field.name());
      } else if (applies(field, c) && !absent(field, c)) {
        const double value = field.get(c);
        check_value(field, value, field.name(), si_text(field, value));
      }
    });
    if (!ok) failed.push_back(field.name());
  }
  relation_problems(c, failed, problems);
  problems.throw_if_any();
}

std::string case_key(const SimulationCase& c) {
  if (c.torque1.kind == Torque::Kind::user || c.torque2.kind == Torque::Kind::user) return {};
  std::string key;
  for (const Field& field : case_schema()) {
    if (field.section.empty() && field.key == "name") continue;
    if (!applies(field, c) || absent(field, c)) continue;
    key += field.name() + "=" + value_text(field, c, false) + "\n";
  }
  for (std::size_t i = 0; i < c.faults.size(); ++i) {
    SimulationCase one;
    one.faults = {c.faults[i]};
    for (const Field& field : fault_schema()) {
      if (!fault_row_applies(field, one) || absent(field, one)) continue;
      key += "faults[" + std::to_string(i) + "]." + std::string(field.key) + "=" +
             value_text(field, one, false) + "\n";
    }
  }
  return key;
}

std::string schema_markdown() {
  const auto cell = [](std::string text) {
    std::string escaped;
    for (char ch : text) {
      if (ch == '|') escaped += '\\';
      escaped += ch;
    }
    return escaped;
  };
  std::string table = "| key | unit | default | allowed | meaning |\n|---|---|---|---|---|\n";
  std::vector<const Field*> rows;
  for (const Field& field : case_schema()) rows.push_back(&field);
  for (const Field& field : fault_schema()) rows.push_back(&field);
  for (const Field& field : train_schema()) rows.push_back(&field);
  for (const Field* row : rows) {
    const Field& field = *row;
    std::string help(field.help);
    if (field.kind == FieldKind::choice) {
      for (const ChoiceName& c : field.choices) {
        if (c.has_text) help += "; \"" + std::string(c.name) + "\": " + std::string(c.meaning);
      }
    }
    if (field.only_when) help += " (only with " + field.only_when->text() + ")";
    const bool has_unit =
        field.kind == FieldKind::quantity || field.kind == FieldKind::quantity_list;
    const std::string unit = has_unit ? std::string(field.unit) : std::string("-");
    table += "| `" + field.name() + "` | " + cell(unit) + " | " + cell(default_text(field)) +
             " | " + cell(allowed_text(field)) + " | " + cell(help) + " |\n";
  }
  return table;
}

}  // namespace gearimpact
