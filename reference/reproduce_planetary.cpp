// The planetary section of `gearimpact reproduce` (docs/planetary.md): the linear stage's modes
// for the example system of Lin & Parker (1999) (examples/planetary_lp99.toml) with N = 3, 4 and
// 5 planets against the published frequencies, their types and multiplicities; the ring-housing
// sensor's spectrum of the nonlinear rotational stage of examples/planetary_stage_cracked_sun.toml,
// healthy (its [[faults]] left out) and with its cracked sun tooth, against the ring-sensor rule;
// the phasing rule on a nonlinear run of the same stage with other tooth counts and N = 4.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/dynamics/planetary_train.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/planetary.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/planetary_file.hpp"
#include "gearimpact/modes/planetary.hpp"
#include "gearimpact/paper/lin_parker_1999.hpp"
#include "gearimpact/signals/fft.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

namespace {

// The published table is paper/lin_parker_1999.hpp's; its source, as a row names it.
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
  const std::vector<double> published_planet(kLinParker1999Planet.begin(),
                                             kLinParker1999Planet.end());
  for (const LinParker1999Table& published : kLinParker1999) {
    struct {
      int planets;
      std::vector<double> rotational, translational;
    } table{published.planets,
            {published.rotational.begin(), published.rotational.end()},
            {published.translational.begin(), published.translational.end()}};
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
        paper = &published_planet;
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
      kinds.push_back({"planet", &planet, &published_planet, StageModeType::planet});
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

// The phasing rule on a nonlinear run: the stage of the ring-sensor runs with 26/22/70 teeth and
// N = 4 planets (Z_s mod N = 2: the odd harmonics excite planet modes only, the even ones the
// rotational modes), the sun driven so that a mesh period is T_m = N M h (M = 100 steps of 1 us),
// so that the shift of k T_m / N that relabels the planets lies on the step grid; the carrier
// loaded with 1000 N m so that every mesh stays on its drive line. After k T_m / N the stage's
// state repeats with the planets relabelled and the equations, nonlinear as they are, are unchanged
// by it: the sun meshes' summed force holds harmonic l of one mesh's force times
// sum_n exp(-2 pi i l gamma_n), N times it in phase and 0 off the rule, as does the carrier.
// Left over: the start's asymmetric part, decayed by the mesh damper over 4 ms, and rounding.
struct PhasingLine {
  int harmonic = 0;
  HarmonicType type = HarmonicType::planet;
  double sum_over_singles = 0.0;  // |sum of the N sun meshes' line| / sum of each line's |.|
  double carrier = 0.0;           // the carrier speed's line over its harmonic-2 line
};
constexpr int kPhasingHarmonics = 6;

std::vector<PhasingLine> phasing_lines(PlanetaryStage stage, bool& drive_contact) {
  constexpr int kSun = 26, kPlanet = 22, kRing = 70, kPlanets = 4;
  constexpr double kStep = 1.0e-6;
  constexpr int kPerPeriod = kPlanets * 100;
  constexpr int kPeriods = 4;
  const double tm = kPerPeriod * kStep;
  // w_s - w_c = 2 pi / (Z_s T_m), and w_c = w_s Z_s / (Z_s + Z_r) with the ring held.
  const double ws = 2.0 * pi / (kSun * tm) * (kSun + kRing) / kRing;
  stage.teeth = {kSun, kPlanet, kRing};
  stage.planets = kPlanets;
  stage.planet_angles_rad.clear();
  stage.faults.clear();
  stage.held = HeldMember::ring;
  stage.input_speed_rad_per_s = ws;
  stage.sun_torque.mean_speed_rad_per_s = ws;
  stage.carrier_torque.kind = Torque::Kind::constant;
  stage.carrier_torque.constant_n_m = -1000.0;
  stage.integrator.step_s = kStep;
  stage.integrator.output_every = 1;
  stage.integrator.end_time_s = 0.004 + kPeriods * tm;
  const TrainResult run = simulate_train(planetary_train(stage));
  const auto m = static_cast<std::size_t>(kPeriods * kPerPeriod);
  const std::size_t first = run.series.size() - m;
  std::vector<std::vector<double>> force(kPlanets, std::vector<double>(m));
  std::vector<double> sum(m, 0.0), carrier(m);
  drive_contact = true;
  for (std::size_t i = 0; i < m; ++i) {
    const TrainRow& row = run.series[first + i];
    for (const TrainMeshRow& q : row.meshes) {
      drive_contact = drive_contact && q.region == static_cast<int>(Region::n1);
    }
    for (std::size_t k = 0; k < force.size(); ++k) {
      force[k][i] = row.meshes[k].normal_force_n;  // sun-planet k + 1
      sum[i] += force[k][i];
    }
    carrier[i] = row.w_rad_per_s[kCarrierBody];
  }
  const std::vector<std::complex<double>> total = signals::real_dft(sum);
  const std::vector<std::complex<double>> turning = signals::real_dft(carrier);
  std::vector<std::vector<std::complex<double>>> single;
  for (const std::vector<double>& f : force) single.push_back(signals::real_dft(f));
  std::vector<PhasingLine> lines;
  for (int l = 1; l <= kPhasingHarmonics; ++l) {
    const auto bin = static_cast<std::size_t>(l * kPeriods);
    double singles = 0.0;
    for (const auto& f : single) singles += std::abs(f[bin]);
    lines.push_back({l, harmonic_type(l, kSun, kPlanets), std::abs(total[bin]) / singles,
                     std::abs(turning[bin]) / std::abs(turning[2 * kPeriods])});
  }
  return lines;
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
                {"set key below", "set logscale y", "set format y '10^{%L}'",
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

  bool drive_contact = false;
  const std::vector<PhasingLine> lines = phasing_lines(healthy, drive_contact);
  std::string phasing = "harmonic,type,sum_over_singles,carrier_over_harmonic2\n";
  double in_phase = 0.0;  // the largest |sum / singles - 1| of the harmonics with l Z_s / N whole
  double off_rule = 0.0;  // the largest sum / singles, and carrier ratio, of the others
  for (const PhasingLine& q : lines) {
    const char* type = q.type == HarmonicType::rotational      ? "rotational"
                       : q.type == HarmonicType::translational ? "translational"
                                                               : "planet";
    std::snprintf(line, sizeof line, "%d,%s,%.17g,%.17g\n", q.harmonic, type, q.sum_over_singles,
                  q.carrier);
    phasing += line;
    if (q.type == HarmonicType::rotational) {
      in_phase = std::max(in_phase, std::fabs(q.sum_over_singles - 1.0));
    } else {
      off_rule = std::max({off_rule, q.sum_over_singles, q.carrier});
    }
  }
  write_file_atomically((context.out / "planetary_phasing.csv").string(), phasing);
  ReportRow in_row;
  in_row.id = "planetary_phasing_in_phase";
  in_row.statement =
      "26/22/70, N = 4, nonlinear run: at the mesh harmonics l = 2, 4, 6 (l Z_s / N whole) the "
      "sun meshes' summed force line over the sum of their single lines";
  in_row.source = "the phasing rule (docs/planetary.md, Mesh phases and the type of a harmonic)";
  in_row.paper = "1";
  in_row.ours =
      "1 within " + number(in_phase, 2) + (drive_contact ? "" : " (left the drive lines)");
  in_row.tolerance = "1e-6: rounding and the start's decay";
  in_row.verdict = in_phase < 1e-6 && drive_contact ? Verdict::pass : Verdict::fail;
  section.rows.push_back(in_row);
  ReportRow off_row = in_row;
  off_row.id = "planetary_phasing_off_rule";
  off_row.statement =
      "the same run at l = 1, 3, 5 (planet-mode harmonics): the summed force's line over the "
      "single lines' sum, and the carrier speed's line over its l = 2 line, the larger";
  off_row.paper = "0 (below 1e-8)";
  off_row.ours = number(off_rule, 3);
  off_row.tolerance = "1e-8: rounding and the start's decay, measured 1e-11";
  off_row.verdict = off_rule < 1e-8 && drive_contact ? Verdict::pass : Verdict::fail;
  section.rows.push_back(off_row);

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
      "a turn and puts lines between them.\n\n"
      "The phasing rule on a nonlinear run (`planetary_phasing.csv`): the same stage's settings "
      "with 26/22/70 teeth and N = 4 planets, the sun driven so that a mesh period is 400 steps "
      "of 1 us and the carrier loaded with 1000 N m, every mesh on its drive line, analysed over 4 "
      "mesh periods after 4 ms. With Z_s mod N = 2 the even mesh harmonics excite only rotational "
      "modes (the N sun meshes' lines add in phase) and the odd ones only planet modes (they "
      "cancel in the sum and in the carrier's speed, nonlinear mixing and all, by the stage's "
      "symmetry).\n";
  return section;
}

}  // namespace gearimpact::cli
