#include "mesh_stiffness_figure.hpp"

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/io/results.hpp"

namespace gearimpact::cli {

Figure mesh_stiffness_figure(const TruePeriodMeshStiffness& tvms,
                             const std::vector<ToothFault>& faults, const std::string& name) {
  Figure f;
  f.name = "mesh_stiffness";
  f.title = "Mesh stiffness over the true period (" + tvms.period_kind + ", " +
            std::to_string(tvms.mesh_periods) + " mesh periods), " + literal_key(name);
  f.x_label = "pinion angle {/Symbol q}_1 from pinion tooth 0 entering against wheel tooth 0, deg";
  f.y_label = "mesh stiffness, 10^8 N/m";
  const double degrees = 180.0 / pi;
  // The true period's end, one step past the last sample (there are at least two).
  const double step_deg = (tvms.samples[1].theta1_rad - tvms.samples[0].theta1_rad) * degrees;
  const double end_deg = tvms.samples.back().theta1_rad * degrees + step_deg;
  f.setup = {"set key outside right top vertical",
             "set xrange [0:" + format_data_number(end_deg) + "]"};
  // The faulted teeth in contact, stretch by stretch: a stretch runs while one faulted tooth
  // stays in contact (it is in contact for eps_alpha mesh periods on end).
  const auto faulted_tooth = [&](const TeethInContact& t) -> std::string {
    for (const ToothFault& fault : faults) {
      const int tooth = fault.gear == Gear::one ? t.pinion_tooth : t.wheel_tooth;
      if (tooth == fault.tooth) {
        return std::string(fault.gear == Gear::one ? "pinion " : "wheel ") +
               std::to_string(fault.tooth) + " " + to_string(fault.state.kind);
      }
    }
    return "";
  };
  std::map<std::string, double> open;  // a faulted tooth in contact since this angle
  int object = 0;
  const auto close = [&](const std::string& label, double from_deg, double to_deg) {
    ++object;
    f.setup.push_back("set object " + std::to_string(object) + " rect from " +
                      format_data_number(from_deg) + ", graph 0 to " + format_data_number(to_deg) +
                      ", graph 1 fc rgb '#fddbc7' fs solid 0.6 noborder behind");
    f.setup.push_back("set label " + std::to_string(object) + " " + gnuplot_string(label) + " at " +
                      format_data_number(0.5 * (from_deg + to_deg)) +
                      ", graph 0.04 left rotate by 90 font ',8'");
  };
  for (const TruePeriodSample& sample : tvms.samples) {
    const double at = sample.theta1_rad * degrees;
    std::map<std::string, double> now;
    for (const TeethInContact& t : sample.teeth) {
      const std::string label = faulted_tooth(t);
      if (label.empty()) continue;
      const auto found = open.find(label);
      now[label] = found != open.end() ? found->second : at;
    }
    for (const auto& [label, from] : open) {
      if (now.count(label) == 0) close(label, from, at);
    }
    open = std::move(now);
  }
  for (const auto& [label, from] : open) close(label, from, end_deg);
  f.series = {"'mesh_stiffness.csv' using ($2 * " + format_data_number(degrees) +
                  "):($5 * 1e-8) with lines lw 2 lc rgb 'gray50' title 'all teeth healthy'",
              "'mesh_stiffness.csv' using ($2 * " + format_data_number(degrees) +
                  "):($4 * 1e-8) with lines lw 2 lc rgb '#1f77b4' title 'with the faults'"};
  return f;
}

}  // namespace gearimpact::cli
