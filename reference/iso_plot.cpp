#include "iso_plot.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/steady/iso_resonance.hpp"

namespace gearimpact::cli {

namespace {

constexpr int kBandIntervals = 400;

}  // namespace

double highest_iso_kv(const IsoScale& scale, double n_max, double from, double to) {
  double highest = 0.0;
  for (int i = 0; i <= kBandIntervals; ++i) {
    const double n = n_max * i / kBandIntervals;
    if (n < from || n > to) continue;
    highest = std::max(
        highest,
        iso_dynamic_factor_perfect_gears(n, scale.contact_ratio, scale.line_load_n_per_m).value);
  }
  return highest;
}

void write_iso_kv_band(const std::filesystem::path& file, const IsoScale& scale, double n_max) {
  std::string csv = "iso_resonance_ratio,iso_kv_perfect_gears\n";
  constexpr int intervals = kBandIntervals;
  for (int i = 0; i <= intervals; ++i) {
    const double n = n_max * i / intervals;
    csv += format_data_number(n) + "," +
           format_data_number(
               iso_dynamic_factor_perfect_gears(n, scale.contact_ratio, scale.line_load_n_per_m)
                   .value) +
           "\n";
  }
  write_file_atomically(file.string(), csv);
}

Figure dynamic_factor_vs_iso_n(const std::string& name, const IsoScale& scale,
                               const std::string& data, int direction_column, int n_column,
                               int df_column, const std::string& band, bool quasi_static) {
  const std::string to_iso_n = format_data_number(scale.resonance_speed_rad_per_s /
                                                  scale.resonance_speed_iso_stiffness_rad_per_s);
  char load[96];
  std::snprintf(load, sizeof load, "{/Symbol e}_{/Symbol a} %.3g, F_t/b %.3g N/mm",
                scale.contact_ratio, scale.line_load_n_per_m * 1e-3);
  Figure f;
  f.name = name;
  f.title = "Dynamic factor against ISO 6336-1's resonance ratio N";
  f.x_label = "N = w_1 / w_{E1}, c_{/Symbol ga} b = the model's mean mesh stiffness";
  f.y_label = "dynamic factor (max mesh force / static)";
  f.setup = {"set key outside bottom center horizontal",
             "set yrange [0:*]",
             "set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb 'gray30'",
             "set link x2 via x*" + to_iso_n + " inverse x/" + to_iso_n,
             "set x2tics 0.5",
             "set xtics nomirror",
             "set x2label \"N with ISO's own c_{/Symbol ga}\""};
  const std::string d = std::to_string(direction_column);
  const std::string n = std::to_string(n_column);
  const std::string df = std::to_string(df_column);
  f.series = {
      gnuplot_string(data) + " using (strcol(" + d + ") eq \"up\" ? $" + n + " : NaN):" + df +
          " with linespoints pt 7 ps 0.6 lw 1.5 title 'simulated, sweep up'",
      gnuplot_string(data) + " using (strcol(" + d + ") eq \"down\" ? $" + n + " : NaN):" + df +
          " with linespoints pt 6 ps 0.9 dt 2 title 'simulated, sweep down'",
      gnuplot_string(band) + " using 1:2 with lines lw 2 lc rgb 'dark-red' title " +
          gnuplot_string("ISO K_v, perfect gears (" + std::string(load) + ")")};
  if (quasi_static) {
    // The ratio to 17 digits, so that the curve is the CSV's column over it exactly as drawn.
    const std::string qs = "($" + df + " / " + format_number(scale.quasi_static_force_ratio) + ")";
    char ratio[64];
    std::snprintf(ratio, sizeof ratio, "%.4g", scale.quasi_static_force_ratio);
    f.y_label = "dynamic factor: max mesh force / static load (grey), / quasi-static peak (colour)";
    f.title = "Dynamic factor against ISO 6336-1's resonance ratio N (quasi-static peak = " +
              std::string(ratio) + " x static load)";
    f.series[0] = gnuplot_string(data) + " using (strcol(" + d + ") eq \"up\" ? $" + n +
                  " : NaN):" + df +
                  " with linespoints pt 7 ps 0.4 lc rgb 'gray60' title 'over static load, up'";
    f.series[1] =
        gnuplot_string(data) + " using (strcol(" + d + ") eq \"down\" ? $" + n + " : NaN):" + df +
        " with linespoints pt 6 ps 0.6 dt 2 lc rgb 'gray60' title 'over static load, down'";
    f.series.insert(
        f.series.begin() + 2,
        {gnuplot_string(data) + " using (strcol(" + d + ") eq \"up\" ? $" + n + " : NaN):" + qs +
             " with linespoints pt 7 ps 0.6 lw 1.5 lc rgb 'blue' title 'over "
             "quasi-static peak, up'",
         gnuplot_string(data) + " using (strcol(" + d + ") eq \"down\" ? $" + n + " : NaN):" + qs +
             " with linespoints pt 6 ps 0.9 dt 2 lc rgb 'blue' title 'over "
             "quasi-static peak, down'"});
  }
  return f;
}

}  // namespace gearimpact::cli
