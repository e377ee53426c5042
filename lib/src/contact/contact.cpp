#include "gearimpact/contact/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gearimpact {

namespace {

// The imperial units of Benedict and Kelley's formula, in SI.
constexpr double kInch_m = 0.0254;
constexpr double kPoundForce_n = 4.4482216152605;  // 1 lbf = 0.45359237 kg x 9.80665 m/s^2
constexpr double kPoundPerInch_n_per_m = kPoundForce_n / kInch_m;
constexpr double kCentipoise_pa_s = 1e-3;
constexpr double kMicroinch_m = 1e-6 * kInch_m;

}  // namespace

double restitution_coefficient(const RestitutionLaw& law, double impact_speed_m_s) {
  // (33)
  const double e =
      1.0 - law.coefficient * std::pow(impact_speed_m_s / law.speed_unit_m_s, law.exponent);
  return e < 0.0 ? 0.0 : (e > 1.0 ? 1.0 : e);
}

double damping_factor_per_stiffness(DampingForm form, double restitution, double impact_speed_m_s) {
  const double e = restitution;
  // (32) in the three forms docs/model.md lists.
  switch (form) {
    case DampingForm::herbert_mcwhannell:
      return 6.0 * (1.0 - e) / (((2.0 * e - 1.0) * (2.0 * e - 1.0) + 3.0) * impact_speed_m_s);
    case DampingForm::hunt_crossley:
      return 3.0 * (1.0 - e) / (2.0 * impact_speed_m_s);
    case DampingForm::lee_wang:
      return 3.0 * (1.0 - e) / (4.0 * impact_speed_m_s);
  }
  return 0.0;
}

double benedict_kelley_coefficient(const BenedictKelleyLaw& law, double load_per_width_n_per_m,
                                   double sliding_speed_m_s, double entrainment_speed_m_s) {
  const double w = load_per_width_n_per_m / kPoundPerInch_n_per_m;
  if (!(w > 0.0)) return 0.0;
  const double nu0 = law.viscosity_pa_s / kCentipoise_pa_s;
  const double vs = std::fabs(sliding_speed_m_s) / kInch_m;
  const double ve = std::fabs(entrainment_speed_m_s) / kInch_m;
  const double s = law.roughness_m / kMicroinch_m;
  // A zero speed puts the log argument at +infinity: f at its clip.
  const double denominator = nu0 * vs * ve * ve;
  if (!(denominator > 0.0)) return law.most_coefficient;
  const double c_r = 50.0 / (50.0 - s);
  const double f = 0.0127 * c_r * std::log10(3.17e8 * w / denominator);
  return std::clamp(f, 0.0, law.most_coefficient);
}

double slide_to_roll_ratio(double sliding_speed_m_s, double entrainment_speed_m_s) {
  if (entrainment_speed_m_s == 0.0) {
    if (sliding_speed_m_s == 0.0) return 0.0;
    return std::copysign(std::numeric_limits<double>::infinity(), sliding_speed_m_s);
  }
  return 2.0 * sliding_speed_m_s / entrainment_speed_m_s;
}

double table_friction_coefficient(const FrictionTable& table, double slide_to_roll) {
  const std::vector<double>& r = table.slide_to_roll;
  const std::vector<double>& f = table.coefficient;
  if (!(slide_to_roll > r.front())) return f.front();
  if (slide_to_roll >= r.back()) return f.back();
  // r.front() < slide_to_roll < r.back(): an interval [r[i-1], r[i]) holds it.
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(r.begin(), r.end(), slide_to_roll) - r.begin());
  const double weight = (slide_to_roll - r[i - 1]) / (r[i] - r[i - 1]);
  return f[i - 1] + weight * (f[i] - f[i - 1]);
}

}  // namespace gearimpact
