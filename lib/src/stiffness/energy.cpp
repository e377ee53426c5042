#include "gearimpact/stiffness/energy.hpp"

#include <algorithm>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

ElasticEnergy pair_energy(const Compliances& compliance, double force_n) {
  // (5),(16),(17),(28)
  const double half_f2 = 0.5 * force_n * force_n;
  ElasticEnergy u;
  for (std::size_t i = 0; i < kTermCount; ++i) u.j[i] = half_f2 * compliance.m_per_n[i];
  return u;
}

ElasticEnergy shared_load_energy(const std::vector<MeshStiffness>& pairs, double total_force_n) {
  double stiffness_sum = 0.0;
  for (const MeshStiffness& k : pairs) stiffness_sum += k.ke;
  ElasticEnergy sum;
  for (const MeshStiffness& k : pairs) {
    const ElasticEnergy u = pair_energy(k.included, total_force_n * k.ke / stiffness_sum);
    for (std::size_t i = 0; i < kTermCount; ++i) sum.j[i] += u.j[i];
  }
  return sum;
}

std::vector<EnergyRatios> energy_ratio_cycle(const GearPair& pair, int points,
                                             const StiffnessModel& model) {
  // Every ratio is a term's energy over the bending energy: undefined without
  // it. A term that is off has no energy, and its ratio is 0.
  if (!model.terms.has(Term::bending)) {
    throw InputError("model.bending_term", "\"off\"",
                     "\"on\" for the energy ratios of Fig. 8: each is a term's energy over the "
                     "bending energy, which is 0 without the bending term");
  }
  const MeshLayout layout(pair, CoastPhase::half_base_pitch);
  std::vector<EnergyRatios> rows;
  rows.reserve(static_cast<std::size_t>(std::max(points, 0)));
  for (const double x : contact_positions(pair, points)) {
    // (42) with this tooth as pair 0: the tooth first, then the others.
    const MeshStiffness own = mesh_stiffness(pair, x, model);
    std::vector<MeshStiffness> loaded{own};
    const LoadedRange range = layout.loaded(x);
    for (int k = range.k_first; k < range.k_first + range.count; ++k) {
      if (k != 0) loaded.push_back(mesh_stiffness(pair, layout.position_m(x, k), model));
    }
    const ElasticEnergy one = pair_energy(own.included, 1.0);
    const ElasticEnergy system = shared_load_energy(loaded, 1.0);
    const double bending_one = one.of(Term::bending);
    const double bending_system = system.of(Term::bending);
    rows.push_back({x, contact_angle(pair, Gear::one, x) * 180.0 / pi,
                    static_cast<int>(loaded.size()), one.of(Term::hertz) / bending_one,
                    one.of(Term::axial) / bending_one, system.of(Term::hertz) / bending_system,
                    system.of(Term::axial) / bending_system});
  }
  return rows;
}

RatioExtremes extremes(const std::vector<EnergyRatios>& rows, double EnergyRatios::*ratio) {
  if (rows.empty()) throw InputError("rows", "none", "at least one row of a cycle");
  RatioExtremes r{rows.front().*ratio, rows.front().*ratio, rows.front().phi1_deg};
  for (const EnergyRatios& row : rows) {
    const double v = row.*ratio;
    r.min = std::min(r.min, v);
    if (v > r.max) {
      r.max = v;
      r.phi1_at_max_deg = row.phi1_deg;
    }
  }
  return r;
}

AngleZone one_pair_zone(const std::vector<EnergyRatios>& rows) {
  AngleZone zone{0.0, 0.0};
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (rows[i - 1].pairs == 2 && rows[i].pairs == 1) zone.start_deg = rows[i].phi1_deg;
    if (rows[i - 1].pairs == 1 && rows[i].pairs == 2) zone.end_deg = rows[i - 1].phi1_deg;
  }
  return zone;
}

}  // namespace gearimpact
