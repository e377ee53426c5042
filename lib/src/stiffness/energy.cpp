#include "gearimpact/stiffness/energy.hpp"

#include <algorithm>
#include "gearimpact/constants.hpp"
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

ElasticEnergy pair_energy(const MeshStiffness& k, double force_n) {
  const double half_f2 = 0.5 * force_n * force_n;
  return {half_f2 / k.kh, half_f2 * (1.0 / k.kb1 + 1.0 / k.kb2),
          half_f2 * (1.0 / k.ka1 + 1.0 / k.ka2)};
}

ElasticEnergy shared_load_energy(const std::vector<MeshStiffness>& pairs, double total_force_n) {
  double stiffness_sum = 0.0;
  for (const MeshStiffness& k : pairs) stiffness_sum += k.ke;
  ElasticEnergy sum;
  for (const MeshStiffness& k : pairs) {
    const ElasticEnergy u = pair_energy(k, total_force_n * k.ke / stiffness_sum);
    sum.hertz_j += u.hertz_j;
    sum.bending_j += u.bending_j;
    sum.axial_j += u.axial_j;
  }
  return sum;
}

std::vector<EnergyRatios> energy_ratio_cycle(const GearPair& pair, int points,
                                             const StiffnessModel& model) {
  if (points < 2) {
    throw InputError("points", std::to_string(points), "an integer >= 2");
  }
  const ContactSegment segment = contact_segment(pair);
  const double t0 = base_pitch(pair);
  const double step = (segment.end_m - segment.start_m) / (points - 1);
  std::vector<EnergyRatios> rows;
  rows.reserve(static_cast<std::size_t>(points));
  for (int i = 0; i < points; ++i) {
    // The last point is set exactly so that X_end is not lost to rounding.
    const double x = i + 1 == points ? segment.end_m : segment.start_m + i * step;
    const MeshStiffness own = mesh_stiffness(pair, x, model);
    std::vector<MeshStiffness> loaded{own};
    for (double other = x - t0; other >= segment.start_m; other -= t0) {
      loaded.push_back(mesh_stiffness(pair, other, model));
    }
    for (double other = x + t0; other <= segment.end_m; other += t0) {
      loaded.push_back(mesh_stiffness(pair, other, model));
    }
    const ElasticEnergy one = pair_energy(own, 1.0);
    const ElasticEnergy system = shared_load_energy(loaded, 1.0);
    rows.push_back({x, contact_angle(pair, Gear::one, x) * 180.0 / pi,
                    static_cast<int>(loaded.size()), one.hertz_j / one.bending_j,
                    one.axial_j / one.bending_j, system.hertz_j / system.bending_j,
                    system.axial_j / system.bending_j});
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
