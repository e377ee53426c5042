// The rows of [torque1] and [torque2]: the external torques, drivers and loads.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "schema_rows.hpp"

namespace gearimpact {

using namespace schema_detail;

namespace {

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

}  // namespace

void schema_detail::add_torque_rows(std::vector<Field>& rows) {
  add_torque(
      rows, "torque1", 1, [](auto& c) -> auto& { return c.torque1; });
  add_torque(
      rows, "torque2", 2, [](auto& c) -> auto& { return c.torque2; });
}

}  // namespace gearimpact
