#include "gearimpact/stiffness/mesh_tables.hpp"

#include <numeric>
#include <utility>

#include "gearimpact/stiffness/mesh_stiffness.hpp"

namespace gearimpact {

namespace {

// The distinct states of one gear's teeth, healthy first, and each tooth's
// index among them.
std::vector<ToothState> classify(const std::vector<ToothFault>& faults, Gear gear, int z,
                                 std::vector<int>& tooth_class) {
  std::vector<ToothState> states{ToothState{}};
  tooth_class.assign(static_cast<std::size_t>(z), 0);
  for (const ToothFault& f : faults) {
    if (f.gear != gear) continue;
    std::size_t c = 0;
    while (c < states.size() && states[c] != f.state) ++c;
    if (c == states.size()) states.push_back(f.state);
    tooth_class[static_cast<std::size_t>(f.tooth)] = static_cast<int>(c);
  }
  return states;
}

}  // namespace

MeshTables::MeshTables(const GearPair& pair, const StiffnessModel& model,
                       std::vector<ToothFault> faults,
                       std::shared_ptr<const StiffnessTable> healthy, StiffnessTableOptions options)
    : pair_(pair), faults_(std::move(faults)), healthy_(std::move(healthy)) {
  check_tooth_faults(pair_, model, faults_);
  if (!healthy_) healthy_ = std::make_shared<const StiffnessTable>(pair_, model, options);
  const int z1 = teeth(pair_, Gear::one);
  const int z2 = teeth(pair_, Gear::two);
  const std::vector<ToothState> pinion = classify(faults_, Gear::one, z1, pinion_class_);
  const std::vector<ToothState> wheel = classify(faults_, Gear::two, z2, wheel_class_);
  wheel_states_ = wheel.size();
  distinct_ = {pinion.size() > 1, wheel.size() > 1};
  tables_.assign(pinion.size() * wheel_states_, nullptr);
  // The combinations that meet: pinion tooth i meets wheel tooth j on N1 when
  // i = j mod gcd(z1, z2), on N2 when j = i + 1 mod gcd (teeth_of_pair); so
  // every pair of one hunting period on both lines.
  std::vector<bool> meets(tables_.size(), false);
  const int period = static_cast<int>(std::lcm(z1, z2));
  for (int n = 0; n < period; ++n) {
    meets[combination(teeth_of_pair(pair_, Region::n1, -n))] = true;
    meets[combination(teeth_of_pair(pair_, Region::n2, n))] = true;
  }
  const ContactSegment segment = contact_segment(pair_);
  for (std::size_t a = 0; a < pinion.size(); ++a) {
    for (std::size_t b = 0; b < wheel_states_; ++b) {
      const std::size_t c = a * wheel_states_ + b;
      if (!meets[c] || pinion[a].kind == ToothKind::missing ||
          wheel[b].kind == ToothKind::missing) {
        continue;
      }
      if (a == 0 && b == 0) {
        tables_[c] = healthy_;
        continue;
      }
      const ToothState& s1 = pinion[a];
      const ToothState& s2 = wheel[b];
      tables_[c] = std::make_shared<const StiffnessTable>(
          segment.start_m, segment.end_m,
          [&](double x1_m) { return mesh_stiffness(pair_, x1_m, model, s1, s2).included; },
          options);
      ++fault_tables_;
    }
  }
}

long long MeshTables::true_period_mesh_periods() const {
  return gearimpact::true_period_mesh_periods(pair_, distinct_);
}

}  // namespace gearimpact
