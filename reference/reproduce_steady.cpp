// The steady state of the loaded pair (docs/steady-state.md sections 3.5 and 4): the paper's pair
// with its time-varying stiffness, swept in w1 up and down through ISO's N = 1/2, 1 and 2.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/batch/steady_sweep.hpp"
#include "gearimpact/dynamics/mesh.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/paper/table1.hpp"
#include "gearimpact/steady/iso_resonance.hpp"
#include "gearimpact/steady/sweep.hpp"
#include "iso_plot.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

constexpr double static_force_n = 1000.0;

// The paper's pair loaded by static_force_n, with the viscous mesh damper and no Hertzian damping;
// at the static deflection of the stiffest mesh, so that the first point starts in contact.
SimulationCase loaded_pair(double w1_rad_per_s) {
  PairLoad load;
  load.static_force_n = static_force_n;
  load.damping_update = DampingUpdate::off;
  load.deflection_stiffness_n_per_m = 1e9;
  return loaded_paper_pair(w1_rad_per_s, load);
}

struct Row {
  double n = 0.0;
  double n_iso = 0.0;
  const SweepPointResult* r = nullptr;
};

std::string regime_of(const SweepPointResult& r) {
  return r.point.converged ? to_string(r.point.regime) : "not converged";
}

double amplitude_of(const SweepPointResult& r) {
  return r.point.dte_amplitude_m.value_or(NAN);
}

std::string df_text(const SweepPointResult& r) {
  return r.point.dynamic_factor ? number(*r.point.dynamic_factor, 3) : "-";
}

// Jumps along the sweep's own order: neighbours whose DTE amplitudes differ by more than 2x (on
// this grid the smooth stretches change by at most about 1.5x per step, measured; a steep but
// continuous rise where contact is first lost can still pass 2x, so the up and down columns
// together tell a jump with hysteresis from a steep rise).
std::string jumps(const std::vector<Row>& rows, bool up) {
  std::string text;
  const int n = static_cast<int>(rows.size());
  for (int k = 1; k < n; ++k) {
    const Row& from = rows[static_cast<std::size_t>(up ? k - 1 : n - k)];
    const Row& to = rows[static_cast<std::size_t>(up ? k : n - k - 1)];
    const double a = amplitude_of(*from.r);
    const double b = amplitude_of(*to.r);
    if (!(a > 0.0 && b > 0.0) || std::max(a / b, b / a) <= 2.0) continue;
    text += (text.empty() ? "" : "; ") + number(from.r->value_si, 5) + " to " +
            number(to.r->value_si, 5) + " rad/s (N " + number(from.n, 3) + " to " +
            number(to.n, 3) + "): " + number(a * 1e6, 3) + " to " + number(b * 1e6, 3) + " um";
  }
  return text.empty() ? "none" : text;
}

std::string first_contact_loss(const std::vector<Row>& rows, bool up) {
  const int n = static_cast<int>(rows.size());
  for (int k = 0; k < n; ++k) {
    const Row& row = rows[static_cast<std::size_t>(up ? k : n - 1 - k)];
    if (row.r->point.converged && row.r->point.regime != Regime::no_impact) {
      return number(row.r->value_si, 5) + " rad/s (N " + number(row.n, 3) + ", " +
             regime_of(*row.r) + ")";
    }
  }
  return "none";
}

std::string peak(const std::vector<Row>& rows) {
  const Row* best = nullptr;
  for (const Row& row : rows) {
    if (!row.r->point.dynamic_factor) continue;
    if (best == nullptr || *row.r->point.dynamic_factor > *best->r->point.dynamic_factor) {
      best = &row;
    }
  }
  if (best == nullptr) return "-";
  return df_text(*best->r) + " at N " + number(best->n, 3) + " (" + number(best->r->value_si, 5) +
         " rad/s)";
}

}  // namespace

ReportSection reproduce_steady_state(const ReproduceContext& context) {
  const auto started = std::chrono::steady_clock::now();
  const SimulationCase base = loaded_pair(1000.0);
  const auto table = context.pool->table_for(base);
  const IsoScale iso = *iso_scale(base, *table);
  // Where the model's undamped resonance z1 w1 = w_n falls on the N axis.
  const double resonance_n = natural_frequency_rad_per_s(base, *table) /
                             (base.gears.teeth1 * iso.resonance_speed_rad_per_s);
  // N from 0.3 to 2.3 in steps of 0.05: N = 1/2, 1 and 2 are grid points.
  SteadySweepSpec spec;
  spec.base = base;
  spec.vary = "initial.w1";
  spec.from_si = 0.3 * iso.resonance_speed_rad_per_s;
  spec.to_si = 2.3 * iso.resonance_speed_rad_per_s;
  spec.points = 41;
  const SteadySweep sweep = run_steady_sweep(spec, *context.pool);
  // Each direction in the order it ran: up in ascending w1, down in descending.
  std::vector<SweepPointResult> up;
  std::vector<SweepPointResult> down;
  for (const SweepPointResult& r : sweep.rows) {
    (r.direction == SweepDirection::up ? up : down).push_back(r);
  }
  std::reverse(down.begin(), down.end());
  const std::size_t points = static_cast<std::size_t>(spec.points);
  // Both in ascending w1, as the grid.
  std::vector<Row> up_rows(points);
  std::vector<Row> down_rows(points);
  std::string csv =
      "direction,index,w1_rad_s,iso_resonance_ratio,iso_resonance_ratio_iso_stiffness,regime,"
      "period,dte_amplitude_m,dynamic_factor,impacts_drive_per_period,impacts_coast_per_period\n";
  const auto optional_text = [](const std::optional<double>& v) {
    return v ? number(*v, 10) : std::string();
  };
  for (const std::vector<SweepPointResult>* line : {&up, &down}) {
    for (const SweepPointResult& r : *line) {
      Row row;
      row.n = iso_resonance_ratio(r.value_si, iso.resonance_speed_rad_per_s);
      row.n_iso = iso_resonance_ratio(r.value_si, iso.resonance_speed_iso_stiffness_rad_per_s);
      row.r = &r;
      (line == &up ? up_rows : down_rows)[static_cast<std::size_t>(r.index)] = row;
      const SteadyPoint& p = r.point;
      csv += to_string(r.direction) + "," + std::to_string(r.index) + "," + number(r.value_si, 10) +
             "," + number(row.n, 10) + "," + number(row.n_iso, 10) + "," +
             (p.converged ? to_string(p.regime) : "") + "," + period_label(p) + "," +
             optional_text(p.dte_amplitude_m) + "," + optional_text(p.dynamic_factor) + "," +
             optional_text(p.impacts_drive_per_period) + "," +
             optional_text(p.impacts_coast_per_period) + "\n";
    }
  }
  write_file_atomically((context.out / "steady_state.csv").string(), csv);
  write_iso_kv_band(context.out / "steady_state_iso_kv_band.csv", iso, 2.5);
  render(context.out,
         dynamic_factor_vs_iso_n("steady_state_dynamic_factor", iso, "steady_state.csv", 1, 4, 9,
                                 "steady_state_iso_kv_band.csv", true));
  Figure regimes;
  regimes.name = "steady_state_regimes";
  regimes.title = "Steady DTE amplitude and regime, loaded pair swept in w1";
  regimes.x_label = "N = w_1 / w_{E1}, c_{/Symbol ga} b = the model's mean mesh stiffness";
  regimes.y_label = "half peak-to-peak of s (um)";
  regimes.setup = {"set key outside bottom center horizontal", "set cbrange [-0.5:3.5]",
                   "set palette maxcolors 4 defined (0 'web-blue', 1 'dark-orange', 2 'red', 3 "
                   "'gray')",
                   "set cbtics ('NI' 0, 'SS' 1, 'DS' 2, 'NC' 3)",
                   "set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb 'gray30'"};
  const std::string regime_code =
      "(strcol(6) eq \"NI\" ? 0 : strcol(6) eq \"SS\" ? 1 : strcol(6) eq \"DS\" ? 2 : 3)";
  regimes.series = {
      "'steady_state.csv' using (strcol(1) eq \"up\" ? $4 : NaN):($8 * 1e6) with lines lc rgb "
      "'gray50' title 'sweep up'",
      "'steady_state.csv' using (strcol(1) eq \"down\" ? $4 : NaN):($8 * 1e6) with lines dt 2 lc "
      "rgb 'gray50' title 'sweep down'",
      "'steady_state.csv' using (strcol(1) eq \"up\" ? $4 : NaN):($8 * 1e6):" + regime_code +
          " with points pt 7 ps 1.0 palette notitle",
      "'steady_state.csv' using (strcol(1) eq \"down\" ? $4 : NaN):($8 * 1e6):" + regime_code +
          " with points pt 6 ps 1.6 palette notitle"};
  render(context.out, regimes);
  const double took_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  ReportSection section;
  section.title = "Steady state of the loaded pair";
  std::string text =
      "The paper's pair with its time-varying mesh stiffness, loaded with a static force of " +
      number(static_force_n, 4) +
      " N on the line of action (balanced torques), no friction (a steady state needs none), the "
      "viscous mesh damper at zeta = 0.05 and no Hertzian damping, swept in w1 up and down "
      "(each point continued from the previous one's state) over N = 0.3 to 2.3 in steps of "
      "0.05 (`steady_state.csv`, `steady_state_dynamic_factor.png`, "
      "`steady_state_regimes.png`). N = w1 / w_E1 of ISO 6336-1 method B with c_gamma_alpha b "
      "= the model's mean mesh stiffness (w_E1 = " +
      number(iso.resonance_speed_rad_per_s, 5) +
      " rad/s), so that the model's resonance z1 w1 = sqrt(k_mean / m_e) sits at N = "
      "(d_m1 / d_1)^2 = " +
      number(resonance_n, 3) + "; with ISO's own c_gamma_alpha w_E1 = " +
      number(iso.resonance_speed_iso_stiffness_rad_per_s, 5) +
      " rad/s. Hertzian damping is off because with D frozen at 0.1 m/s it keeps the teeth in "
      "contact at every speed of this range (dynamic factor at most about 2, "
      "verify/steady/test_iso_main_resonance.cpp), so no regime would change. The dynamic "
      "factor is the largest mesh force over the static load (`steady_state.csv`); the figure "
      "also draws it over the quasi-static peak, " +
      number(iso.quasi_static_force_ratio, 4) +
      " times the static load (where a pair enters, the loaded pairs keep their deflection for "
      "an instant: K_after / K_before), which tends to 1 at N -> 0 where ISO's K_v does. ISO's "
      "K_v "
      "(perfect gears, eps_alpha " +
      number(iso.contact_ratio, 3) + ", F_t/b " + number(iso.line_load_n_per_m * 1e-3, 3) +
      " N/mm) is a band to compare with, not a tolerance. Computed in " + number(took_s, 2) +
      " s.\n\n";
  text += "| quantity | sweep up | sweep down | ISO 6336-1, perfect gears |\n|---|---|---|---|\n";
  text += "| jumps of the DTE amplitude (> 2x between grid points) | " + jumps(up_rows, true) +
          " | " + jumps(down_rows, false) + " | - |\n";
  text += "| first contact loss along the sweep | " + first_contact_loss(up_rows, true) + " | " +
          first_contact_loss(down_rows, false) + " | - |\n";
  text +=
      "| largest dynamic factor | " + peak(up_rows) + " | " + peak(down_rows) + " | " +
      number(iso_dynamic_factor_perfect_gears(1.0, iso.contact_ratio, iso.line_load_n_per_m).value,
             3) +
      " in the main resonance range |\n";
  for (const double n : {0.5, 1.0, 2.0}) {
    const auto at = [&](const std::vector<Row>& rows) {
      for (const Row& row : rows) {
        if (std::fabs(row.n - n) < 1e-9) return df_text(*row.r) + " (" + regime_of(*row.r) + ")";
      }
      return std::string("-");
    };
    text +=
        "| dynamic factor at N = " + number(n, 2) + " | " + at(up_rows) + " | " + at(down_rows) +
        " | " +
        number(iso_dynamic_factor_perfect_gears(n, iso.contact_ratio, iso.line_load_n_per_m).value,
               3) +
        " |\n";
  }
  text +=
      "\nThe paper's runs in ISO's N:\n\n| w1 (rad/s) | N, c_gamma_alpha b = the model's mean "
      "stiffness | N, ISO's own c_gamma_alpha |\n|---|---|---|\n";
  for (const double w1 : {1000.0, 10000.0}) {
    text += "| " + number(w1, 5) + " | " +
            number(iso_resonance_ratio(w1, iso.resonance_speed_rad_per_s), 3) + " | " +
            number(iso_resonance_ratio(w1, iso.resonance_speed_iso_stiffness_rad_per_s), 3) +
            " |\n";
  }
  section.text = text;
  return section;
}

}  // namespace gearimpact::cli
