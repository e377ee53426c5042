#include "iso_plot.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/dynamics/system.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/stiffness/iso6336.hpp"

namespace gearimpact::cli {

namespace {

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

std::optional<IsoScale> iso_scale(const SimulationCase& c, const StiffnessTable& table) {
  const GearPair& g = c.gears;
  const double r1 = pitch_radius(g, Gear::one);
  const double line_load = std::fabs(mean_torque_n_m(c.torque1, "torque1")) / (r1 * g.face_width_m);
  if (!(line_load > 0.0)) return std::nullopt;
  // d_m1 = (d_a1 + d_f1) / 2, the tip and root circles of the rack-cut pinion.
  const RackGearGeometry pinion = rack_gear_geometry(g, Gear::one);
  const double mean_diameter1 = pinion.tip_radius_m + pinion.root_radius_m;
  const double m_red =
      iso_reduced_mass_kg_per_m(g.density_kg_m3, static_cast<double>(g.teeth2) / g.teeth1,
                                mean_diameter1, 2.0 * base_radius(g, Gear::one));
  const Iso6336Stiffness iso = iso6336_method_b(iso6336_pair(g, 0.0));
  IsoScale scale;
  scale.resonance_speed_rad_s = iso_resonance_speed_rad_per_s(
      g.teeth1, mean_mesh_stiffness_n_m(c, table) / g.face_width_m, m_red);
  scale.resonance_speed_iso_stiffness_rad_s =
      iso_resonance_speed_rad_per_s(g.teeth1, iso.mesh_stiffness_n_per_m2, m_red);
  scale.contact_ratio = iso.transverse_contact_ratio;
  scale.line_load_n_m = line_load;
  return scale;
}

void write_iso_kv_band(const std::filesystem::path& file, const IsoScale& scale, double n_max) {
  std::string csv = "iso_resonance_ratio,iso_kv_perfect_gears\n";
  constexpr int intervals = 400;
  for (int i = 0; i <= intervals; ++i) {
    const double n = n_max * i / intervals;
    csv +=
        number(n) + "," +
        number(
            iso_dynamic_factor_perfect_gears(n, scale.contact_ratio, scale.line_load_n_m).value) +
        "\n";
  }
  write_file_atomically(file.string(), csv);
}

Figure dynamic_factor_vs_iso_n(const std::string& name, const IsoScale& scale,
                               const std::string& data, int direction_column, int n_column,
                               int df_column, const std::string& band) {
  const std::string to_iso_n =
      number(scale.resonance_speed_rad_s / scale.resonance_speed_iso_stiffness_rad_s);
  char load[96];
  std::snprintf(load, sizeof load, "{/Symbol e}_{/Symbol a} %.3g, F_t/b %.3g N/mm",
                scale.contact_ratio, scale.line_load_n_m * 1e-3);
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
  f.series = {"'" + data + "' using (strcol(" + d + ") eq \"up\" ? $" + n + " : NaN):" + df +
                  " with linespoints pt 7 ps 0.6 lw 1.5 title 'simulated, sweep up'",
              "'" + data + "' using (strcol(" + d + ") eq \"down\" ? $" + n + " : NaN):" + df +
                  " with linespoints pt 6 ps 0.9 dt 2 title 'simulated, sweep down'",
              "'" + band +
                  "' using 1:2 with lines lw 2 lc rgb 'dark-red' title 'ISO K_v, perfect "
                  "gears (" +
                  std::string(load) + ")'"};
  return f;
}

}  // namespace gearimpact::cli
