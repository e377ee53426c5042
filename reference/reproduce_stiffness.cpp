#include <string>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/comparison.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

std::string percent_of(double value, double reference) {
  const double p = 100.0 * (value / reference - 1.0);
  std::string text = number(p, 3);
  if (p >= 0.0) text.insert(0, 1, '+');
  text += " %";
  return text;
}

// 1/compliance in N/m, "-" for a term the model does not have.
std::string term_cell(const MeshStiffness& k, Term term, StiffnessModelKind kind) {
  if (!provides(kind, term)) return "-";
  return number(1.0 / k.pair.of(term), 4);
}

}  // namespace

ReportSection reproduce_stiffness(const ReproduceContext& context) {
  GearPair pair = paper_gear_pair();
  pair.bore_diameter1_m = 20e-3;
  pair.bore_diameter2_m = 60e-3;
  const StiffnessComparison comparison = compare_stiffness_models(pair, 400);

  std::vector<std::string> series;
  for (const ModelComparison& m : comparison.models) {
    const std::string stem = "stiffness_tvms_" + to_string(m.kind);
    write_file_atomically((context.out / (stem + ".csv")).string(), mesh_stiffness_csv(m.tvms));
    series.push_back(gnuplot_string(stem + ".csv") + " using 1:4 every ::1 with lines lw 2 title " +
                     gnuplot_string(to_string(m.kind)));
  }
  series.push_back(number(comparison.iso_single_n_per_m, 6) +
                   " with lines dt 2 lw 2 title \"ISO 6336-1 c' b\"");
  series.push_back(number(comparison.iso_mesh_n_per_m, 6) +
                   " with lines dt 3 lw 2 title 'ISO 6336-1 c_{/Symbol g}{/Symbol a} b'");
  render(context.out, {"stiffness_models",
                       "Mesh stiffness over one mesh period, paper's pair (bores 20/60 mm)",
                       "fraction of the mesh period",
                       "mesh stiffness (N/m)",
                       {"set key outside right top vertical", "set xrange [0:1]"},
                       series});

  ReportSection section;
  section.title = "Stiffness models and ISO 6336-1";
  const ModelComparison& pe = comparison.models[1];
  std::string text =
      "The paper's pair (20/80, m 2 mm, b 10 mm) with the bores of the ROSS peer run (20 mm, 60 "
      "mm) under the three named models and ISO 6336-1 method B (`stiffness_models.png`, data "
      "`stiffness_tvms_<model>.csv`). ISO is an empirical fit with a scatter of its own: a band, "
      "not an identity.";
  if (!pe.tvms.foundation_extrapolations.empty()) {
    text +=
        " Warning: " + foundation_extrapolation_warning(pe.tvms.foundation_extrapolations) + ".";
  }
  text += "\n\nOver one mesh period (N/m; per cent against ISO's c_gamma_alpha b = " +
          number(comparison.iso_mesh_n_per_m, 4) +
          " for the mean, c' b = " + number(comparison.iso_single_n_per_m, 4) +
          " for the minimum):\n\n";
  text += "| model | min | max | mean | min vs c' b | mean vs c_gamma_alpha b |\n";
  text += "|---|---|---|---|---|---|\n";
  for (const ModelComparison& m : comparison.models) {
    text += "| " + to_string(m.kind) + " | " + number(m.tvms.min_n_per_m, 4) + " | " +
            number(m.tvms.max_n_per_m, 4) + " | " + number(m.tvms.mean_n_per_m, 4) + " | " +
            percent_of(m.tvms.min_n_per_m, comparison.iso_single_n_per_m) + " | " +
            percent_of(m.tvms.mean_n_per_m, comparison.iso_mesh_n_per_m) + " |\n";
  }
  text +=
      "\nOne pair at the pitch point, stiffness of each term (N/m, both teeth in series; "
      "\"-\": not in the model):\n\n";
  text += "| model | hertz | bending | axial | shear | foundation | pair |\n";
  text += "|---|---|---|---|---|---|---|\n";
  for (const ModelComparison& m : comparison.models) {
    const MeshStiffness& k = m.at_pitch_point;
    text += "| " + to_string(m.kind) + " | " + term_cell(k, Term::hertz, m.kind) + " | " +
            term_cell(k, Term::bending, m.kind) + " | " + term_cell(k, Term::axial, m.kind) +
            " | " + term_cell(k, Term::shear, m.kind) + " | " +
            term_cell(k, Term::foundation, m.kind) + " | " + number(k.ke, 4) + " |\n";
  }
  section.text = text;
  return section;
}

}  // namespace gearimpact::cli
