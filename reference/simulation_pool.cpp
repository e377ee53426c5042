#include "simulation_pool.hpp"

#include <algorithm>
#include <cstdio>
#include <type_traits>
#include <utility>

namespace gearimpact::cli {

namespace {

// The number of members of an aggregate, so that a member added to one of the
// structs below stops the build here until the key covers it too.
struct AnyMember {
  template <typename T>
  operator T() const;  // never defined: used in unevaluated contexts only
};
template <typename T, typename... Members>
constexpr std::size_t member_count() {
  if constexpr (requires { T{Members{}..., AnyMember{}}; }) {
    return member_count<T, Members..., AnyMember>();
  } else {
    return sizeof...(Members);
  }
}
static_assert(member_count<GearPair>() == 10, "add the new GearPair member to the key");
static_assert(member_count<Torque>() == 6, "add the new Torque member to the key");
static_assert(member_count<InitialState>() == 4, "add the new InitialState member to the key");
static_assert(member_count<RestitutionLaw>() == 3, "add the new RestitutionLaw member to the key");
static_assert(member_count<StiffnessModel>() == 7, "add the new StiffnessModel member to the key");
static_assert(member_count<ModelOptions>() == 6, "add the new ModelOptions member to the key");
static_assert(member_count<IntegratorSettings>() == 5,
              "add the new IntegratorSettings member to the key");
static_assert(member_count<SimulationCase>() == 7, "add the new SimulationCase member to the key");

class Key {
 public:
  Key& operator<<(double value) {
    char text[40];
    std::snprintf(text, sizeof text, "%a,", value);  // exact
    text_ += text;
    return *this;
  }
  Key& operator<<(int value) {
    text_ += std::to_string(value) + ",";
    return *this;
  }
  template <typename Enum>
  requires std::is_enum_v<Enum> Key& operator<<(Enum value) {
    return *this << static_cast<int>(value);
  }
  std::string text() const { return text_; }

 private:
  std::string text_;
};

std::string stiffness_key(const GearPair& g, const StiffnessModel& m) {
  Key key;
  key << g.teeth1 << g.teeth2 << g.module_m << g.pressure_angle_rad << g.face_width_m
      << g.addendum_coefficient << g.youngs_modulus_pa << g.poisson_ratio << g.density_kg_m3
      << g.backlash_m;
  key << m.method << m.moment_sign << m.relative_tolerance << m.xform_rule
      << static_cast<int>(m.hertz_term) << static_cast<int>(m.bending_term)
      << static_cast<int>(m.axial_term);
  return key.text();
}

void add_torque(Key& key, const Torque& t) {
  key << t.kind << t.constant_n_m << t.amplitude_n_m << t.angular_frequency_rad_s << t.phase_rad;
}

// Every input of a run but its name, which does not change the result. Empty
// for a run that cannot be compared (a user torque function).
std::string run_key(const SimulationCase& c, bool keep_series) {
  if (c.torque1.kind == Torque::Kind::user || c.torque2.kind == Torque::Kind::user) return {};
  Key key;
  add_torque(key, c.torque1);
  add_torque(key, c.torque2);
  key << c.initial.theta1_rad << c.initial.theta2_rad << c.initial.w1_rad_s << c.initial.w2_rad_s;
  const ModelOptions& m = c.model;
  key << m.friction_coefficient << m.damping_form << m.damping_stiffness
      << m.restitution.coefficient << m.restitution.exponent << m.restitution.speed_unit_m_s
      << m.coast_phase;
  const IntegratorSettings& s = c.integrator;
  key << s.kind << s.step_s << s.end_time_s << s.adaptive_relative_tolerance;
  // The rows kept matter only with the series.
  return stiffness_key(c.gears, m.stiffness) + "|" + key.text() + "|" +
         (keep_series ? "series every " + std::to_string(s.output_every) : "summary");
}

// The part of a run key before what is kept of the series.
std::string inputs_of(const std::string& run_key) {
  return run_key.substr(0, run_key.rfind('|') + 1);
}

}  // namespace

SimulationPool::SimulationPool(unsigned threads) {
  const unsigned n = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  for (unsigned i = 0; i < n; ++i) workers_.emplace_back([this] { work(); });
}

SimulationPool::~SimulationPool() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  ready_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

std::shared_future<SimulationResult> SimulationPool::submit(const SimulationCase& c,
                                                            bool keep_series) {
  const std::string key = run_key(c, keep_series);
  std::unique_lock lock(mutex_);
  ++requested_;
  if (!key.empty()) {
    if (const auto found = runs_.find(key); found != runs_.end()) return found->second;
    if (!keep_series) {
      // Any run with the series and the same inputs has this summary.
      const std::string with_series = inputs_of(key) + "series";
      const auto found_series = runs_.lower_bound(with_series);
      if (found_series != runs_.end() && found_series->first.starts_with(with_series)) {
        return found_series->second;
      }
    }
  }
  const std::string table_key = stiffness_key(c.gears, c.model.stiffness);
  std::shared_ptr<const StiffnessTable>& table = tables_[table_key];
  if (!table) {
    // Built here, once per gear pair; a bad case throws InputError to the caller.
    validate(c);
    table = std::make_shared<const StiffnessTable>(c.gears, c.model.stiffness);
  }
  auto task =
      std::make_shared<std::packaged_task<SimulationResult()>>([c, table = table, keep_series] {
        RunControl control;
        control.keep_series = keep_series;
        return simulate(c, *table, control);
      });
  std::shared_future<SimulationResult> result = task->get_future().share();
  if (!key.empty()) runs_.emplace(key, result);
  ++computed_;
  queue_.emplace_back([task] { (*task)(); });
  lock.unlock();
  ready_.notify_one();
  return result;
}

std::size_t SimulationPool::requested() const {
  const std::lock_guard lock(mutex_);
  return requested_;
}

std::size_t SimulationPool::computed() const {
  const std::lock_guard lock(mutex_);
  return computed_;
}

void SimulationPool::work() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
  }
}

}  // namespace gearimpact::cli
