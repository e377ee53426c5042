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
#include "gearimpact/stiffness/surface_faults.hpp"
#include "gnuplot.hpp"
#include "reproduce.hpp"
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
  // A spall of this width (m; 0: none) on the pinion's drive flank at the pitch point: both
  // teeth in 3-D, loaded over the whole face and over the width the spall leaves.
  std::vector<double> spall_widths;
  // The contact positions s of the solid runs (m from T_1; none: the pitch point).
  std::vector<double> solid_positions;
  // A chip of these widths (m) above chip_radius on the pinion, in 3-D.
  std::vector<double> chip_widths;
  double chip_radius = 0.0;
  double spall_depth = 2e-4;
  double solid_element_size = 1.0;
  double crack_angle_deg = 45.0;
  bool overwrite = false;
  bool no_plots = false;
  // Nothing on stdout (reproduce reads the files).
  bool quiet = false;
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
              std::string set = "P";
              set += std::to_string(i + 1);
              loads.push_back(
                  {g.node_of(set), -std::cos(contacts[i].tau_rad), -std::sin(contacts[i].tau_rad)});
            }
            return loads;
          },
          [&](const FeMesh& g) {
            std::vector<long> nodes;
            for (std::size_t i = 0; i < contacts.size(); ++i) {
              for (const char* prefix : {"C", "A", "B"}) {
                std::string set = prefix;
                set += std::to_string(i + 1);
                nodes.push_back(g.node_of(set));
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
  if (!o.quiet) {
    std::fputs(table.c_str(), stdout);
    if (!cracks.empty()) std::fputs(crack_table.c_str(), stdout);
    std::fputs(json.c_str(), stdout);
  }
  if (!converged) {
    throw std::runtime_error(
        "fe-check: the meshes have not converged: the compliance at s = " +
        format_number(rows[worst_at].s_m) + " m changed by " + format_number(100.0 * worst_change) +
        " % between the two finest meshes (at most " + format_number(100.0 * kConvergence) +
        " % asked); a smaller --element-size refines all three (the results are in " + o.out + ")");
  }
}

// gmsh meshes `geo` in 3-D as `stem`_mesh.inp in `dir`; the mesh read back.
FeMesh3 mesh_solid(const std::filesystem::path& dir, const std::string& stem,
                   const std::string& geo) {
  write_file_atomically((dir / (stem + ".geo")).string(), geo);
  ProgramCall mesher;
  mesher.argv = {"gmsh", "-3", "-format", "inp", "-o", stem + "_mesh.inp", stem + ".geo"};
  mesher.dir = dir;
  mesher.shown = (dir / (stem + ".geo")).string();
  mesher.missing_hint = "Debian's gmsh; scripts/setup.sh installs it";
  mesher.capture_output = true;
  run_program(mesher);
  return read_gmsh_inp_3d(read_text(dir / (stem + "_mesh.inp")));
}

// CalculiX solves the solid `mesh` held on `fixed` under each step of `steps`; each step's
// displacements of `printed`.
std::vector<FeDisplacements> solve_solid(const std::filesystem::path& dir, const std::string& stem,
                                         const FeMesh3& mesh, const FeMaterial& material,
                                         const std::vector<long>& fixed,
                                         const std::vector<std::vector<FeLoad>>& steps,
                                         const std::vector<long>& printed) {
  write_file_atomically((dir / (stem + ".inp")).string(),
                        calculix_input_3d(mesh, material, fixed, steps, printed));
  ProgramCall solver;
  solver.argv = {"ccx", "-i", stem};
  solver.dir = dir;
  solver.shown = (dir / (stem + ".inp")).string();
  solver.missing_hint = "Debian's calculix-ccx; scripts/setup.sh installs it";
  solver.environment = {"OMP_NUM_THREADS=1", "CCX_NPROC_STIFFNESS=1",
                        "CCX_NPROC_EQUATION_SOLVER=1"};
  solver.capture_output = true;
  const std::string log = run_program(solver);
  const auto error = log.find("*ERROR");
  if (error != std::string::npos) {
    throw std::runtime_error("ccx failed on " + solver.shown + ": " +
                             log.substr(error, std::min<std::size_t>(400, log.size() - error)));
  }
  return read_calculix_dat(read_text(dir / (stem + ".dat")), steps.size(), printed);
}

// The solid's mesh sizes of refinement k (a factor sqrt 2 apart: halving would multiply a
// solid's cost by 8) and its layers, a multiple of 4 (so that b/4, b/2, 3b/4 fall on layer
// planes), each at most twice the tooth's element size: quadratic along z.
struct SolidSizes {
  FeMeshSizes sizes;
  int layers;
};
SolidSizes solid_sizes(const FeCheckOptions& o, const ToothOutline& outline, double m, double b,
                       int k) {
  const double factor = std::pow(2.0, -0.5 * k);
  const FeMeshSizes sizes{
      o.solid_element_size * m * factor,
      std::min(4.0 * m, (outline.root_radius_m - outline.bore_radius_m) / 3.0) * std::sqrt(factor)};
  return {sizes, 4 * static_cast<int>(std::ceil(b / (8.0 * sizes.tooth_m)))};
}

// A width of a solid run's fault: a quarter, a half or three quarters of b, distinct.
void check_quarters(std::vector<double>& widths, double b, const char* flag) {
  std::sort(widths.begin(), widths.end());
  for (std::size_t w = 0; w < widths.size(); ++w) {
    const double quarters = 4.0 * widths[w] / b;
    if (!(widths[w] > 0.0 && widths[w] < b) || std::fabs(quarters - std::round(quarters)) > 1e-9 ||
        (w > 0 && std::fabs(widths[w] - widths[w - 1]) < 1e-12)) {
      throw InputError(flag, widths[w],
                       "distinct quarters of the contact width (" + format_number(b) +
                           " m: b/4, b/2 or 3b/4): the layers of the solid mesh meet there");
    }
  }
}

// The solid runs' contact positions (--solid-at; none: the pitch point), sorted, on the active
// path less 0.5 mm at each end.
std::vector<double> solid_positions(const FeCheckOptions& o, const RackGearPairGeometry& pair) {
  const double s_pitch = pair.gear1.base_radius_m * std::tan(pair.operating_pressure_angle_rad);
  std::vector<double> positions = o.solid_positions;
  if (positions.empty()) positions.push_back(s_pitch);
  std::sort(positions.begin(), positions.end());
  const double s_low = pair.start_of_active_profile_m + 5e-4;
  const double s_high = pair.end_of_active_profile_m - 5e-4;
  for (std::size_t p = 0; p < positions.size(); ++p) {
    if (!(positions[p] >= s_low && positions[p] <= s_high) ||
        (p > 0 && positions[p] - positions[p - 1] < 1e-4)) {
      throw InputError("--solid-at", positions[p],
                       "distinct contact positions s (m from T_1, at least 0.1 mm apart) in [" +
                           format_number(s_low) + ", " + format_number(s_high) +
                           "] (the active path less the spall's half band, 0.5 mm)");
    }
  }
  return positions;
}

// The spall in 3-D (docs/verification.md, "The spall in 3-D"): each tooth of the pair at each
// contact position, loaded along the line of action by a unit force spread evenly over the whole
// face and over the width each spall leaves (z in [b_s, b]: the spall takes z in [0, b_s], where
// the flanks do not touch); its compliance the load-weighted mean of the section readings
// along z. The pair's compliance adds Hertz over the contact length; the pit's material stays.
// One mesh per gear and refinement carries every position (its load vertices); one linear step
// per position and loaded width.
void run_spall(const FeCheckOptions& o) {
  const SimulationCase c = read_pair_or_run_file(o.case_file).simulation_case;
  const RackGearPairGeometry pair = rack_gear_pair_geometry(c.gears);
  const double b = pair.contact_width_m;
  std::vector<double> widths = o.spall_widths;
  check_quarters(widths, b, "--spall-width");
  const double s_pitch = pair.gear1.base_radius_m * std::tan(pair.operating_pressure_angle_rad);
  // The spall's band, +-0.5 mm of roll about each contact, inside the active profile.
  const std::vector<double> positions = solid_positions(o, pair);
  const std::size_t np = positions.size();
  const std::size_t nw = widths.size();
  StiffnessModel pe_model;
  pe_model.kind = StiffnessModelKind::potential_energy;
  const RackGearGeometry* gears[2] = {&pair.gear1, &pair.gear2};
  const char* bore_keys[2] = {"gears.bore_diameter1", "gears.bore_diameter2"};
  // [gear][position]
  std::vector<ToothContact> contact[2];
  std::vector<ToothCompliances> healthy_model[2];
  // [position][width]: the pinion's spalled terms by this code's reading.
  std::vector<std::vector<ToothCompliances>> spalled_pinion(np);
  for (std::size_t p = 0; p < np; ++p) {
    const PairContact both = pair_contact(pair, positions[p]);
    contact[0].push_back(both.gear1);
    contact[1].push_back(both.gear2);
    for (int g = 0; g < 2; ++g) {
      healthy_model[g].push_back(tooth_compliances(*gears[g], g == 0 ? Gear::one : Gear::two,
                                                   contact[g].back(), b, pe_model));
    }
    for (const double b_s : widths) {
      Spall spall;
      spall.start_radius_m = radius_at_roll_distance(pair.gear1.base_radius_m, positions[p] - 5e-4);
      spall.end_radius_m = radius_at_roll_distance(pair.gear1.base_radius_m, positions[p] + 5e-4);
      spall.width_m = b_s;
      spall.depth_m = o.spall_depth;
      place_spall(spall, pair.gear1, b);
      spalled_pinion[p].push_back(
          spalled_tooth_compliances(pair.gear1, Gear::one, both.gear1, b, pe_model, spall));
    }
  }
  ToothOutline outlines[2];
  for (int g = 0; g < 2; ++g) {
    std::vector<double> taus;
    for (const ToothContact& t : contact[g]) taus.push_back(t.tau_rad);
    outlines[g] = tooth_outline(*gears[g], bore_keys[g], 24, 48, taus);
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  const double m = c.gears.module_m;
  // fe[gear][mesh][position][0: whole face, 1 + w: the width spall w leaves].
  std::vector<std::vector<std::vector<double>>> fe[2];
  std::vector<std::size_t> wedges;
  std::vector<int> layer_counts;
  std::vector<double> sizes_used;
  for (int g = 0; g < 2; ++g) {
    const RackGearGeometry& gear = *gears[g];
    const ToothOutline& outline = outlines[g];
    const FeMaterial material{gear.youngs_modulus_pa, gear.poisson_ratio, b};
    for (int k = 0; k < o.refinements; ++k) {
      const auto [sizes, layers] = solid_sizes(o, outline, m, b, k);
      const std::string stem =
          "solid_gear" + std::to_string(g + 1) + "_mesh" + std::to_string(k + 1);
      const FeMesh3 mesh =
          mesh_solid(dir, stem, tooth_geo_3d(outline, contact[g], sizes, b, layers));
      const std::size_t n = static_cast<std::size_t>(2 * layers + 1);
      struct Lines {
        std::vector<long> p, c, a, b;
      };
      std::vector<Lines> lines(np);
      std::vector<std::vector<FeLoad>> steps;
      std::vector<std::vector<double>> step_weights;
      std::vector<long> printed;
      for (std::size_t q = 0; q < np; ++q) {
        const OutlinePoint& pt = outline.flank.at(outline.vertex_index.at(q));
        const ToothContact& t = contact[g][q];
        Lines& l = lines[q];
        l.p = nodes_on_z_line(mesh, pt.x_m, pt.y_m);
        l.c = nodes_on_z_line(mesh, 0.0, t.y_m);
        l.a = nodes_on_z_line(mesh, -0.5 * t.x_m, t.y_m);
        l.b = nodes_on_z_line(mesh, 0.5 * t.x_m, t.y_m);
        if (l.p.size() != n || l.c.size() != n || l.a.size() != n || l.b.size() != n) {
          throw std::runtime_error("the solid mesh " + stem +
                                   " lacks the lines of nodes along z at the load and its section");
        }
        std::vector<double> z;
        for (const long id : l.p) z.push_back(mesh.nodes_m.at(id)[2]);
        const double dx = -std::cos(t.tau_rad);
        const double dy = -std::sin(t.tau_rad);
        for (std::size_t w = 0; w <= nw; ++w) {
          const std::vector<double> weights = line_load_weights(z, w == 0 ? 0.0 : widths[w - 1], b);
          std::vector<FeLoad> step;
          for (std::size_t i = 0; i < n; ++i) {
            if (weights[i] != 0.0) step.push_back({l.p[i], dx * weights[i], dy * weights[i]});
          }
          steps.push_back(step);
          step_weights.push_back(weights);
        }
        for (const auto* line : {&l.c, &l.a, &l.b}) {
          printed.insert(printed.end(), line->begin(), line->end());
        }
      }
      std::sort(printed.begin(), printed.end());
      printed.erase(std::unique(printed.begin(), printed.end()), printed.end());
      const auto u = solve_solid(dir, stem, mesh, material,
                                 nodes_at_radius(mesh, outline.bore_radius_m), steps, printed);
      // Each step's compliance: the section readings along z weighted by the step's load.
      std::vector<std::vector<double>> by_position(np, std::vector<double>(nw + 1, 0.0));
      for (std::size_t q = 0; q < np; ++q) {
        const Lines& l = lines[q];
        for (std::size_t w = 0; w <= nw; ++w) {
          const std::size_t step = q * (nw + 1) + w;
          const std::vector<double>& weights = step_weights[step];
          for (std::size_t i = 0; i < n; ++i) {
            if (weights[i] == 0.0) continue;
            by_position[q][w] += weights[i] * tooth_reading(contact[g][q], u[step].at(l.c[i]),
                                                            u[step].at(l.a[i]), u[step].at(l.b[i]))
                                                  .compliance_m_per_n;
          }
        }
      }
      fe[g].push_back(by_position);
      if (g == 0) {
        wedges.push_back(mesh.wedges.size());
        layer_counts.push_back(layers);
        sizes_used.push_back(sizes.tooth_m);
      }
    }
  }
  // The pair: Hertz over the contact length plus both teeth.
  const double e1 = pair.gear1.youngs_modulus_pa;
  const double e2 = pair.gear2.youngs_modulus_pa;
  const double nu1 = pair.gear1.poisson_ratio;
  const double nu2 = pair.gear2.poisson_ratio;
  const double hertz_full = 1.0 / hertz_stiffness_two_materials(b, e1, nu1, e2, nu2);
  struct Reading {
    std::string name;
    double tooth1_healthy, tooth1_spalled, tooth2_healthy, tooth2_spalled;
  };
  std::string table =
      "| s, mm | b_s / b | reading | pinion tooth healthy, m/N | spalled | change | wheel tooth "
      "healthy | spalled | change | pair healthy, N/m | spalled | pair stiffness lost | loss vs "
      "FE |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::string csv =
      "s_m,spall_width_m,reading,tooth1_healthy_m_per_n,tooth1_spalled_m_per_n,"
      "tooth2_healthy_m_per_n,tooth2_spalled_m_per_n,hertz_healthy_m_per_n,hertz_spalled_m_per_n,"
      "pair_healthy_n_per_m,pair_spalled_n_per_m,pair_loss\n";
  std::string json_losses;
  for (std::size_t p = 0; p < np; ++p) {
    for (std::size_t w = 0; w < nw; ++w) {
      const double b_s = widths[w];
      const double hertz_part = 1.0 / hertz_stiffness_two_materials(b - b_s, e1, nu1, e2, nu2);
      const double scale = b / (b - b_s);
      // The library's reading (surface_faults.hpp), each tooth by its root thickness.
      const SpallWidthFactors factors[2] = {
          spall_width_factors(b - b_s, b, root_thickness(pair.gear1)),
          spall_width_factors(b - b_s, b, root_thickness(pair.gear2))};
      const auto effective = [](const ToothCompliances& t, const SpallWidthFactors& f) {
        return f.beam * (t.bending_m_per_n + t.shear_m_per_n + t.axial_m_per_n) +
               f.foundation * t.foundation_m_per_n;
      };
      const auto width_scaled = [&](const ToothCompliances& t) {
        return scale * (t.bending_m_per_n + t.foundation_m_per_n) + t.shear_m_per_n +
               t.axial_m_per_n;
      };
      const std::vector<Reading> readings{
          {"finite elements (3-D, finest mesh)", fe[0].back()[p][0], fe[0].back()[p][1 + w],
           fe[1].back()[p][0], fe[1].back()[p][1 + w]},
          {"potential-energy, Hertz-only (Hertz over b - b_s, pit sections)",
           healthy_model[0][p].total_m_per_n(), spalled_pinion[p][w].total_m_per_n(),
           healthy_model[1][p].total_m_per_n(), healthy_model[1][p].total_m_per_n()},
          {"potential-energy, width-scaled (bending and foundation x b / (b - b_s))",
           healthy_model[0][p].total_m_per_n(), width_scaled(healthy_model[0][p]),
           healthy_model[1][p].total_m_per_n(), width_scaled(healthy_model[1][p])},
          {"potential-energy, effective-width (spall_reading = \"effective-width\")",
           healthy_model[0][p].total_m_per_n(), effective(spalled_pinion[p][w], factors[0]),
           healthy_model[1][p].total_m_per_n(), effective(healthy_model[1][p], factors[1])}};
      double fe_loss = 0.0;
      for (const Reading& r : readings) {
        const double k_healthy = 1.0 / (hertz_full + r.tooth1_healthy + r.tooth2_healthy);
        const double k_spalled = 1.0 / (hertz_part + r.tooth1_spalled + r.tooth2_spalled);
        const double loss = 1.0 - k_spalled / k_healthy;
        if (&r == &readings.front()) fe_loss = loss;
        char head[64];
        std::snprintf(head, sizeof head, "| %.3f | %.2f | ", positions[p] * 1e3, b_s / b);
        table += head + r.name + " | " + scientific(r.tooth1_healthy) + " | " +
                 scientific(r.tooth1_spalled) + " | " +
                 percent(r.tooth1_spalled / r.tooth1_healthy - 1.0) + " | " +
                 scientific(r.tooth2_healthy) + " | " + scientific(r.tooth2_spalled) + " | " +
                 percent(r.tooth2_spalled / r.tooth2_healthy - 1.0) + " | " +
                 scientific(k_healthy) + " | " + scientific(k_spalled) + " | " +
                 percent(loss).substr(1) + " | " + percent(loss - fe_loss) + " |\n";
        std::vector<double> fields{r.tooth1_healthy, r.tooth1_spalled, r.tooth2_healthy,
                                   r.tooth2_spalled, hertz_full,       hertz_part,
                                   k_healthy,        k_spalled,        loss};
        csv += format_data_number(positions[p]) + "," + format_data_number(b_s) + ",\"" + r.name +
               "\"";
        for (const double v : fields) {
          csv += ',';
          csv += format_data_number(v);
        }
        csv += '\n';
      }
      if (!json_losses.empty()) json_losses += ", ";
      json_losses += "{\"s_m\": " + format_data_number(positions[p]) +
                     ", \"spall_width_m\": " + format_data_number(b_s) +
                     ", \"fe_pair_loss\": " + format_data_number(fe_loss) + "}";
    }
  }
  // Convergence: every mesh's compliances, at every position and loaded width.
  std::string meshes_csv =
      "mesh,tooth_element_m,layers,wedges_gear1,s_m,loaded_from_m,tooth1_m_per_n,"
      "tooth2_m_per_n,tooth1_change,tooth2_change\n";
  double worst_change = 0.0;
  for (std::size_t k = 0; k < fe[0].size(); ++k) {
    for (std::size_t p = 0; p < np; ++p) {
      for (std::size_t w = 0; w <= nw; ++w) {
        double change[2] = {0.0, 0.0};
        for (int g = 0; g < 2; ++g) {
          if (k > 0) change[g] = fe[g][k][p][w] / fe[g][k - 1][p][w] - 1.0;
          if (k > 0 && k + 1 == fe[0].size()) {
            worst_change = std::max(worst_change, std::fabs(change[g]));
          }
        }
        std::vector<double> fields{sizes_used[k],
                                   static_cast<double>(layer_counts[k]),
                                   static_cast<double>(wedges[k]),
                                   positions[p],
                                   w == 0 ? 0.0 : widths[w - 1],
                                   fe[0][k][p][w],
                                   fe[1][k][p][w],
                                   change[0],
                                   change[1]};
        meshes_csv += std::to_string(k + 1);
        for (const double v : fields) {
          meshes_csv += ',';
          meshes_csv += format_data_number(v);
        }
        meshes_csv += '\n';
      }
    }
  }
  const bool converged = o.refinements < 2 || worst_change < kConvergence;
  const std::string json =
      "{\n  \"case\": \"" + c.name + "\",\n  \"s_pitch_m\": " + format_data_number(s_pitch) +
      ",\n  \"contact_width_m\": " + format_data_number(b) +
      ",\n  \"spall_depth_m\": " + format_data_number(o.spall_depth) +
      ",\n  \"largest_last_mesh_change\": " + format_data_number(worst_change) +
      ",\n  \"converged\": " + (converged ? "true" : "false") + ",\n  \"fe_pair_losses\": [" +
      json_losses + "]\n}\n";
  write_file_atomically((dir / "fe_spall.csv").string(), csv);
  write_file_atomically((dir / "fe_spall.md").string(), table);
  write_file_atomically((dir / "fe_spall_meshes.csv").string(), meshes_csv);
  write_file_atomically((dir / "summary.json").string(), json);
  folder.commit();
  if (!o.quiet) {
    std::fputs(table.c_str(), stdout);
    std::fputs(meshes_csv.c_str(), stdout);
    std::fputs(json.c_str(), stdout);
  }
  if (!converged) {
    throw std::runtime_error(
        "fe-check --spall-width: the solid meshes changed by " +
        format_number(100.0 * worst_change) + " % between the two finest (at most " +
        format_number(100.0 * kConvergence) + " % asked; the results are in " + o.out + ")");
  }
}

// The chip in 3-D (docs/verification.md, "The chip in 3-D"): the pinion's tooth meshed with a
// line across it at the chip's edge (the section through the flank point at r_k), whole and with
// the wedges above that section cut away over z in [0, b_k]. Each position loads the chipped
// tooth over the whole face, or over [b_k, b] where its contact lies above r_k; the whole tooth
// is loaded over the whole face, and over [b_k, b] at those positions too (the load's width
// apart from the material's). Compliances read as the spall's.
void run_chip(const FeCheckOptions& o) {
  const SimulationCase c = read_pair_or_run_file(o.case_file).simulation_case;
  const RackGearPairGeometry pair = rack_gear_pair_geometry(c.gears);
  const RackGearGeometry& gear = pair.gear1;
  const double b = pair.contact_width_m;
  std::vector<double> widths = o.chip_widths;
  check_quarters(widths, b, "--chip-width");
  const std::vector<double> positions = solid_positions(o, pair);
  const double r_k = o.chip_radius;
  const double rb = gear.base_radius_m;
  const double s_k = r_k > rb ? std::sqrt((r_k - rb) * (r_k + rb)) : 0.0;
  if (!(s_k > pair.start_of_active_profile_m && s_k < pair.end_of_active_profile_m)) {
    throw InputError(
        "--chip-radius", r_k,
        "(" + format_number(radius_at_roll_distance(rb, pair.start_of_active_profile_m)) + ", " +
            format_number(radius_at_roll_distance(rb, pair.end_of_active_profile_m)) +
            ") m: the pinion's active profile, so that the mesh has its section");
  }
  const std::size_t np = positions.size();
  const std::size_t nw = widths.size();
  StiffnessModel pe_model;
  pe_model.kind = StiffnessModelKind::potential_energy;
  std::vector<ToothContact> contacts;
  std::vector<bool> above;
  std::vector<double> taus;
  for (const double s : positions) {
    contacts.push_back(pair_contact(pair, s).gear1);
    taus.push_back(contacts.back().tau_rad);
    above.push_back(radius_at_roll_distance(rb, s) > r_k);
  }
  taus.push_back(pair_contact(pair, s_k).gear1.tau_rad);
  const ToothOutline outline = tooth_outline(gear, "gears.bore_diameter1", 24, 48, taus);
  const double y_cut = outline.flank.at(outline.vertex_index.back()).y_m;
  // The model: [position] healthy, [width][position] chipped (this code's reading).
  std::vector<ToothCompliances> healthy_model;
  std::vector<std::vector<ToothCompliances>> chipped_model(nw);
  for (std::size_t p = 0; p < np; ++p) {
    healthy_model.push_back(tooth_compliances(gear, Gear::one, contacts[p], b, pe_model));
  }
  for (std::size_t w = 0; w < nw; ++w) {
    TipChip chip;
    chip.radius_m = r_k;
    chip.width_m = widths[w];
    place_chip(chip, gear, b);
    for (std::size_t p = 0; p < np; ++p) {
      chipped_model[w].push_back(
          chipped_tooth_compliances(gear, Gear::one, contacts[p], b, pe_model, chip));
    }
  }
  AtomicFolder folder(o.out, o.overwrite, {o.case_file});
  const std::filesystem::path dir = folder.temporary();
  const FeMaterial material{gear.youngs_modulus_pa, gear.poisson_ratio, b};
  // [mesh][position]: whole tooth over the whole face; [mesh][width][position]: whole tooth over
  // [b_k, b], chipped tooth as loaded.
  std::vector<std::vector<double>> whole;
  std::vector<std::vector<std::vector<double>>> whole_part;
  std::vector<std::vector<std::vector<double>>> chipped;
  std::vector<std::size_t> wedges;
  for (int k = 0; k < o.refinements; ++k) {
    const auto [sizes, layers] = solid_sizes(o, outline, c.gears.module_m, b, k);
    const std::string stem = "solid_chip_mesh" + std::to_string(k + 1);
    const FeMesh3 mesh =
        mesh_solid(dir, stem, tooth_geo_3d(outline, contacts, sizes, b, layers, true));
    wedges.push_back(mesh.wedges.size());
    const std::size_t n = static_cast<std::size_t>(2 * layers + 1);
    struct Lines {
      std::vector<long> p, c, a, b;
      std::vector<double> z;
    };
    std::vector<Lines> lines(np);
    for (std::size_t q = 0; q < np; ++q) {
      const OutlinePoint& pt = outline.flank.at(outline.vertex_index.at(q));
      const ToothContact& t = contacts[q];
      Lines& l = lines[q];
      l.p = nodes_on_z_line(mesh, pt.x_m, pt.y_m);
      l.c = nodes_on_z_line(mesh, 0.0, t.y_m);
      l.a = nodes_on_z_line(mesh, -0.5 * t.x_m, t.y_m);
      l.b = nodes_on_z_line(mesh, 0.5 * t.x_m, t.y_m);
      if (l.p.size() != n || l.c.size() != n || l.a.size() != n || l.b.size() != n) {
        throw std::runtime_error("the solid mesh " + stem +
                                 " lacks the lines of nodes along z at the load and its section");
      }
      for (const long id : l.p) l.z.push_back(mesh.nodes_m.at(id)[2]);
    }
    const std::vector<long> fixed = nodes_at_radius(mesh, outline.bore_radius_m);
    // One solve: `loads` [step] = (position, loaded from z); the compliance of each step.
    const auto solve_steps = [&](const FeMesh3& solid, const std::string& name,
                                 const std::vector<std::pair<std::size_t, double>>& loads) {
      std::vector<std::vector<FeLoad>> steps;
      std::vector<std::vector<double>> weights;
      std::vector<long> printed;
      for (const auto& [q, from] : loads) {
        const Lines& l = lines[q];
        weights.push_back(line_load_weights(l.z, from, b));
        const double dx = -std::cos(contacts[q].tau_rad);
        const double dy = -std::sin(contacts[q].tau_rad);
        std::vector<FeLoad> step;
        for (std::size_t i = 0; i < n; ++i) {
          if (weights.back()[i] == 0.0) continue;
          step.push_back({l.p[i], dx * weights.back()[i], dy * weights.back()[i]});
          printed.insert(printed.end(), {l.c[i], l.a[i], l.b[i]});
        }
        steps.push_back(step);
      }
      std::sort(printed.begin(), printed.end());
      printed.erase(std::unique(printed.begin(), printed.end()), printed.end());
      const auto u = solve_solid(dir, name, solid, material, fixed, steps, printed);
      std::vector<double> out;
      for (std::size_t j = 0; j < loads.size(); ++j) {
        const Lines& l = lines[loads[j].first];
        double reading = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
          if (weights[j][i] == 0.0) continue;
          reading += weights[j][i] * tooth_reading(contacts[loads[j].first], u[j].at(l.c[i]),
                                                   u[j].at(l.a[i]), u[j].at(l.b[i]))
                                         .compliance_m_per_n;
        }
        out.push_back(reading);
      }
      return out;
    };
    // The whole tooth: every position over the whole face, then each width over [b_k, b].
    std::vector<std::pair<std::size_t, double>> loads;
    for (std::size_t q = 0; q < np; ++q) loads.push_back({q, 0.0});
    for (std::size_t w = 0; w < nw; ++w) {
      for (std::size_t q = 0; q < np; ++q) loads.push_back({q, widths[w]});
    }
    const std::vector<double> r = solve_steps(mesh, stem, loads);
    whole.emplace_back(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(np));
    whole_part.emplace_back();
    chipped.emplace_back();
    for (std::size_t w = 0; w < nw; ++w) {
      const auto from = r.begin() + static_cast<std::ptrdiff_t>(np * (w + 1));
      whole_part.back().emplace_back(from, from + static_cast<std::ptrdiff_t>(np));
      FeMesh3 cut = mesh;
      cut_chip(cut, y_cut, widths[w]);
      std::vector<std::pair<std::size_t, double>> chip_loads;
      for (std::size_t q = 0; q < np; ++q) chip_loads.push_back({q, above[q] ? widths[w] : 0.0});
      chipped.back().push_back(
          solve_steps(cut, stem + "_chip" + std::to_string(w + 1), chip_loads));
    }
  }
  // The tables: each width and position, the finest mesh.
  std::string table =
      "| b_k / b | s, mm | contact above r_k | FE whole tooth, m/N | FE chipped | FE change | FE "
      "whole tooth loaded over [b_k, b] | change | model whole tooth | model chipped (this "
      "code) | change | chipped, beam and foundation x effective-width factors | change |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::string csv =
      "chip_width_m,s_m,above_chip,fe_whole_m_per_n,fe_chipped_m_per_n,fe_whole_part_m_per_n,"
      "model_whole_m_per_n,model_chipped_m_per_n,model_chipped_effective_m_per_n\n";
  for (std::size_t w = 0; w < nw; ++w) {
    const SpallWidthFactors f = spall_width_factors(b - widths[w], b, root_thickness(gear));
    for (std::size_t p = 0; p < np; ++p) {
      const double fe_whole = whole.back()[p];
      const double fe_chip = chipped.back()[w][p];
      const double fe_part = whole_part.back()[w][p];
      const ToothCompliances& m = chipped_model[w][p];
      const double model_whole = healthy_model[p].total_m_per_n();
      const double model_chip = m.total_m_per_n();
      const double model_eff =
          above[p] ? f.beam * (m.bending_m_per_n + m.shear_m_per_n + m.axial_m_per_n) +
                         f.foundation * m.foundation_m_per_n
                   : model_chip;
      char head[64];
      std::snprintf(head, sizeof head, "| %.2f | %.3f | %s | ", widths[w] / b, positions[p] * 1e3,
                    above[p] ? "yes" : "no");
      table += head + scientific(fe_whole) + " | " + scientific(fe_chip) + " | " +
               percent(fe_chip / fe_whole - 1.0) + " | " + scientific(fe_part) + " | " +
               percent(fe_part / fe_whole - 1.0) + " | " + scientific(model_whole) + " | " +
               scientific(model_chip) + " | " + percent(model_chip / model_whole - 1.0) + " | " +
               scientific(model_eff) + " | " + percent(model_eff / model_whole - 1.0) + " |\n";
      std::vector<double> fields{positions[p], above[p] ? 1.0 : 0.0, fe_whole,   fe_chip,
                                 fe_part,      model_whole,          model_chip, model_eff};
      csv += format_data_number(widths[w]);
      for (const double v : fields) {
        csv += ',';
        csv += format_data_number(v);
      }
      csv += '\n';
    }
  }
  std::string meshes_csv = "mesh,wedges,chip_width_m,s_m,fe_whole_m_per_n,fe_chipped_m_per_n\n";
  double worst_change = 0.0;
  for (std::size_t k = 0; k < whole.size(); ++k) {
    for (std::size_t w = 0; w < nw; ++w) {
      for (std::size_t p = 0; p < np; ++p) {
        std::vector<double> fields{static_cast<double>(wedges[k]), widths[w], positions[p],
                                   whole[k][p], chipped[k][w][p]};
        meshes_csv += std::to_string(k + 1);
        for (const double v : fields) {
          meshes_csv += ',';
          meshes_csv += format_data_number(v);
        }
        meshes_csv += '\n';
        if (k > 0 && k + 1 == whole.size()) {
          worst_change = std::max(worst_change, std::fabs(whole[k][p] / whole[k - 1][p] - 1.0));
          worst_change =
              std::max(worst_change, std::fabs(chipped[k][w][p] / chipped[k - 1][w][p] - 1.0));
        }
      }
    }
  }
  const bool converged = o.refinements < 2 || worst_change < kConvergence;
  const std::string json =
      "{\n  \"case\": \"" + c.name + "\",\n  \"chip_radius_m\": " + format_data_number(r_k) +
      ",\n  \"contact_width_m\": " + format_data_number(b) +
      ",\n  \"largest_last_mesh_change\": " + format_data_number(worst_change) +
      ",\n  \"converged\": " + (converged ? "true" : "false") + "\n}\n";
  write_file_atomically((dir / "fe_chip.csv").string(), csv);
  write_file_atomically((dir / "fe_chip.md").string(), table);
  write_file_atomically((dir / "fe_chip_meshes.csv").string(), meshes_csv);
  write_file_atomically((dir / "summary.json").string(), json);
  folder.commit();
  if (!o.quiet) {
    std::fputs(table.c_str(), stdout);
    std::fputs(meshes_csv.c_str(), stdout);
    std::fputs(json.c_str(), stdout);
  }
  if (!converged) {
    throw std::runtime_error(
        "fe-check --chip-width: the solid meshes changed by " +
        format_number(100.0 * worst_change) + " % between the two finest (at most " +
        format_number(100.0 * kConvergence) + " % asked; the results are in " + o.out + ")");
  }
}

// The paper's pair with the bores of the ROSS peer run, as examples/paper_pair_bores.toml.
constexpr const char* kPaperPairBores =
    "name = \"paper_pair_bores\"\n\n[gears]\nteeth1 = 20\nteeth2 = 80\nmodule = \"2 mm\"\n"
    "pressure_angle = \"20 deg\"\nface_width = \"10 mm\"\nyoungs_modulus = \"206.8 GPa\"\n"
    "poisson_ratio = 0.3\ndensity = \"7800 kg/m^3\"\nbacklash = \"0.05 mm\"\n"
    "bore_diameter1 = \"20 mm\"\nbore_diameter2 = \"60 mm\"\n\n[model]\n"
    "stiffness_model = \"potential-energy\"\n";

}  // namespace

ReportSection reproduce_fe(const ReproduceContext& context) {
  const std::filesystem::path dir = context.out / "fe";
  std::filesystem::create_directories(dir);
  write_file_atomically((dir / "paper_pair_bores.toml").string(), kPaperPairBores);
  write_file_atomically((dir / "rig_17_38.toml").string(), rig_17_38_toml());
  FeCheckOptions tooth;
  tooth.case_file = (dir / "paper_pair_bores.toml").string();
  tooth.out = (dir / "wheel").string();
  tooth.gear = 2;
  tooth.crack_depths = {0.0, 1e-3, 2e-3};
  tooth.overwrite = true;
  tooth.no_plots = true;
  tooth.quiet = true;
  run_tooth(tooth);
  FeCheckOptions solid;
  solid.case_file = (dir / "rig_17_38.toml").string();
  solid.out = (dir / "spall").string();
  solid.spall_widths = {7.5e-3};
  solid.overwrite = true;
  solid.quiet = true;
  run_spall(solid);
  // The figure: the wheel's compliance over the path of contact at each crack depth.
  Figure f;
  f.name = "fe_crack";
  f.title = "Paper's wheel tooth with a root crack (45 deg): finite elements against the models";
  f.x_label = "contact position s from T_1 on the line of action, mm";
  f.y_label = "tooth compliance along the load, 1e-9 m/N";
  f.setup = {"set key outside right top vertical"};
  const char* colours[3] = {"#1f77b4", "#ff7f0e", "#d62728"};
  const char* depths[3] = {"0", "0.001", "0.002"};
  const char* names[3] = {"healthy", "q = 1 mm", "q = 2 mm"};
  for (int j = 0; j < 3; ++j) {
    const std::string pick = std::string("(abs($1-") + depths[j] + ")<1e-9 ? $5*1e3 : 1/0)";
    const std::string colour = std::string(" lc rgb '") + colours[j] + "'";
    f.series.push_back("'wheel/fe_crack.csv' using " + pick +
                       ":($9*1e9) with linespoints lw 2 pt 7" + colour + " title 'FE, " + names[j] +
                       "'");
    f.series.push_back("'wheel/fe_crack.csv' using " + pick +
                       ":($10*1e9) with linespoints lw 1 dt 2 pt 5" + colour +
                       " title 'potential energy, " + names[j] + "'");
    f.series.push_back("'wheel/fe_crack.csv' using " + pick +
                       ":($11*1e9) with linespoints lw 1 dt 3 pt 4" + colour +
                       " title 'ross-compatible, " + names[j] + "'");
  }
  render(dir, f);
  // The spall: the pair's stiffness lost by a half-face spall, each reading.
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  };
  {
    std::istringstream rows(read(dir / "spall" / "fe_spall.csv"));
    std::string line;
    std::getline(rows, line);
    const char* labels[4] = {"finite elements", "Hertz only (default)", "width-scaled",
                             "effective width"};
    std::string bars = "reading,pair_loss_percent\n";
    for (int r = 0; r < 4 && std::getline(rows, line); ++r) {
      bars += std::string("\"") + labels[r] + "\"," +
              format_data_number(100.0 * std::stod(line.substr(line.rfind(',') + 1))) + "\n";
    }
    write_file_atomically((dir / "fe_spall_loss.csv").string(), bars);
  }
  Figure g;
  g.name = "fe_spall";
  g.title = "Rig pair 17/38 at the pitch point, half-face spall on the pinion: stiffness lost";
  g.x_label = "reading of the spall";
  g.y_label = "pair stiffness lost, %";
  g.setup = {"set style fill solid 0.6 border -1", "set boxwidth 0.5", "set yrange [0:*]",
             "set xrange [-0.6:3.6]", "unset key"};
  g.series = {"'fe_spall_loss.csv' using 0:2:xtic(1) with boxes lc rgb '#1f77b4'",
              "'fe_spall_loss.csv' using 0:2:(sprintf('%.1f %%', $2)) with labels offset 0,1"};
  render(dir, g);
  ReportSection section;
  section.title = "Finite-element check of the tooth compliance (reproduce --fe)";
  section.text =
      "gmsh and CalculiX (docs/verification.md, \"Finite-element check of the tooth "
      "compliance\"). The paper's wheel (80 teeth, bore 60 mm) in 2-D plane stress, healthy and "
      "with a root crack of q = 1 and 2 mm at 45 deg from the potential-energy model's crack "
      "start, as a slit; 1e-9 m/N, finest of three meshes (`fe/wheel/`; a depth of 0 is the "
      "healthy tooth). FE change, PE change: the compliance the crack adds by each.\n\n" +
      read(dir / "wheel" / "fe_crack.md") +
      "\n![Cracked wheel tooth](fe/fe_crack.png)\n\nThe healthy wheel term by term:\n\n" +
      read(dir / "wheel" / "fe_check.md") +
      "\nThe rig pair (17/38, m 3 mm, b 15 mm) at the pitch point in 3-D, each tooth loaded over "
      "the whole face and over the half a spall of b_s = 7.5 mm leaves (`fe/spall/`; the pair "
      "adds Hertz over the contact length to the teeth):\n\n" +
      read(dir / "spall" / "fe_spall.md") + "\nThe solid meshes (m/N):\n\n```\n" +
      read(dir / "spall" / "fe_spall_meshes.csv") + "```\n\n![Spall](fe/fe_spall.png)\n";
  return section;
}

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
  fe->add_option("--spall-width", o->spall_widths,
                 "solve the spall in 3-D instead: both teeth at each --solid-at position, loaded "
                 "over the whole face and over the width each spall this wide leaves (m, "
                 "comma-separated; a quarter, half or three quarters of the face); fe_spall.csv, "
                 "fe_spall.md, fe_spall_meshes.csv")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  fe->add_option("--solid-at", o->solid_positions,
                 "with --spall-width or --chip-width: contact positions s (m from T_1 along the "
                 "line of action, comma-separated, on the active path less 0.5 mm at each end; "
                 "default the pitch point)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  fe->add_option("--chip-width", o->chip_widths,
                 "solve a chip in 3-D instead: the pinion's tooth above --chip-radius cut away "
                 "over each of these widths b_k from the face z = 0 (m, comma-separated; a "
                 "quarter, half or three quarters of the face), loaded at each --solid-at "
                 "position over the face the chip leaves; fe_chip.csv, fe_chip.md, "
                 "fe_chip_meshes.csv")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  fe->add_option("--chip-radius", o->chip_radius,
                 "with --chip-width: r_k, the radius of the flank point on the chip's edge (m, "
                 "above the lowest and below the highest contact of the pinion)")
      ->check(CLI::Range(0.0, 10.0));
  fe->add_option("--spall-depth", o->spall_depth,
                 "the spall's depth d_s for the models' reading (m, default 2e-4; the solid "
                 "keeps the pit's material)")
      ->check(CLI::Range(0.0, 0.01));
  fe->add_option("--solid-element-size", o->solid_element_size,
                 "with --spall-width: the coarsest solid mesh's element size on the tooth, a "
                 "fraction of the module in [0.2, 1]; each finer mesh divides it by sqrt 2")
      ->check(CLI::Range(0.2, 1.0));
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
    if (o->edge_crack > 0.0 && !o->cantilever) {
      throw InputError("--edge-crack", o->edge_crack, "only with --cantilever");
    }
    if (!o->solid_positions.empty() && o->spall_widths.empty() && o->chip_widths.empty()) {
      throw InputError("--solid-at", "given", "only with --spall-width or --chip-width");
    }
    if (!o->chip_widths.empty() &&
        (o->cantilever || !o->crack_depths.empty() || !o->spall_widths.empty())) {
      throw InputError("--chip-width", "given",
                       "a case's 3-D chip, without --cantilever, --crack-depths or --spall-width");
    }
    if (o->chip_widths.empty() != !(o->chip_radius > 0.0)) {
      throw InputError("--chip-radius", o->chip_radius, "given with --chip-width, and only then");
    }
    if (!o->spall_widths.empty() && (o->cantilever || !o->crack_depths.empty())) {
      throw InputError("--spall-width", "given",
                       "a case's 3-D spall, without --cantilever or --crack-depths");
    }
    if (!o->crack_depths.empty() && o->cantilever) {
      throw InputError("--crack-depths", "given", "a case's cracked tooth, without --cantilever");
    }
    require_output_folder(
        o->out, o->overwrite,
        o->case_file.empty() ? std::vector<std::string>{} : std::vector<std::string>{o->case_file});
    if (o->cantilever) {
      run_cantilever(*o);
    } else if (!o->spall_widths.empty()) {
      run_spall(*o);
    } else if (!o->chip_widths.empty()) {
      run_chip(*o);
    } else {
      run_tooth(*o);
    }
  });
}

}  // namespace gearimpact::cli
