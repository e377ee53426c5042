// `gearimpact fe-check CASE --out DIR`: the tooth's compliance by finite
// elements (gmsh and CalculiX) beside the potential-energy terms, position by
// position, over three meshes; and `fe-check --cantilever`, the same pipeline
// on a beam whose deflection has a closed form (docs/verification.md,
// "Finite-element check").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_outline.hpp"
#include "gearimpact/io/atomic_file.hpp"
#include "gearimpact/io/case_file.hpp"
#include "gearimpact/io/results.hpp"
#include "gearimpact/stiffness/finite_element_check.hpp"
#include "gearimpact/stiffness/mesh_models.hpp"
#include "gearimpact/stiffness/root_crack.hpp"
#include "gnuplot.hpp"
#include "run_program.hpp"

namespace gearimpact::cli {

namespace {

struct FeCheckOptions {
  std::string case_file;
  std::string out;
  int gear = 1;
  int positions = 7;
  double element_size = 0.4;
  int refinements = 3;
  bool cantilever = false;
  // A slit from the cantilever's top edge at x = 40 mm (m; 0: none).
  double edge_crack = 0.0;
  // Root cracks of these depths (m) as slits, each on its own three meshes.
  std::vector<double> crack_depths;
  double crack_angle_deg = 45.0;
  bool overwrite = false;
  bool no_plots = false;
};

// The convergence asked of the two finest meshes at every position.
constexpr double kConvergence = 0.01;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// gmsh meshes `stem`.geo into `stem`_mesh.inp; CalculiX solves `stem`.inp
// (the loads of `loads`) into `stem`.dat. Returns each step's displacements of
// `printed`, and the mesh's element count through `triangles`.
std::vector<FeDisplacements> solve(const std::filesystem::path& dir, const std::string& stem,
                                   const std::string& geo, const FeMaterial& material,
                                   const std::function<std::vector<FeLoad>(const FeMesh&)>& loads,
                                   const std::function<std::vector<long>(const FeMesh&)>& printed,
                                   std::size_t& triangles, FeMesh* mesh_out = nullptr,
                                   const std::optional<FeSlit>& slit = std::nullopt) {
  write_file_atomically((dir / (stem + ".geo")).string(), geo);
  ProgramCall mesher;
  mesher.argv = {"gmsh", "-2", "-format", "inp", "-o", stem + "_mesh.inp", stem + ".geo"};
  mesher.dir = dir;
  mesher.shown = (dir / (stem + ".geo")).string();
  mesher.missing_hint = "Debian's gmsh; scripts/setup.sh installs it";
  mesher.capture_output = true;
  run_program(mesher);
  FeMesh mesh = read_gmsh_inp(read_text(dir / (stem + "_mesh.inp")));
  if (slit) open_slit(mesh, *slit, "SLIT");
  triangles = mesh.triangles.size();
  const std::vector<FeLoad> steps = loads(mesh);
  const std::vector<long> nodes = printed(mesh);
  write_file_atomically((dir / (stem + ".inp")).string(),
                        calculix_input(mesh, material, "FIXED", steps, nodes));
  ProgramCall solver;
  solver.argv = {"ccx", "-i", stem};
  solver.dir = dir;
  solver.shown = (dir / (stem + ".inp")).string();
  solver.missing_hint = "Debian's calculix-ccx; scripts/setup.sh installs it";
  // One thread: the machine's cores belong to the caller (a sweep, a test suite).
  solver.environment = {"OMP_NUM_THREADS=1", "CCX_NPROC_STIFFNESS=1",
                        "CCX_NPROC_EQUATION_SOLVER=1"};
  solver.capture_output = true;
  const std::string log = run_program(solver);
  // CalculiX may report an error in its log and still exit with 0.
  const auto error = log.find("*ERROR");
  if (error != std::string::npos) {
    throw std::runtime_error("ccx failed on " + solver.shown + ": " +
                             log.substr(error, std::min<std::size_t>(400, log.size() - error)));
  }
  if (mesh_out) *mesh_out = mesh;
  return read_calculix_dat(read_text(dir / (stem + ".dat")), steps.size(), nodes);
}

// The cantilever: L = 100 mm, h = 10 mm, b = 10 mm, E = 206 GPa, nu = 0, a
// unit tip load at the end's centre; the deflection of the neutral axis at
// x = L - h, one depth from the load.
void run_cantilever(const FeCheckOptions& o) {
  const double length = 0.1;
  const double depth = 0.01;
  const double measured_x = length - depth;
  const double crack_x = 0.04;
  const FeMaterial material{206e9, 0.0, 0.01};
  std::optional<FeSlit> slit;
  if (o.edge_crack > 0.0) {
    slit = FeSlit{{crack_x, 0.5 * depth}, {crack_x, 0.5 * depth - o.edge_crack}};
  }
  AtomicFolder folder(o.out, o.overwrite);
  const std::filesystem::path dir = folder.temporary();
  std::size_t triangles = 0;
  const auto u = solve(
      dir, "cantilever", cantilever_geo(length, depth, 0.0015, measured_x, crack_x, o.edge_crack),
      material,
      [](const FeMesh& m) {
        return std::vector<FeLoad>{{m.node_of("LOAD"), 0.0, -1.0}};
      },
      [](const FeMesh& m) { return std::vector<long>{m.node_of("MEAS")}; }, triangles, nullptr,
      slit);
  // The printed node is the only one.
  const double deflection = -u.front().begin()->second[1];
  const std::string json =
      "{\n  \"length_m\": " + format_data_number(length) +
      ",\n  \"depth_m\": " + format_data_number(depth) +
      ",\n  \"width_m\": " + format_data_number(material.thickness_m) +
      ",\n  \"youngs_modulus_pa\": " + format_data_number(material.youngs_modulus_pa) +
      ",\n  \"poisson_ratio\": 0,\n  \"measured_x_m\": " + format_data_number(measured_x) +
      ",\n  \"edge_crack_m\": " + format_data_number(o.edge_crack) +
      ",\n  \"crack_x_m\": " + format_data_number(crack_x) +
      ",\n  \"triangles\": " + std::to_string(triangles) +
      ",\n  \"deflection_m_per_n\": " + format_data_number(deflection) + "\n}\n";
  write_file_atomically((dir / "cantilever.json").string(), json);
  folder.commit();
  std::fputs(json.c_str(), stdout);
}

struct PositionRow {
  double s_m;
  ToothContact contact;
  std::vector<double> fe;              // per mesh, coarsest first
  std::vector<double> fe_centre_line;  // d . u_C alone, per mesh
  ToothCompliances pe;                 // potential-energy
  ToothCompliances ross;               // ross-compatible
};

std::string percent(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.1f %%", 100.0 * value);
  return text;
}

std::string scientific(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4e", value);
  return text;
}

void run_tooth(const FeCheckOptions& o) {
  const SimulationCase c = read_pair_or_run_file(o.case_file).simulation_case;
  const RackGearPairGeometry pair = rack_gear_pair_geometry(c.gears);
  const Gear which = o.gear == 1 ? Gear::one : Gear::two;
  const RackGearGeometry& gear = o.gear == 1 ? pair.gear1 : pair.gear2;
  const char* bore_key = o.gear == 1 ? "gears.bore_diameter1" : "gears.bore_diameter2";
  // The positions: even steps of s over the path of contact, ends included.
  std::vector<PositionRow> rows;
  std::vector<ToothContact> contacts;
  std::vector<double> taus;
  for (int i = 0; i < o.positions; ++i) {
    const double s =
        pair.start_of_active_profile_m +
        (pair.end_of_active_profile_m - pair.start_of_active_profile_m) * i / (o.positions - 1);
    const PairContact both = pair_contact(pair, s);
    const ToothContact contact = o.gear == 1 ? both.gear1 : both.gear2;
    rows.push_back({s, contact, {}, {}, {}, {}});
    contacts.push_back(contact);
    taus.push_back(contact.tau_rad);
  }
  // Every refusal before the meshes: a missing bore, a foundation fit's refusal.
  const ToothOutline outline = tooth_outline(gear, bore_key, 24, 48, taus);
  StiffnessModel pe_model;
  pe_model.kind = StiffnessModelKind::potential_energy;
  StiffnessModel ross_model = pe_model;
  ross_model.kind = StiffnessModelKind::ross_compatible;
  for (PositionRow& row : rows) {
    row.pe = tooth_compliances(gear, which, row.contact, pair.contact_width_m, pe_model);
    row.ross = tooth_compliances(gear, which, row.contact, pair.contact_width_m, ross_model);
  }
  // The foundation fit outside its range, for this gear: said on stderr and in the summary.
  std::vector<FoundationExtrapolation> extrapolated;
  for (const FoundationExtrapolation& e : foundation_extrapolations(pair, pe_model)) {
    if (e.gear == which) extrapolated.push_back(e);
  }
  // The cracks, placed and refused (q sin nu >= h_c) before any mesh: a uniform crack of each
  // depth at the model's default start, the same for both models.
  struct CrackRun {
    RootCrack crack;
    PlacedCrack placed;
    std::vector<ToothCompliances> pe;
    std::vector<ToothCompliances> ross;
  };
  std::vector<CrackRun> cracks;
  for (const double depth : o.crack_depths) {
    CrackRun run;
    run.crack.depth_m = depth;
    run.crack.angle_rad = o.crack_angle_deg * pi / 180.0;
    run.placed = place_crack(run.crack, gear, pe_model.kind, pair.contact_width_m);
    for (const PositionRow& row : rows) {
      run.pe.push_back(cracked_tooth_compliances(gear, which, row.contact, pair.contact_width_m,
                                                 pe_model, run.crack));
      run.ross.push_back(cracked_tooth_compliances(gear, which, row.contact, pair.contact_width_m,
                                                   ross_model, run.crack));
    }
    cracks.push_back(run);
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  const FeMaterial material{gear.youngs_modulus_pa, gear.poisson_ratio, pair.contact_width_m};
  const double m = c.gears.module_m;
  // One geometry (healthy, or with a slit) on every mesh: its readings per position, per mesh.
  struct Meshes {
    std::vector<std::vector<FeToothReading>> readings;  // [position][mesh]
    std::vector<std::size_t> triangles;
    std::vector<double> tooth_sizes;
  };
  const auto run_meshes = [&](const std::string& name, const std::optional<FeSlit>& slit) {
    Meshes out;
    out.readings.resize(contacts.size());
    for (int k = 0; k < o.refinements; ++k) {
      const double factor = std::ldexp(1.0, -k);
      // The ring far from the tooth carries little strain energy: its elements refine by the
      // square root of the tooth's, so that a large wheel's ring does not dominate the cost (the
      // convergence check covers both).
      const FeMeshSizes sizes{
          o.element_size * m * factor,
          std::min(4.0 * m, (outline.root_radius_m - outline.bore_radius_m) / 3.0) *
              std::sqrt(factor)};
      out.tooth_sizes.push_back(sizes.tooth_m);
      const std::string stem = name + "_mesh" + std::to_string(k + 1);
      std::size_t triangles = 0;
      FeMesh mesh;
      const auto u = solve(
          dir, stem, tooth_geo(outline, contacts, sizes, slit), material,
          [&](const FeMesh& g) {
            std::vector<FeLoad> loads;
            for (std::size_t i = 0; i < contacts.size(); ++i) {
              loads.push_back({g.node_of("P" + std::to_string(i + 1)),
                               -std::cos(contacts[i].tau_rad), -std::sin(contacts[i].tau_rad)});
            }
            return loads;
          },
          [&](const FeMesh& g) {
            std::vector<long> nodes;
            for (std::size_t i = 0; i < contacts.size(); ++i) {
              for (const char* set : {"C", "A", "B"}) {
                nodes.push_back(g.node_of(set + std::to_string(i + 1)));
              }
            }
            return nodes;
          },
          triangles, &mesh, slit);
      out.triangles.push_back(triangles);
      for (std::size_t i = 0; i < contacts.size(); ++i) {
        const std::string n = std::to_string(i + 1);
        const FeDisplacements& step = u[i];
        out.readings[i].push_back(tooth_reading(contacts[i], step.at(mesh.node_of("C" + n)),
                                                step.at(mesh.node_of("A" + n)),
                                                step.at(mesh.node_of("B" + n))));
      }
    }
    return out;
  };
  const Meshes healthy = run_meshes("tooth", std::nullopt);
  const std::vector<std::size_t>& triangles = healthy.triangles;
  const std::vector<double>& tooth_sizes = healthy.tooth_sizes;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (const FeToothReading& r : healthy.readings[i]) {
      rows[i].fe.push_back(r.compliance_m_per_n);
      rows[i].fe_centre_line.push_back(r.centre_line_m_per_n);
    }
  }
  // The cracked teeth: each depth's slit on its own three meshes (a depth of 0 is the healthy
  // tooth's meshes), against each model's cracked reading and as the change the crack makes.
  std::string crack_csv = "depth_m,angle_rad,start_radius_m,start_half_thickness_m,s_m,radius_m";
  for (int k = 0; k < o.refinements; ++k) {
    crack_csv += ",fe_mesh" + std::to_string(k + 1) + "_m_per_n";
  }
  crack_csv +=
      ",pe_total_m_per_n,ross_total_m_per_n,fe_vs_pe,fe_vs_ross,fe_change,pe_change,ross_change,"
      "last_mesh_change\n";
  std::string crack_table =
      "| q, mm | s, mm | r, mm | FE, m/N | PE total | FE vs PE | ROSS total | FE vs ROSS | FE "
      "change | PE change | ROSS change | FE mesh change |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  double crack_worst_change = 0.0;
  for (std::size_t j = 0; j < cracks.size(); ++j) {
    const CrackRun& run = cracks[j];
    const Meshes cracked = run.crack.depth_m > 0.0
                               ? run_meshes("crack" + std::to_string(j + 1),
                                            root_crack_slit(run.placed.start_radius_m,
                                                            run.placed.start_half_thickness_m,
                                                            run.crack.depth_m, run.crack.angle_rad))
                               : healthy;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const PositionRow& r = rows[i];
      const auto& fe_meshes = cracked.readings[i];
      const double fe = fe_meshes.back().compliance_m_per_n;
      const double fe_healthy = healthy.readings[i].back().compliance_m_per_n;
      const double change =
          fe_meshes.size() > 1
              ? std::fabs(fe - fe_meshes[fe_meshes.size() - 2].compliance_m_per_n) / fe
              : 0.0;
      crack_worst_change = std::max(crack_worst_change, change);
      const double pe = run.pe[i].total_m_per_n();
      const double ross = run.ross[i].total_m_per_n();
      const double radius = std::hypot(r.contact.x_m, r.contact.y_m);
      std::vector<double> fields{run.crack.depth_m,
                                 run.crack.angle_rad,
                                 run.placed.start_radius_m,
                                 run.placed.start_half_thickness_m,
                                 r.s_m,
                                 radius};
      for (const FeToothReading& v : fe_meshes) fields.push_back(v.compliance_m_per_n);
      for (const double v :
           {pe, ross, fe / pe - 1.0, fe / ross - 1.0, fe / fe_healthy - 1.0,
            pe / r.pe.total_m_per_n() - 1.0, ross / r.ross.total_m_per_n() - 1.0, change}) {
        fields.push_back(v);
      }
      for (std::size_t f = 0; f < fields.size(); ++f) {
        if (f) crack_csv += ',';
        crack_csv += format_data_number(fields[f]);
      }
      crack_csv += '\n';
      char head[80];
      std::snprintf(head, sizeof head, "| %.3f | %.3f | %.3f | ", run.crack.depth_m * 1e3,
                    r.s_m * 1e3, radius * 1e3);
      crack_table +=
          head + scientific(fe) + " | " + scientific(pe) + " | " + percent(fe / pe - 1.0) + " | " +
          scientific(ross) + " | " + percent(fe / ross - 1.0) + " | " +
          percent(fe / fe_healthy - 1.0) + " | " + percent(pe / r.pe.total_m_per_n() - 1.0) +
          " | " + percent(ross / r.ross.total_m_per_n() - 1.0) + " | " + percent(change) + " |\n";
    }
  }
  if (!cracks.empty()) {
    write_file_atomically((dir / "fe_crack.csv").string(), crack_csv);
    write_file_atomically((dir / "fe_crack.md").string(), crack_table);
  }
  // The table: CSV with every mesh, Markdown with the finest.
  std::string csv = "s_m,radius_m,y_t_m,tau_rad";
  for (int k = 0; k < o.refinements; ++k) csv += ",fe_mesh" + std::to_string(k + 1) + "_m_per_n";
  csv +=
      ",fe_centre_line_m_per_n,pe_bending_m_per_n,pe_shear_m_per_n,pe_axial_m_per_n,"
      "pe_foundation_m_per_n,pe_total_m_per_n,pe_without_foundation_m_per_n,ross_total_m_per_n,"
      "fe_vs_pe,fe_vs_ross,last_mesh_change\n";
  std::string table =
      "| s, mm | r, mm | FE, m/N | PE bending | shear | axial | foundation | PE total | FE vs PE "
      "| ROSS-compatible total | FE vs ROSS | FE mesh change |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  double worst_change = 0.0;
  std::size_t worst_at = 0;
  double worst_pe = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const PositionRow& r = rows[i];
    const double fe = r.fe.back();
    const double change =
        r.fe.size() > 1 ? std::fabs(fe - r.fe[r.fe.size() - 2]) / std::fabs(fe) : 0.0;
    if (change >= worst_change) {
      worst_change = change;
      worst_at = i;
    }
    const double pe = r.pe.total_m_per_n();
    const double ross = r.ross.total_m_per_n();
    worst_pe = std::max(worst_pe, std::fabs(fe / pe - 1.0));
    const double radius = std::hypot(r.contact.x_m, r.contact.y_m);
    csv += format_data_number(r.s_m) + "," + format_data_number(radius) + "," +
           format_data_number(r.contact.y_m) + "," + format_data_number(r.contact.tau_rad);
    for (const double v : r.fe) csv += "," + format_data_number(v);
    csv += "," + format_data_number(r.fe_centre_line.back()) + "," +
           format_data_number(r.pe.bending_m_per_n) + "," + format_data_number(r.pe.shear_m_per_n) +
           "," + format_data_number(r.pe.axial_m_per_n) + "," +
           format_data_number(r.pe.foundation_m_per_n) + "," + format_data_number(pe) + "," +
           format_data_number(pe - r.pe.foundation_m_per_n) + "," + format_data_number(ross) + "," +
           format_data_number(fe / pe - 1.0) + "," + format_data_number(fe / ross - 1.0) + "," +
           format_data_number(change) + "\n";
    char head[64];
    std::snprintf(head, sizeof head, "| %.3f | %.3f | ", r.s_m * 1e3, radius * 1e3);
    table += head + scientific(fe) + " | " + scientific(r.pe.bending_m_per_n) + " | " +
             scientific(r.pe.shear_m_per_n) + " | " + scientific(r.pe.axial_m_per_n) + " | " +
             scientific(r.pe.foundation_m_per_n) + " | " + scientific(pe) + " | " +
             percent(fe / pe - 1.0) + " | " + scientific(ross) + " | " + percent(fe / ross - 1.0) +
             " | " + percent(change) + " |\n";
  }
  std::string meshes = "  \"meshes\": [";
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    meshes += std::string(k ? ", " : "") +
              "{\"tooth_element_m\": " + format_data_number(tooth_sizes[k]) +
              ", \"triangles\": " + std::to_string(triangles[k]) + "}";
  }
  meshes += "],\n";
  const bool converged = o.refinements < 2 || worst_change < kConvergence;
  const std::string json =
      "{\n  \"case\": \"" + c.name + "\",\n  \"gear\": " + std::to_string(o.gear) +
      ",\n  \"positions\": " + std::to_string(o.positions) + ",\n" + meshes +
      "  \"plane\": \"stress\",\n  \"thickness_m\": " + format_data_number(material.thickness_m) +
      ",\n  \"largest_last_mesh_change\": " + format_data_number(worst_change) +
      ",\n  \"converged\": " + (converged ? "true" : "false") +
      ",\n  \"largest_fe_vs_pe\": " + format_data_number(worst_pe) +
      (cracks.empty()
           ? std::string()
           : ",\n  \"crack_largest_last_mesh_change\": " + format_data_number(crack_worst_change) +
                 ",\n  \"crack_converged\": " +
                 (o.refinements < 2 || crack_worst_change < kConvergence ? "true" : "false")) +
      ",\n  \"foundation_extrapolated\": " + (extrapolated.empty() ? "false" : "true") + "\n}\n";
  write_file_atomically((dir / "fe_check.csv").string(), csv);
  write_file_atomically((dir / "fe_check.md").string(), table);
  write_file_atomically((dir / "summary.json").string(), json);
  if (!o.no_plots) {
    Figure f;
    f.name = "fe_check";
    f.title = "Tooth compliance of gear " + std::to_string(o.gear) + " (" + literal_key(c.name) +
              "): finite elements and the potential-energy terms";
    f.x_label = "contact position s from T_1 on the line of action, mm";
    f.y_label = "compliance along the load, 1e-9 m/N";
    f.setup = {"set key outside right top vertical"};
    const int fe_column = 4 + o.refinements;
    const int pe_column = fe_column + 6;
    f.series = {
        "'fe_check.csv' using ($1*1e3):($" + std::to_string(fe_column) +
            "*1e9) with linespoints lw 2 pt 7 lc rgb '#d62728' title 'FE (finest mesh)'",
        "'fe_check.csv' using ($1*1e3):($" + std::to_string(pe_column) +
            "*1e9) with linespoints lw 2 pt 5 lc rgb '#1f77b4' title 'potential energy: b+s+a+f'",
        "'fe_check.csv' using ($1*1e3):($" + std::to_string(pe_column + 1) +
            "*1e9) with linespoints lw 1 dt 2 lc rgb '#1f77b4' title 'potential energy: b+s+a'",
        "'fe_check.csv' using ($1*1e3):($" + std::to_string(pe_column + 2) +
            "*1e9) with linespoints lw 1 pt 4 lc rgb '#2ca02c' title 'ross-compatible'"};
    render(dir, f);
  }
  folder.commit();
  if (!extrapolated.empty()) {
    std::fprintf(stderr, "gearimpact: warning: %s\n",
                 foundation_extrapolation_warning(extrapolated).c_str());
  }
  std::fputs(table.c_str(), stdout);
  if (!cracks.empty()) std::fputs(crack_table.c_str(), stdout);
  std::fputs(json.c_str(), stdout);
  if (!converged) {
    throw std::runtime_error(
        "fe-check: the meshes have not converged: the compliance at s = " +
        format_number(rows[worst_at].s_m) + " m changed by " + format_number(100.0 * worst_change) +
        " % between the two finest meshes (at most " + format_number(100.0 * kConvergence) +
        " % asked); a smaller --element-size refines all three (the results are in " + o.out + ")");
  }
}

}  // namespace

void register_fe_commands(CLI::App& app) {
  auto o = std::make_shared<FeCheckOptions>();
  CLI::App* fe = app.add_subcommand(
      "fe-check",
      "The tooth's compliance by finite elements (gmsh, CalculiX: plane stress, one tooth on its "
      "rim down to the bore) beside the potential-energy terms, at contact positions over the "
      "path of contact, on three meshes: fe_check.csv, fe_check.md, summary.json, fe_check.png, "
      "and the meshes' and solver's files (docs/verification.md). --cantilever: the same "
      "pipeline on a beam with a closed-form deflection");
  fe->add_option("case", o->case_file,
                 "case file: a pair file ([gears] with both bores) or a run file");
  fe->add_flag("--cantilever", o->cantilever,
               "solve the rectangular cantilever of the pipeline's check instead of a case");
  fe->add_option("--gear", o->gear, "the gear whose tooth is modelled, 1 (pinion) or 2")
      ->check(CLI::Range(1, 2));
  fe->add_option("--positions", o->positions,
                 "contact positions, evenly spaced over the path of contact, 2 to 25")
      ->check(CLI::Range(2, 25));
  fe->add_option("--element-size", o->element_size,
                 "the coarsest mesh's element size on the tooth, a fraction of the module in "
                 "[0.02, 0.5]; each finer mesh halves it")
      ->check(CLI::Range(0.02, 0.5));
  fe->add_option("--refinements", o->refinements, "meshes, 1 to 4 (the convergence needs 2)")
      ->check(CLI::Range(1, 4));
  fe->add_option("--out", o->out,
                 "output folder: new or empty (else --overwrite), in a folder that exists")
      ->required();
  fe->add_option("--crack-depths", o->crack_depths,
                 "root-crack depths q in m (comma-separated, e.g. 0,1e-3,2e-3): each a slit on "
                 "the loaded flank from the model's crack start, on its own three meshes; "
                 "fe_crack.csv and fe_crack.md")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 0.1));
  fe->add_option("--crack-angle", o->crack_angle_deg,
                 "the cracks' angle nu to the tooth's centre line, deg, in (0, 90]")
      ->check(CLI::Range(0.001, 90.0));
  fe->add_option("--edge-crack", o->edge_crack,
                 "with --cantilever: a slit this deep (m, below half the depth, 5 mm) from the "
                 "top edge at x = 40 mm")
      ->check(CLI::Range(0.0, 0.0049));
  fe->add_flag("--overwrite", o->overwrite, "replace a non-empty --out folder whole");
  fe->add_flag("--no-plots", o->no_plots, "write the tables only");
  fe->callback([o] {
    if (o->cantilever == !o->case_file.empty()) {
      throw InputError("case", o->case_file.empty() ? "absent" : o->case_file,
                       "either a case file or --cantilever");
    }
    require_output_folder(
        o->out, o->overwrite,
        o->case_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{o->case_file});
    if (o->cantilever) {
      run_cantilever(*o);
    } else {
      run_tooth(*o);
    }
  });
}

}  // namespace gearimpact::cli
