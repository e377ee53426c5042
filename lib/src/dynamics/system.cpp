#include "gearimpact/dynamics/system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "gearimpact/contact/contact.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// Grazing contacts can have Vi -> 0, where D of (32) grows without bound while
// G = D delta d(delta)/dt stays finite; the floor keeps D finite.
constexpr double kSmallestImpactSpeed_m_s = 1e-9;

}  // namespace

double torque_at(const Torque& torque, double t_s) {
  switch (torque.kind) {
    case Torque::Kind::constant:
      return torque.constant_n_m;
    case Torque::Kind::sinusoidal:
      return torque.mean_n_m +
             torque.amplitude_n_m *
                 std::sin(torque.angular_frequency_rad_per_s * t_s + torque.phase_rad);
    case Torque::Kind::harmonic: {
      double sum = torque.mean_n_m;
      for (std::size_t i = 0; i < torque.harmonic_amplitudes_n_m.size(); ++i) {
        sum += torque.harmonic_amplitudes_n_m[i] *
               std::sin(torque.harmonic_angular_frequencies_rad_per_s[i] * t_s +
                        torque.harmonic_phases_rad[i]);
      }
      return sum;
    }
    case Torque::Kind::user:
      return torque.user(t_s);
    case Torque::Kind::profile:
      return profile_at(torque.profile_times_s, torque.profile_torques_n_m, t_s).value;
    case Torque::Kind::prescribed_speed:
    case Torque::Kind::drag:
    case Torque::Kind::speed_controlled:
    case Torque::Kind::induction_motor:
      // The driver's torque depends on the mesh force, the drag on w2, the
      // controller's and the motor's on the driven body's motion: the
      // systems' right-hand sides compute them from the state.
      break;
  }
  throw std::logic_error("torque_at of a torque that depends on the state");
}

double drag_torque_n_m(const Torque& drag, double w_rad_per_s) {
  return -(drag.drag_constant_n_m * std::tanh(w_rad_per_s / drag.drag_speed_scale_rad_per_s) +
           drag.drag_viscous_n_m_s * w_rad_per_s);
}

double mean_torque_n_m(const Torque& torque, const char* field) {
  switch (torque.kind) {
    case Torque::Kind::constant:
      return torque.constant_n_m;
    case Torque::Kind::sinusoidal:
    case Torque::Kind::harmonic:
      return torque.mean_n_m;
    case Torque::Kind::user:
      throw InputError(
          std::string(field) + ".kind", "user",
          "constant, sinusoidal or harmonic: the mean of a torque function is not known");
    case Torque::Kind::prescribed_speed:
    case Torque::Kind::drag:
    case Torque::Kind::speed_controlled:
    case Torque::Kind::induction_motor:
    case Torque::Kind::profile:
      break;
  }
  const char* kind = torque.kind == Torque::Kind::drag               ? "drag"
                     : torque.kind == Torque::Kind::speed_controlled ? "speed-controlled"
                     : torque.kind == Torque::Kind::induction_motor  ? "induction-motor"
                     : torque.kind == Torque::Kind::profile          ? "profile"
                                                                     : "prescribed-speed";
  throw InputError(std::string(field) + ".kind", kind,
                   "constant, sinusoidal or harmonic: a driver's, a controller's or a motor's "
                   "torque and a drag follow the motion, and a profile's mean depends on the "
                   "run's length, so their mean is not known before the run");
}

GearSystem::GearSystem(const SimulationCase& c, const StiffnessTable& table,
                       const RunControl& control)
    : table_(table), case_(c), layout_(c.gears, c.model.coast_phase) {
  const GearPair& g = c.gears;
  rb1_ = base_radius(g, Gear::one);
  rb2_ = base_radius(g, Gear::two);
  j1_ = moment_of_inertia(g, Gear::one);
  j2_ = moment_of_inertia(g, Gear::two);
  backlash_ = g.backlash_m;
  lp_ = line_of_action_length(g);
  x_pitch_ = pitch_point_position(g);
  t0_ = layout_.base_pitch_m();
  xs_ = layout_.start_m();
  xe_ = layout_.end_m();
  smoothing_speed_ = c.model.friction_smoothing_speed_m_s;
  face_width_ = g.face_width_m;
  kh_ = hertz_stiffness(g);
  constant_k_ = c.model.mesh_stiffness == MeshStiffnessMode::constant
                    ? c.model.constant_mesh_stiffness_n_per_m
                    : 0.0;
  damping_on_current_pair_ = c.model.damping_stiffness == DampingStiffness::current_pair;
  // A constant stiffness has neither the extra torque nor jumps: both forms
  // are then one, bit for bit.
  lagrangian_ = c.model.mesh_force == MeshForce::lagrangian && constant_k_ == 0.0;
  driven_ = c.torque1.kind == Torque::Kind::prescribed_speed;
  const bool controlled = c.torque1.kind == Torque::Kind::speed_controlled;
  induction_ = c.torque1.kind == Torque::Kind::induction_motor;
  if ((driven_ || controlled) && control.resume) {
    // A continued run carries theta1 on from where it stopped, whatever time
    // it restarts at (the steady state's runs restart theirs at 0).
    driver_theta0_ = control.resume->state.theta1_rad -
                     driver_motion(c.torque1, 0.0, control.resume->time_s).theta_rad;
  } else {
    driver_theta0_ = c.initial.theta1_rad;
  }
  if (controlled) controller_ = std::make_shared<const SpeedController>(c, driver_theta0_);
  drag_ = c.torque2.kind == Torque::Kind::drag;
  damping_update_ = resolved_damping_update(c);
  constant_torques_ =
      c.torque1.kind == Torque::Kind::constant && c.torque2.kind == Torque::Kind::constant;
  if (constant_torques_) torque_values_ = {c.torque1.constant_n_m, c.torque2.constant_n_m};
  MeshTeeth teeth = mesh_teeth(c, table, constant_k_);
  teeth_ = std::move(teeth.tables);
  gaps_ = std::move(teeth.gaps);
  kinks_ = std::move(teeth.kinks_m);
  mesh_damping_ = case_mesh_damping_n_s_per_m(c, table, teeth_.get());
}

std::pair<double, double> GearSystem::torques(double t) const {
  if (!constant_torques_ && t != torque_time_) {
    torque_time_ = t;
    // The driver's torque and the drag are set by rhs from the state.
    torque_values_ = {driven_ || controller_ || induction_ ? 0.0 : torque_at(case_.torque1, t),
                      drag_ ? 0.0 : torque_at(case_.torque2, t)};
  }
  return torque_values_;
}

void GearSystem::impose_driver(double t, State& y) const {
  if (!driven_) return;
  const DriverMotion m = driver_motion(case_.torque1, driver_theta0_, t);
  y[kTheta1] = m.theta_rad;
  y[kW1] = m.speed_rad_per_s;
}

// Ke continued along its tangent beyond the segment, or beyond the ends of
// the pair's part at a fault's edge (pair_stiffness_continued).
void GearSystem::pair_stiffness(const StiffnessTable& table, int part, double x, int count,
                                double& ke, double& dke) const {
  if (constant_k_ > 0.0) {
    ke = constant_k_ / count;
    dke = 0.0;
    return;
  }
  const StiffnessAndDerivative k =
      table.part_count() > 1 ? pair_stiffness_continued(table, part, x, table.part_start_m(part),
                                                        table.part_end_m(part))
                             : pair_stiffness_continued(table, -1, x, xs_, xe_);
  ke = k.stiffness_n_per_m;
  dke = k.derivative_n_per_m2;
}

double varying_friction_coefficient(const ModelOptions& model, double face_width_m,
                                    double normal_force_n, double vs, double ve) {
  switch (model.friction_law) {
    case FrictionLaw::constant:
      break;
    case FrictionLaw::benedict_kelley:
      return benedict_kelley_coefficient(model.benedict_kelley, normal_force_n / face_width_m, vs,
                                         ve);
    case FrictionLaw::table:
      return table_friction_coefficient(model.friction_table, slide_to_roll_ratio(vs, ve));
  }
  return model.friction_coefficient;
}

double GearSystem::friction_coefficient(double normal_force_n, double vs, double ve) const {
  return pair_friction_coefficient(case_.model, face_width_, normal_force_n, vs, ve);
}

PairPenetration GearSystem::pair_penetration(const Mode& m, int j, double x, double dl,
                                             double dl_rate, double x_rate) const {
  if (!gaps_) return {dl, dl_rate, 0.0};
  // The zone's branch, as the mode holds it: a stage state of a step that
  // ends on a kink sees the zone's own gap.
  return pair_penetration_with_gap(*gaps_, kinks_, m.zone[j], m.region, m.k_first + j, x, dl,
                                   dl_rate, x_rate, xs_, xe_);
}

double GearSystem::least_gap_m(Region line, double theta1) const {
  return least_pair_gap_m(*gaps_, layout_, line, theta1);
}

double GearSystem::damping_factor(const ContactMemory& d, double ke) const {
  return damping_on_current_pair_ ? d.damping_per_stiffness_s_m * ke
                                  : d.damping_per_stiffness_s_m * d.frozen_stiffness_n_per_m;
}

void GearSystem::rhs(double t, const State& y_in, const Mode& m, const ContactMemory& d,
                     State& dydt, ContactTotals* totals) const {
  auto [t1, t2] = torques(t);
  // A driven pinion is where its closed form puts it, whatever the stage
  // state an integrator passes.
  State driven_state;
  DriverMotion driver;
  if (driven_) {
    driver = driver_motion(case_.torque1, driver_theta0_, t);
    driven_state = y_in;
    driven_state[kTheta1] = driver.theta_rad;
    driven_state[kW1] = driver.speed_rad_per_s;
  }
  const State& y = driven_ ? driven_state : y_in;
  if (drag_) t2 = drag_torque_n_m(case_.torque2, y[kW2]);
  if (controller_) t1 = controller_->torque_n_m(t, y[kTheta1], y[kW1]);
  if (induction_) t1 = induction_motor_torque_n_m(case_.torque1, y[kW1]);
  const double w1 = y[kW1];
  const double w2 = y[kW2];
  double moment1 = t1;
  double moment2 = t2;
  double damping_power = 0.0;
  double friction_power = 0.0;
  double parametric_power = 0.0;
  if (m.region != Region::free) {
    const double sign = line_sign(m.region);
    const double dl = delta(m.region, y);
    const double dl_rate = sign * s_rate(y);
    const double ref = layout_.reference_m(m.region, y[kTheta1]);
    const double x_rate = sign * rb1_ * w1;
    for (int j = 0; j < m.count; ++j) {
      const StiffnessTable* table = m.table[j];
      // A pair with a missing tooth or without contact over a fault across
      // the face: no force, no damping, no friction; nor a pair whose gap is open.
      if (!carries(table, m.part[j]) || (gaps_ && !m.touching[j])) continue;
      const double x = layout_.position_m(ref, m.k_first + j);
      // The pair's own penetration and its rate: the line's, less the gap.
      const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
      const double dk = p.delta_m;
      const double dk_rate = p.rate_m_s;
      const double gap_slope = p.gap_slope;
      double ke = 0.0;
      double dke = 0.0;
      pair_stiffness(*table, m.part[j], x, m.count, ke, dke);
      const double f_elastic = elastic_force(ke, dk);
      const double g_damping = hertzian_damping_force(damping_factor(d, ke), dk, dk_rate);
      const double n = normal_force(f_elastic, g_damping, m.clipped[j]);
      const double vs = sliding_speed(w1, w2, x, lp_);
      const double f = friction_coefficient(n, vs, entrainment_speed(w1, w2, x, lp_));
      const double slip = smoothing_speed_ > 0.0 ? std::tanh(vs / smoothing_speed_)
                          : m.slip_per_stage     ? (vs >= 0.0 ? 1.0 : -1.0)
                                                 : m.slip[j];
      const double ff = friction_force(m.region, f, n, slip);
      // (1),(3) for one pair, (43),(45) summed over the pairs the line carries:
      // on N1 J1 w1' = T1 - [N Rb1 + Ff X], J2 w2' = T2 + [N Rb2 + Ff (lp - X)];
      // every sign flips on N2. In free flight, (2),(44): J w' = T.
      moment1 -= sign * (n * rb1_ + ff * x);
      moment2 += sign * (n * rb2_ + ff * (lp_ - x));
      // The damping force is what N adds to F; with N clipped it is -F, so the
      // stored energy released while the tooth cannot push counts as damping loss.
      damping_power += (n - f_elastic) * dk_rate;
      friction_power += f * n * slip * vs;
      // d/dt of 1/2 Ke(X) delta^2 at fixed delta. Newtonian: work of the
      // varying stiffness. Lagrangian: -dV/dtheta1 adds the torque
      // -1/2 dKe/dX (dX/dtheta1) delta^2, dX/dtheta1 = sign Rb1, whose power is
      // minus this; a clipped pair exerts no force, so the stored energy it
      // gains or loses counts with its damping loss, as above.
      const double stiffness_power = 0.5 * dk * dk * dke * x_rate;
      if (!lagrangian_) {
        parametric_power += stiffness_power;
      } else if (m.clipped[j]) {
        damping_power -= stiffness_power;
      } else {
        moment1 -= 0.5 * dk * dk * dke * sign * rb1_;
      }
      if (gaps_) {
        // The gap moves with the pinion: the pair's penetration changes at
        // fixed s by -de_k/dX dX/dt, and N acting on it does the work
        // -N de_k/dX dX/dt. Newtonian: more work of the varying mesh.
        // Lagrangian: N acts on delta_k, whose lever on the pinion is
        // sign Rb1 (1 - de_k/dX), and that torque does this work on the pinion.
        if (!lagrangian_) {
          parametric_power -= n * gap_slope * x_rate;
        } else {
          moment1 += sign * rb1_ * n * gap_slope;
        }
      }
      if (totals != nullptr) {
        totals->normal_force_n += n;
        totals->friction_force_n += ff;
        totals->friction_load_n += f * n;
      }
    }
  }
  double mesh_damping_power = 0.0;
  if (mesh_damping_ > 0.0) {
    // The viscous mesh damper acts on s' at all times, in contact and in the
    // backlash alike, as the c x' of docs/steady-state.md's clearance oscillator:
    // a force c s' along the line of action in the sense of an N1 contact force.
    const double rate = s_rate(y);
    const double force = mesh_damping_ * rate;
    moment1 -= force * rb1_;
    moment2 += force * rb2_;
    mesh_damping_power = force * rate;
  }
  if (driven_) {
    // The driver applies the torque that gives the pinion its prescribed
    // acceleration against the mesh (moment1 holds the mesh's moments, t1 = 0):
    // J1 w1' = T_driver + moment1. Its work is the ledger's torque work.
    t1 = j1_ * driver.acceleration_rad_per_s2 - moment1;
    moment1 += t1;
  }
  dydt[kTheta1] = w1;
  dydt[kTheta2] = w2;
  dydt[kW1] = moment1 / j1_;
  dydt[kW2] = moment2 / j2_;
  dydt[kTorqueWork] = t1 * w1 + t2 * w2;
  dydt[kDampingLoss] = damping_power;
  dydt[kFrictionLoss] = friction_power;
  dydt[kParametricWork] = parametric_power;
  dydt[kMeshDampingLoss] = mesh_damping_power;
}

int GearSystem::event_values(const State& y, const Mode& m, const ContactMemory& d,
                             EventValues& g) const {
  const double sv = s(y);
  if (m.region == Region::free) {
    // Region (2) ends where (31) makes delta positive on either line; with
    // gaps, where it passes the least gap of the line's pairs (a pair that
    // enters the segment already pressed in ends it at its entry).
    if (gaps_) {
      g[0] = backlash_ + least_gap_m(Region::n1, y[kTheta1]) - sv;
      g[1] = sv + backlash_ + least_gap_m(Region::n2, y[kTheta1]);
      return 2;
    }
    g[0] = backlash_ - sv;
    g[1] = sv + backlash_;
    return 2;
  }
  const double dl = delta(m.region, y);
  // With gaps the contact ends where the last touching pair lets go, which
  // the pairs' own values below locate.
  g[0] = gaps_ ? 1.0 : dl;
  // (42): the first and last loaded pair stay in [X_start, X_end], the
  // neighbours outside it. Each position is ref + k t0 for its own k, as
  // MeshLayout::loaded computes it: (ref + k t0) - t0 rounds differently, and
  // far from theta1 = 0 (|ref| of metres after a long run) the two could
  // disagree about a pair at the edge, which then enters a step late.
  const double ref = layout_.reference_m(m.region, y[kTheta1]);
  const double first = layout_.position_m(ref, m.k_first);
  const double last = layout_.position_m(ref, m.k_first + m.count - 1);
  g[1] = first - xs_;
  g[2] = xs_ - layout_.position_m(ref, m.k_first - 1);
  g[3] = xe_ - last;
  g[4] = layout_.position_m(ref, m.k_first + m.count) - xe_;
  int n = 5;
  const double dl_rate = line_sign(m.region) * s_rate(y);
  const double x_rate = line_sign(m.region) * rb1_ * y[kW1];
  for (int j = 0; j < m.count; ++j) {
    const double x = layout_.position_m(ref, m.k_first + j);
    const StiffnessTable* table = m.table[j];
    append_part_events(table, m.part[j], x, g.data(), n);
    const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
    const double dk = p.delta_m;
    const double dk_rate = p.rate_m_s;
    if (gaps_ && !append_gap_events(m.touching[j], m.zone[j], kinks_, x, dk, g.data(), n)) {
      continue;
    }
    // A smoothed sign, or one taken per stage, has no switch to locate: the value stays positive.
    g[n++] = smoothing_speed_ > 0.0 || m.slip_per_stage
                 ? 1.0
                 : m.slip[j] * sliding_speed(y[kW1], y[kW2], x, lp_);
    const double push = push_sign_function(table, m.part[j], x, m.count, d, dk, dk_rate);
    g[n++] = m.clipped[j] ? -push : push;
  }
  return n;
}

// A function with the sign and the zeros of F + G of one pair. With D
// proportional to the pair's own Ke, F + G = Ke delta (1 + (D/K) d(delta)/dt)
// and the positive factor Ke need not be evaluated.
// A pair that cannot carry (a missing tooth, no contact) never pushes nor switches: 1.
double GearSystem::push_sign_function(const StiffnessTable* table, int part, double x, int count,
                                      const ContactMemory& d, double dl, double dl_rate) const {
  if (!carries(table, part)) return 1.0;
  if (damping_on_current_pair_) {
    return dl * (1.0 + d.damping_per_stiffness_s_m * dl_rate);
  }
  double ke = 0.0;
  double dke = 0.0;
  pair_stiffness(*table, part, x, count, ke, dke);
  return elastic_force(ke, dl) + hertzian_damping_force(damping_factor(d, ke), dl, dl_rate);
}

bool GearSystem::mode_holds(const State& y, const Mode& m, const ContactMemory& d) const {
  // Not zeroed: only the n values set are read.
  EventValues g;
  const int n = event_values(y, m, d, g);
  for (int i = 0; i < n; ++i) {
    if (g[i] < 0.0) return false;
  }
  return true;
}

Mode GearSystem::classify_geometry(const State& y) const {
  Mode m;
  const double sv = s(y);
  if (gaps_) {
    // The line one of whose pairs is pressed in: delta - e_k > 0 (the
    // backlash check of the case keeps the two lines from both touching).
    for (const Region line : {Region::n1, Region::n2}) {
      const double dl = penetration(line, sv, backlash_);
      const double ref = layout_.reference_m(line, y[kTheta1]);
      const LoadedRange range = layout_.loaded(ref);
      bool any = false;
      for (int j = 0; j < range.count; ++j) {
        const int k = range.k_first + j;
        const double x = layout_.position_m(ref, k);
        m.touching[j] = dl - gaps_->gap_m(line, k, x) > 0.0;
        m.zone[j] = gap_zone(kinks_, x);
        any = any || m.touching[j];
      }
      if (any) {
        m.region = line;
        m.k_first = range.k_first;
        m.count = range.count;
        set_parts(y, m);
        return m;
      }
    }
    m.touching = {};
    m.zone = {};
    return m;
  }
  if (sv - backlash_ > 0.0) {
    m.region = Region::n1;
  } else if (-sv - backlash_ > 0.0) {
    m.region = Region::n2;
  } else {
    return m;
  }
  const LoadedRange range = layout_.loaded(layout_.reference_m(m.region, y[kTheta1]));
  m.k_first = range.k_first;
  m.count = range.count;
  set_parts(y, m);
  return m;
}

void GearSystem::set_parts(const State& y, Mode& m) const {
  for (int j = 0; j < m.count; ++j) {
    const StiffnessTable* table = pair_table(m.region, m.k_first + j);
    m.table[j] = table;
    if (!teeth_) continue;
    m.part[j] = table != nullptr && table->part_count() > 1
                    ? table->part_of(std::clamp(pair_position(m, y, j), xs_, xe_))
                    : 0;
  }
}

void GearSystem::classify_forces(const State& y, const ContactMemory& d, Mode& m) const {
  if (m.region == Region::free) return;
  const double dl = delta(m.region, y);
  const double dl_rate = line_sign(m.region) * s_rate(y);
  const double x_rate = line_sign(m.region) * rb1_ * y[kW1];
  for (int j = 0; j < m.count; ++j) {
    const double x = pair_position(m, y, j);
    m.slip[j] = sliding_speed(y[kW1], y[kW2], x, lp_) >= 0.0 ? 1.0 : -1.0;
    const PairPenetration p = pair_penetration(m, j, x, dl, dl_rate, x_rate);
    m.clipped[j] =
        push_sign_function(m.table[j], m.part[j], x, m.count, d, p.delta_m, p.rate_m_s) < 0.0;
  }
}

OnsetDamping onset_damping(const ModelOptions& model, DampingUpdate update, double approach_m_s) {
  OnsetDamping onset;
  onset.impact_speed_m_s = std::max(approach_m_s, kSmallestImpactSpeed_m_s);
  // DampingUpdate: e and D of (32),(33) from this impact's Vi, from the
  // case's reference speed, or none.
  const double speed =
      update == DampingUpdate::frozen ? model.damping_reference_speed_m_s : onset.impact_speed_m_s;
  onset.restitution = restitution_coefficient(model.restitution, speed);
  onset.damping_per_stiffness_s_m =
      update == DampingUpdate::off
          ? 0.0
          : damping_factor_per_stiffness(model.damping_form, onset.restitution, speed);
  return onset;
}

GearSystem::Onset GearSystem::damping_at_onset(const State& y, const Mode& m) const {
  Onset onset{};
  const double line_rate = line_sign(m.region) * s_rate(y);
  double approach = line_rate;
  if (gaps_) {
    // The fastest approach among the pairs that touch, each at its own
    // penetration rate.
    const double dl = delta(m.region, y);
    const double x_rate = line_sign(m.region) * rb1_ * y[kW1];
    approach = -std::numeric_limits<double>::infinity();
    for (int j = 0; j < m.count; ++j) {
      if (!m.touching[j]) continue;
      approach = std::max(
          approach, pair_penetration(m, j, pair_position(m, y, j), dl, line_rate, x_rate).rate_m_s);
    }
  }
  const OnsetDamping damping = onset_damping(case_.model, damping_update_, approach);
  onset.impact_speed_m_s = damping.impact_speed_m_s;
  onset.restitution = damping.restitution;
  ContactMemory& d = onset.damping;
  d.damping_per_stiffness_s_m = damping.damping_per_stiffness_s_m;
  if (case_.model.damping_stiffness == DampingStiffness::hertz) {
    d.frozen_stiffness_n_per_m = kh_;
  } else if (m.count > 0) {
    // The loaded pair nearest the pitch point; with faults, among the pairs
    // that carry (none: the stiffness stays 0, as nothing pushes).
    int nearest = -1;
    for (int j = 0; j < m.count; ++j) {
      if (!carries(m.table[j], m.part[j])) continue;
      if (nearest < 0 || std::fabs(pair_position(m, y, j) - x_pitch_) <
                             std::fabs(pair_position(m, y, nearest) - x_pitch_)) {
        nearest = j;
      }
    }
    if (nearest >= 0) {
      double ke = 0.0;
      double dke = 0.0;
      pair_stiffness(*m.table[nearest], m.part[nearest], pair_position(m, y, nearest), m.count, ke,
                     dke);
      d.frozen_stiffness_n_per_m = ke;
    }
  }
  return onset;
}

ElasticEnergy GearSystem::stored_energy(const State& y, const Mode& m) const {
  ElasticEnergy u;
  if (m.region == Region::free) return u;
  const double line_delta = delta(m.region, y);
  for (int j = 0; j < m.count; ++j) {
    const double x = pair_position(m, y, j);
    // A pair whose gap is open stores nothing; one that touches, by its own
    // penetration.
    if (gaps_ && !m.touching[j]) continue;
    const double dl = pair_penetration(m, j, x, line_delta, 0.0, 0.0).delta_m;
    if (constant_k_ > 0.0) {
      u.j[index_of(Term::hertz)] += 0.5 * constant_k_ / m.count * dl * dl;
      continue;
    }
    const StiffnessTable* table = m.table[j];
    // A missing tooth stores nothing, nor a pair without contact over a fault across the face.
    if (!carries(table, m.part[j])) continue;
    // At a fault's edge, the side of the pair's part: the ledger books the jump between the two
    // sides at the event.
    const Compliances c =
        table->part_count() > 1
            ? table->compliance_in_part(
                  std::clamp(x, table->part_start_m(m.part[j]), table->part_end_m(m.part[j])),
                  m.part[j])
            : table->compliance(std::clamp(x, xs_, xe_));
    // (30) F = Ke delta with 1/Ke the total compliance of (29).
    const ElasticEnergy pair = pair_energy(c, dl / c.total_m_per_n());
    for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] += pair.j[i];
  }
  return u;
}

}  // namespace gearimpact
