// The readings docs/model.md leaves open, run side by side and scored against the
// paper's statements; and case 3 as an ensemble of slightly perturbed runs.
#include <algorithm>
#include <cmath>
#include <future>
#include <map>
#include <string>
#include <vector>

#include "gearimpact/case/simulation_case.hpp"
#include "gearimpact/dynamics/simulate.hpp"
#include "gearimpact/paper/scoring.hpp"
#include "gearimpact/paper/statements.hpp"
#include "gearimpact/paper/table1.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

struct NamedReading {
  std::string name;
  PaperReading reading;
};

std::vector<NamedReading> readings() {
  std::vector<NamedReading> list{{"default (docs/model.md)", {}}};
  const auto with = [&](const std::string& name, auto change) {
    PaperReading r;
    change(r);
    list.push_back({name, r});
  };
  with("(32) Hunt-Crossley", [](PaperReading& r) { r.damping_form = DampingForm::hunt_crossley; });
  with("(32) Lee-Wang", [](PaperReading& r) { r.damping_form = DampingForm::lee_wang; });
  with("D from Kh", [](PaperReading& r) { r.damping_stiffness = DampingStiffness::hertz; });
  with("D from the pitch pair at impact",
       [](PaperReading& r) { r.damping_stiffness = DampingStiffness::pitch_pair_at_impact; });
  with("(33) p = 0.36", [](PaperReading& r) { r.restitution.exponent = 0.36; });
  with("(33) Vi in in/s", [](PaperReading& r) { r.restitution.speed_unit_m_s = 0.0254; });
  with("(33) Vi in m/s", [](PaperReading& r) { r.restitution.speed_unit_m_s = 1.0; });
  with("torques in N-mm", [](PaperReading& r) { r.torque_unit = TorqueUnit::n_mm; });
  with("case 3 W = 1000 rad/s",
       [](PaperReading& r) { r.case3_angular_frequency_rad_per_s = 1000.0; });
  with("coast contacts in phase (literal (9))",
       [](PaperReading& r) { r.coast_phase = CoastPhase::in_phase; });
  return list;
}

struct Score {
  std::vector<double> damping_over_friction;  // case 1, 2, 3 at f = 0.01 and 0.09
  double last_n2_ms = 0.0;
  StatementTally tally;
};

// The runs a reading is scored on, submitted to the pool.
struct ReadingRuns {
  FrictionSweep sweep;
  std::shared_future<SimulationResult> case2;
};

ReadingRuns submit_reading(const PaperReading& reading, const ReproduceContext& context) {
  std::vector<SimulationCase> cases;
  for (int case_number = 1; case_number <= 3; ++case_number) {
    cases.push_back(paper_case(case_number, reading));
  }
  return {FrictionSweep(*context.pool, cases, 0.01, 0.09 + 1e-9, 0.08),
          context.pool->submit(cases[1], false)};
}

Score score(const ReadingRuns& runs, const std::map<std::string, PaperStatement>& statements) {
  const std::vector<SweepRow> rows = runs.sweep.get();
  const SimulationResult& case2 = runs.case2.get();
  Score s;
  for (std::size_t k = 0; k < 3; ++k) {
    for (const bool largest : {false, true}) {
      const double value = damping_over_friction(rows, k, largest ? 0.09 : 0.01);
      s.damping_over_friction.push_back(value);
      const PaperStatement& statement =
          statements.at(fig7_statement_id(static_cast<int>(k + 1), largest));
      s.tally.add(statement, value, statement.paper_low);
    }
  }
  s.last_n2_ms = case2.summary.last_n2_impact_s.value_or(0.0) * 1e3;
  const PaperStatement& last_n2 = statements.at("case2_last_n2_impact");
  s.tally.add(last_n2, s.last_n2_ms, last_n2.paper_low);
  return s;
}

}  // namespace

ReportSection reproduce_readings(const ReproduceContext& context) {
  const auto statements = read_statements(context.paper_data / "dynamics_statements.csv");
  ReportSection section;
  section.title = "The open readings, side by side";
  section.text =
      "Each reading changes one choice of the default and is scored against seven statements: "
      "damping loss / friction loss of each case at f = 0.01 and 0.09 (paper: 67 and 7 for cases 1 "
      "and 3, 29 and 3 for case 2) and case 2's last N2 impact (paper: about 5 ms), each with the "
      "tolerance of `paper_data/dynamics_statements.csv`. The sign of the Fa h moment is scored "
      "in the Fig. 8 section (it changes the stiffness, not the dissipation).\n\n"
      "| reading | case 1: 0.01 / 0.09 | case 2: 0.01 / 0.09 | case 3: 0.01 / 0.09 | last N2 "
      "impact, case 2 | statements met | mean, worst (tolerances off) "
      "|\n|---|---|---|---|---|---|---|\n";
  const std::vector<NamedReading> list = readings();
  // Every reading's runs first, so that the pool has them all at once.
  std::vector<ReadingRuns> runs;
  for (const NamedReading& r : list) runs.push_back(submit_reading(r.reading, context));
  std::vector<Score> scores;
  for (const ReadingRuns& r : runs) scores.push_back(score(r, statements));
  std::size_t best = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Score& s = scores[i];
    section.text +=
        "| " + list[i].name + " | " + number(s.damping_over_friction[0], 3) + " / " +
        number(s.damping_over_friction[1], 3) + " | " + number(s.damping_over_friction[2], 3) +
        " / " + number(s.damping_over_friction[3], 3) + " | " +
        number(s.damping_over_friction[4], 3) + " / " + number(s.damping_over_friction[5], 3) +
        " | " + number(s.last_n2_ms, 3) + " ms | " + std::to_string(s.tally.met) + " of " +
        std::to_string(s.tally.count) + " | " + number(s.tally.mean_tolerances_off(), 3) + ", " +
        number(s.tally.worst_tolerances_off, 3) + " |\n";
    const Score& b = scores[best];
    if (s.tally.met > b.tally.met ||
        (s.tally.met == b.tally.met &&
         s.tally.mean_tolerances_off() < b.tally.mean_tolerances_off())) {
      best = i;
    }
  }
  // The paper's values are "about" values with tolerances of a fifth or so;
  // a reading that beats the default by less than a quarter of a tolerance on
  // average, at an equal count of statements met, is not told apart by them.
  constexpr double decisive_margin = 0.25;
  const Score& d = scores[0];
  const Score& b = scores[best];
  const bool evidence_for_change =
      b.tally.met > d.tally.met ||
      (b.tally.met == d.tally.met &&
       d.tally.mean_tolerances_off() - b.tally.mean_tolerances_off() > decisive_margin);
  section.text +=
      "\nBest (most statements met, then the smallest mean miss): **" + list[best].name + "**, " +
      std::to_string(b.tally.met) + " of " + std::to_string(b.tally.count) +
      " statements met, mean " + number(b.tally.mean_tolerances_off(), 3) +
      " tolerances off; the default: " + std::to_string(d.tally.met) + " of " +
      std::to_string(d.tally.count) + ", mean " + number(d.tally.mean_tolerances_off(), 3) +
      ". The default changes only for a reading that meets more statements, or as "
      "many with a mean miss smaller by more than " +
      number(decisive_margin, 2) +
      " tolerances (the paper's 'about' values cannot tell smaller differences "
      "apart). " +
      (evidence_for_change
           ? "**The evidence favours " + list[best].name +
                 " over the default**: see the README on why the default stays or goes.\n"
           : std::string("Verdict: the default stands.\n"));
  return section;
}

namespace {

// s of a series at times visited in increasing order: the first row at or
// after t is found by walking on from the previous one, not by a search.
class SeriesCursor {
 public:
  explicit SeriesCursor(const std::vector<SeriesRow>& rows) : rows_(rows) {}
  double s_at(double t) {
    while (next_ < rows_.size() && rows_[next_].t_s < t) ++next_;
    if (next_ == 0) return rows_.front().s_m;
    if (next_ == rows_.size()) return rows_.back().s_m;
    const SeriesRow& b = rows_[next_];
    const SeriesRow& a = rows_[next_ - 1];
    return a.s_m + (b.s_m - a.s_m) * (t - a.t_s) / (b.t_s - a.t_s);
  }

 private:
  const std::vector<SeriesRow>& rows_;
  std::size_t next_ = 0;
};

std::string spread(const std::vector<double>& values, int digits) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return number(*low, digits) + " to " + number(*high, digits);
}

}  // namespace

ReportSection reproduce_case3_ensemble(const ReproduceContext& context) {
  ReportSection section;
  section.title = "Case 3 as an ensemble";
  constexpr int members = 8;
  // 2e-8 rad of gear 1 moves s by 0.38 nm, 8e-6 of the backlash and far
  // below any manufacturing tolerance: runs that part over such a change are
  // sensitive to their initial state.
  const double perturbation_rad = 2e-8;
  // The runs have parted when their s differ by 1 % of the backlash.
  const double parted_m = 0.01 * paper_gear_pair().backlash_m;
  section.text =
      "Case 3 is run " + std::to_string(members) + " times with theta1(0) = k " +
      number(perturbation_rad, 2) + " rad (s(0) = k " +
      number(perturbation_rad * base_radius(paper_gear_pair(), Gear::one) * 1e9, 2) +
      " nm), k = 0.." + std::to_string(members - 1) +
      ". Robust quantities (first impact, peak penetration) are given as numbers, long-time ones "
      "(impact count, losses, the Fig. 7 ratio at f = 0.04) as the ensemble's range. 'Runs part' "
      "is the first time two members' s differ by 1 % of the backlash.\n\n"
      "| torques | first impact | first impact speed | peak penetration | impacts | damping loss "
      "(J) | friction loss (J) | friction / damping | runs part at |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  const std::vector<TorqueUnit> units{TorqueUnit::kgf_mm, TorqueUnit::n_mm};
  // Every member of both ensembles first, so that the pool has them all at once.
  std::vector<std::vector<std::shared_future<SimulationResult>>> runs(units.size());
  for (std::size_t u = 0; u < units.size(); ++u) {
    PaperReading reading;
    reading.torque_unit = units[u];
    for (int k = 0; k < members; ++k) {
      SimulationCase c = paper_case(3, reading);
      c.initial.theta1_rad = k * perturbation_rad;
      runs[u].push_back(context.pool->submit(c, true));
    }
  }
  for (std::size_t u = 0; u < units.size(); ++u) {
    const TorqueUnit unit = units[u];
    std::vector<const SimulationResult*> results;
    for (const auto& run : runs[u]) results.push_back(&run.get());
    std::vector<double> first_impact;
    std::vector<double> first_speed;
    std::vector<double> peak;
    std::vector<double> impacts;
    std::vector<double> damping;
    std::vector<double> friction;
    std::vector<double> ratio;
    double parting_s = -1.0;
    for (const SimulationResult* member : results) {
      const SimulationResult& r = *member;
      const SimulationSummary& s = r.summary;
      first_impact.push_back(s.first_impact_s.value_or(0.0) * 1e3);
      first_speed.push_back(s.first_impact_speed_m_s.value_or(0.0));
      peak.push_back(s.max_penetration_m * 1e6);
      impacts.push_back(s.impacts_n1 + s.impacts_n2);
      damping.push_back(s.damping_loss_j);
      friction.push_back(s.friction_loss_j);
      ratio.push_back(s.damping_loss_j > 0.0 ? s.friction_loss_j / s.damping_loss_j : 0.0);
      SeriesCursor member_s(r.series);
      for (const SeriesRow& row : results.front()->series) {
        if (parting_s >= 0.0 && row.t_s >= parting_s) break;
        if (std::abs(member_s.s_at(row.t_s) - row.s_m) > parted_m) {
          parting_s = row.t_s;
          break;
        }
      }
    }
    section.text +=
        std::string("| ") + (unit == TorqueUnit::kgf_mm ? "kgf-mm (default)" : "N-mm") + " | " +
        spread(first_impact, 4) + " ms | " + spread(first_speed, 4) + " m/s | " + spread(peak, 4) +
        " um | " + spread(impacts, 3) + " | " + spread(damping, 3) + " | " + spread(friction, 3) +
        " | " + spread(ratio, 3) + " | " +
        (parting_s < 0.0 ? "never within the run" : number(parting_s * 1e3, 3) + " ms") + " |\n";
  }
  return section;
}

}  // namespace gearimpact::cli
