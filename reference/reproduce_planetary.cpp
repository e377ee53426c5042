// The planetary section of `gearimpact reproduce` (docs/planetary.md): the linear stage's modes
// for the example system of Lin & Parker (1999) (examples/planetary_lp99.toml) with N = 3, 4 and
// 5 planets against the published frequencies, their types and multiplicities; the ring-housing
// sensor's spectrum of the nonlinear rotational stage of examples/planetary_stage_cracked_sun.toml,
// healthy (its [[faults]] left out) and with its cracked sun tooth, against the ring-sensor rule.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/planetary_file.hpp"
#include "gearimpact/modes/planetary.hpp"
#include "gearimpact/signals/fft.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

// Lin & Parker (1999), J. Vib. Acoust. 121:316-321, Table 2 (Lin's thesis Table C.1), as
// transcribed in gfsReboucas/Drivetrain-python tests/test_lin_parker_1999.py (the paper itself
// not read here), Hz: the rotational frequencies (the rigid mode first), the translational ones
// (each double) and the planet modes' (each N - 3 times, none for N = 3).
struct PublishedTable {
  int planets;
  std::vector<double> rotational;
  std::vector<double> translational;
};
const std::vector<PublishedTable> kPublished{{3,
                                              {0.0, 1475.7, 1930.3, 2658.3, 7462.8, 11775.3},
                                              {743.2, 1102.4, 1896.0, 2276.4, 6986.3, 9647.9}},
                                             {4,
                                              {0.0, 1536.6, 1970.6, 2625.7, 7773.6, 13071.1},
                                              {727.0, 1091.0, 1892.8, 2342.5, 7189.9, 10437.6}},
                                             {5,
                                              {0.0, 1567.4, 2006.1, 2614.8, 8065.4, 14253.1},
                                              {710.0, 1072.0, 1888.1, 2425.3, 7382.4, 11172.3}}};
const std::vector<double> kPublishedPlanet{1808.2, 5963.8, 6981.7};
constexpr const char* kPublishedSource =
    "Lin & Parker (1999), J. Vib. Acoust. 121:316-321, Table 2, as transcribed in "
    "Drivetrain-python";
// Printed to 0.1 Hz: half a unit of the last digit, plus the model's rounding (far below 1e-3 Hz).
constexpr double kPrintedHz = 0.0501;
// Three N = 4 entries (rotational 1536.6, translational 727.0 and 1091.0) that the model misses by
// 4.2e-5, 3.7e-4 and 1.5e-4 while it gives every other entry for N = 3, 4 and 5 to the printed
// digit (docs/planetary.md): held to 4e-4 relative as a known difference.
constexpr double kKnownRelative = 4e-4;
bool known_difference(int planets, StageModeType type, std::size_t i) {
  if (planets != 4) return false;
  if (type == StageModeType::rotational) return i == 1;
  return type == StageModeType::translational && (i == 0 || i == 1);
}

// A frequency of the stage: its value, multiplicity and type.
struct Group {
  double hz = 0.0;
  std::size_t multiplicity = 1;
  StageModeType type = StageModeType::mixed;
};

// The modes' distinct frequencies by type, ascending: the modes of one cluster (one frequency,
// one type) counted once.
std::vector<Group> groups(const PlanetaryModes& m) {
  std::vector<Group> g;
  for (const StageMode& mode : m.modes) {
    if (!g.empty() && g.back().type == mode.type &&
        std::fabs(g.back().hz - mode.frequency_hz) <= 1e-6 * std::max(1.0, mode.frequency_hz)) {
      continue;
    }
    g.push_back({mode.frequency_hz, mode.multiplicity, mode.type});
  }
  return g;
}

std::string joined(const std::vector<double>& values, int decimals) {
  std::string text;
  char buffer[64];
  for (double v : values) {
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    text += (text.empty() ? "" : ", ") + std::string(buffer);
  }
  return text;
}

// The modal part: a row per N and type against the published table, a row per N for the
// structure, and planetary_modes.csv with every distinct frequency.
void modal_rows(const PlanetaryParameters& lp99, ReportSection& section, std::string& csv) {
  for (const PublishedTable& table : kPublished) {
    PlanetaryParameters p = lp99;
    p.planet_angles_rad.clear();
    for (int i = 0; i < table.planets; ++i) {
      p.planet_angles_rad.push_back(2.0 * pi * i / table.planets);
    }
    const PlanetaryModes modes = planetary_modes(planetary_model(p));
    std::vector<double> rotational, translational, planet;
    bool multiplicities = true;
    const std::size_t planet_multiplicity = static_cast<std::size_t>(table.planets - 3);
    for (const Group& g : groups(modes)) {
      const std::string type(stage_mode_type_name(g.type));
      const std::vector<double>* paper = nullptr;
      std::size_t index = 0;
      if (g.type == StageModeType::rotational) {
        multiplicities = multiplicities && g.multiplicity == 1;
        index = rotational.size();
        rotational.push_back(g.hz);
        paper = &table.rotational;
      } else if (g.type == StageModeType::translational) {
        multiplicities = multiplicities && g.multiplicity == 2;
        index = translational.size();
        translational.push_back(g.hz);
        paper = &table.translational;
      } else if (g.type == StageModeType::planet) {
        multiplicities = multiplicities && g.multiplicity == planet_multiplicity;
        index = planet.size();
        planet.push_back(g.hz);
        paper = &kPublishedPlanet;
      } else {
        multiplicities = false;
      }
      char line[160];
      std::snprintf(
          line, sizeof line, "%d,%s,%zu,%.17g,%s\n", table.planets, type.c_str(), g.multiplicity,
          g.hz,
          paper != nullptr && index < paper->size() ? number((*paper)[index], 8).c_str() : "");
      csv += line;
    }
    const std::string n = std::to_string(table.planets);
    ReportRow structure;
    structure.id = "planetary_modes_structure_n" + n;
    structure.statement = "N = " + n +
                          ": distinct frequencies by type (rotational, translational, planet) "
                          "and their multiplicities (1, 2, N - 3)";
    structure.source = "Lin & Parker (1999), J. Vib. Acoust. 121:316-321, the modal structure";
    structure.paper = "6, 6, " + std::to_string(table.planets > 3 ? 3 : 0) + "; 1, 2, " +
                      std::to_string(planet_multiplicity);
    structure.ours = std::to_string(rotational.size()) + ", " +
                     std::to_string(translational.size()) + ", " + std::to_string(planet.size()) +
                     (multiplicities ? "; 1, 2, " + std::to_string(planet_multiplicity)
                                     : "; other multiplicities");
    structure.tolerance = "exact: counts";
    const bool counts = rotational.size() == 6 && translational.size() == 6 &&
                        planet.size() == (table.planets > 3 ? 3u : 0u);
    structure.verdict = counts && multiplicities ? Verdict::pass : Verdict::fail;
    section.rows.push_back(structure);

    struct Kind {
      const char* name;
      const std::vector<double>* ours;
      const std::vector<double>* paper;
      StageModeType type;
    };
    std::vector<Kind> kinds{
        {"rotational", &rotational, &table.rotational, StageModeType::rotational},
        {"translational", &translational, &table.translational, StageModeType::translational}};
    if (table.planets > 3) {
      kinds.push_back({"planet", &planet, &kPublishedPlanet, StageModeType::planet});
    }
    for (const Kind& kind : kinds) {
      ReportRow row;
      row.id = "planetary_modes_" + std::string(kind.name) + "_n" + n;
      row.statement = "N = " + n + ", " + kind.name + " frequencies (Hz)";
      row.source = kPublishedSource;
      row.paper = joined(*kind.paper, 1);
      row.ours = joined(*kind.ours, 3);
      row.tolerance = "± 0.05 Hz: the printed digit";
      bool printed = kind.ours->size() == kind.paper->size();
      bool within_known = printed;
      bool any_known = false;
      std::string missed;  // the entries of the known difference, each with its gap
      for (std::size_t i = 0; printed && i < kind.ours->size(); ++i) {
        const double ours = (*kind.ours)[i];
        const double paper = (*kind.paper)[i];
        const bool meets = std::fabs(ours - paper) <= kPrintedHz;
        if (!meets && known_difference(table.planets, kind.type, i)) {
          any_known = true;
          within_known = within_known && std::fabs(ours - paper) <= kKnownRelative * paper;
          missed += (missed.empty() ? "" : ", ") + number(paper, 5) + " by " +
                    number(std::fabs(ours - paper) / paper, 2);
        } else if (!meets) {
          printed = false;
        }
      }
      if (printed && !any_known) {
        row.verdict = Verdict::pass;
      } else if (printed && within_known) {
        row.verdict = Verdict::known_difference;
        row.tolerance += "; 4e-4 relative for the entries in the note";
        row.note = "missed (relative): " + missed +
                   "; the same model meets every other entry for N = 3, 4 and 5 to its digit, N "
                   "entering only through the planets' count and angles: taken to be the printed "
                   "table's or its transcription's (docs/planetary.md)";
      } else {
        row.verdict = Verdict::fail;
      }
      section.rows.push_back(row);
    }
  }
}

// The ring sensor's amplitude spectrum over the run's last `turns` carrier turns (bin k is
// carrier order k / turns, amplitude 2 |X_k| / n) and its largest lines on the comb of multiples
// of N carrier orders (the mean left out) and off it.
struct RingSpectrum {
  std::vector<double> amplitude;
  double on = 0.0;
  double off = 0.0;
};
constexpr int kTurns = 2;

RingSpectrum ring_spectrum(const PlanetaryStage& stage) {
  const TrainResult run = simulate_train(planetary_train(stage));
  const std::vector<double> y = planetary_ring_sensor(stage, run);
  // The rows per carrier turn at the rigid carrier speed: a whole number in the example file
  // (its sun speed sets a 30 ms turn of 7500 rows), so that each carrier order is a bin.
  const double row_s = run.series[1].t_s - run.series[0].t_s;
  const double turn_rows = 2.0 * pi / std::fabs(planetary_rigid_speeds(stage).carrier) / row_s;
  const auto rows = static_cast<std::size_t>(std::lround(turn_rows)) * kTurns;
  if (std::fabs(turn_rows - std::round(turn_rows)) > 1e-6 * turn_rows || rows >= y.size()) {
    throw std::runtime_error(
        "reproduce: the planetary stage's carrier turn is not a whole "
        "number of rows in its run (" +
        number(turn_rows, 10) + ")");
  }
  const std::vector<double> tail(y.end() - static_cast<std::ptrdiff_t>(rows), y.end());
  const std::vector<std::complex<double>> spectrum = signals::real_dft(tail);
  RingSpectrum s;
  const auto comb = static_cast<std::size_t>(stage.planets * kTurns);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const double a = (k == 0 ? 1.0 : 2.0) * std::abs(spectrum[k]) / static_cast<double>(rows);
    s.amplitude.push_back(a);
    if (k == 0) continue;
    double& line = k % comb == 0 ? s.on : s.off;
    line = std::max(line, a);
  }
  return s;
}

}  // namespace

ReportSection reproduce_planetary(const ReproduceContext& context) {
  ReportSection section;
  section.title = "Planetary stage (an extension)";
  std::string modes_csv = "planets,type,multiplicity,frequency_hz,paper_hz\n";
  modal_rows(parse_planetary(planetary_lp99_toml(), "planetary_lp99.toml").parameters, section,
             modes_csv);
  write_file_atomically((context.out / "planetary_modes.csv").string(), modes_csv);

  const PlanetaryStage cracked =
      parse_stage(planetary_stage_cracked_sun_toml(), "planetary_stage_cracked_sun.toml");
  PlanetaryStage healthy = cracked;
  healthy.faults.clear();
  const RingSpectrum h = ring_spectrum(healthy);
  const RingSpectrum c = ring_spectrum(cracked);
  // Up to 2.5 ring-mesh orders (the ring mesh's frequency is Z_r carrier orders, the ring held).
  const double last_order = 2.5 * cracked.teeth.ring;
  std::string csv = "carrier_order,healthy_N,cracked_sun_N\n";
  char line[128];
  const auto last_bin = static_cast<std::size_t>(std::lround(last_order * kTurns));
  for (std::size_t k = 0; k < h.amplitude.size() && k <= last_bin; ++k) {
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g\n", static_cast<double>(k) / kTurns,
                  h.amplitude[k], c.amplitude[k]);
    csv += line;
  }
  write_file_atomically((context.out / "planetary_ring_spectrum.csv").string(), csv);
  const std::string n = std::to_string(cracked.planets);
  render(context.out,
         Figure{"planetary_ring_spectrum",
                "Ring-housing sensor, last " + std::to_string(kTurns) +
                    " carrier turns: healthy stage and a cracked sun tooth",
                "frequency, carrier orders",
                "amplitude, N",
                {"set key below", "set grid", "set logscale y", "set format y '10^{%L}'",
                 "set xrange [0:" + number(last_order, 6) + "]",
                 // Ticks on the comb: every 9 N carrier orders.
                 "set xtics 0, " + std::to_string(9 * cracked.planets)},
                // Points, not impulses: on the log axis each of the 406 bins' lines would fill
                // the plot down to its bottom.
                {"'planetary_ring_spectrum.csv' using 1:3 with points pt 6 ps 0.6 lc rgb '#d62728' "
                 "title 'cracked sun tooth'",
                 "'planetary_ring_spectrum.csv' using 1:2 with points pt 7 ps 0.4 lc rgb 'black' "
                 "title 'healthy'"}});

  ReportRow healthy_row;
  healthy_row.id = "planetary_ring_sensor_healthy";
  healthy_row.statement =
      "healthy stage: the ring sensor's largest line off the multiples of N = " + n +
      " carrier orders over its largest on them";
  healthy_row.source = "the ring-sensor rule (docs/planetary.md, The ring-housing sensor)";
  healthy_row.paper = "0 (below 1e-8)";
  healthy_row.ours = number(h.off / h.on, 3);
  healthy_row.tolerance = "1e-8: rounding and the start's decay, measured 1e-10";
  healthy_row.verdict = h.off < 1e-8 * h.on ? Verdict::pass : Verdict::fail;
  section.rows.push_back(healthy_row);
  ReportRow cracked_row = healthy_row;
  cracked_row.id = "planetary_ring_sensor_cracked_sun";
  cracked_row.statement = "cracked sun tooth: the same ratio";
  cracked_row.paper = "above 1e-4";
  cracked_row.ours = number(c.off / c.on, 3);
  cracked_row.tolerance = "1e-4: four decades above the healthy bound";
  cracked_row.verdict = c.off > 1e-4 * c.on ? Verdict::pass : Verdict::fail;
  section.rows.push_back(cracked_row);

  section.text =
      "The linear stage of Lin & Parker (1999) (docs/planetary.md), their example system "
      "(examples/planetary_lp99.toml) with N = 3, 4 and 5 equally spaced planets: every distinct "
      "frequency with its type and multiplicity against the published table "
      "(`planetary_modes.csv`). Identical, equally spaced planets give 6 distinct rotational "
      "frequencies (the rigid mode at 0 Hz among them, the ring held), 6 double translational "
      "ones and 3 planet-mode frequencies of multiplicity N - 3.\n\n"
      "The nonlinear rotational stage of examples/planetary_stage_cracked_sun.toml (21/30/81, "
      "N = 3, ring held, contact loss, backlash and the meshes' stiffness tables), run as the "
      "file says and again with its [[faults]] left out: the ring-housing sensor's amplitude "
      "spectrum over the last " +
      std::to_string(kTurns) +
      " carrier turns, in carrier orders (`planetary_ring_spectrum.csv`, "
      "`planetary_ring_spectrum.png`). Identical, equally spaced planets repeat every 1/N of a "
      "carrier turn with the planets relabelled, so the healthy stage's sensor holds only "
      "multiples of N carrier orders; the cracked sun tooth meets a planet every Z_s / (N Z_r) of "
      "a turn and puts lines between them. The phasing rule (harmonic l of the meshes reaches "
      "only the modes of its type) is checked on the linear model and on nonlinear runs by the "
      "suites (docs/planetary.md), not here.\n";
  return section;
}

}  // namespace gearimpact::cli
