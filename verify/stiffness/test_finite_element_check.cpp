// The finite-element check's own pieces without the outside programs: the
// tooth outline against the involute's and the root circle's equations, the
// readers of gmsh's and CalculiX's files on samples of their output, the
// solver input's units, and the reading of a compliance against rigid-body
// kinematics.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_outline.hpp"
#include "gearimpact/stiffness/finite_element_check.hpp"
#include "relative.hpp"

using namespace gearimpact;
using gearimpact::verify::relative_difference;

namespace {

GearPair pair_with_bores() {
  GearPair p = paper_gear_pair();
  p.bore_diameter1_m = 0.020;
  p.bore_diameter2_m = 0.060;
  return p;
}

}  // namespace

TEST_CASE("the tooth outline runs from the root circle along the involute to the tip circle") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(pair_with_bores());
  const RackGearGeometry& g = pair.gear1;
  const double pitch_tau = 0.5 * (g.form_tau_rad + g.tip_tau_rad);
  const ToothOutline o =
      tooth_outline(g, "gears.bore_diameter1", 12, 20, {pitch_tau, g.tip_tau_rad});
  // The foot on the root circle, the last point on the tip circle (relative 1e-12: rounding of
  // the parametric forms).
  CHECK(relative_difference(std::hypot(o.flank.front().x_m, o.flank.front().y_m), g.root_radius_m) <
        1e-12);
  CHECK(relative_difference(std::hypot(o.flank.back().x_m, o.flank.back().y_m), g.tip_radius_m) <
        1e-12);
  CHECK(o.bore_radius_m == doctest::Approx(0.010).epsilon(1e-15));
  // Every involute point satisfies the involute's polar form: at radius r the half angle is
  // theta_b - inv(acos(r_b / r)) (an equation apart from the tau parametrisation).
  for (std::size_t i = 12; i < o.flank.size(); ++i) {
    const double r = std::hypot(o.flank[i].x_m, o.flank[i].y_m);
    const double half_angle = std::atan2(o.flank[i].x_m, o.flank[i].y_m);
    const double expected =
        g.half_tooth_angle_base_rad - involute_function(std::acos(g.base_radius_m / r));
    CHECK(std::fabs(half_angle - expected) < 1e-12);
  }
  // The radii rise from root to tip: a simple polyline.
  for (std::size_t i = 1; i < o.flank.size(); ++i) {
    CHECK(std::hypot(o.flank[i].x_m, o.flank[i].y_m) >
          std::hypot(o.flank[i - 1].x_m, o.flank[i - 1].y_m));
  }
  // The asked points are vertices: the contact at tau lies at r_b sqrt(1 + (tau + theta_b)^2).
  REQUIRE(o.vertex_index.size() == 2);
  const OutlinePoint& at = o.flank[o.vertex_index[0]];
  const double roll = pitch_tau + g.half_tooth_angle_base_rad;
  CHECK(relative_difference(std::hypot(at.x_m, at.y_m),
                            g.base_radius_m * std::sqrt(1.0 + roll * roll)) < 1e-12);
  CHECK(o.vertex_index[1] == o.flank.size() - 1);
}

TEST_CASE("the tooth outline refuses a gear without a bore, naming the key") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(paper_gear_pair());
  try {
    tooth_outline(pair.gear2, "gears.bore_diameter2", 12, 20, {});
    FAIL("no refusal");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("gears.bore_diameter2") != std::string::npos);
  }
}

TEST_CASE("gmsh's inp mesh is read in metres with its six-node triangles and node sets") {
  // The form gmsh 4.8 writes (-format inp, Mesh.SaveGroupsOfNodes = 1).
  const std::string text =
      "*Heading\n mesh.inp\n*NODE\n1, 0, 0, 0\n2, 2, 0, 0\n3, 0, 2, 0\n4, 1, 0, 0\n5, 1, 1, 0\n"
      "6, 0, 1, 0\n******* E L E M E N T S *************\n*ELEMENT, type=T3D3, ELSET=Line1\n"
      "1, 1, 3, 6\n*ELEMENT, type=CPS6, ELSET=Surface1\n2, 1, 2, 3, 4, 5, 6\n"
      "*ELSET,ELSET=BODY\n2, \n*NSET,NSET=LOAD\n2, \n*NSET,NSET=FIXED\n1, 3, 6, \n";
  const FeMesh mesh = read_gmsh_inp(text);
  REQUIRE(mesh.nodes_m.size() == 6);
  CHECK(mesh.nodes_m.at(2)[0] == doctest::Approx(0.002).epsilon(1e-15));
  REQUIRE(mesh.triangles.size() == 1);  // the line elements of the curve are left out
  CHECK(mesh.triangles[0][5] == 6);
  CHECK(mesh.node_of("LOAD") == 2);
  CHECK(mesh.node_sets.at("FIXED").size() == 3);
  CHECK_THROWS_AS(mesh.node_of("FIXED"), std::runtime_error);
  CHECK_THROWS_AS(read_gmsh_inp("*NODE\n1, 0, 0, 0\n"), std::runtime_error);
}

TEST_CASE("the CalculiX input is in mm, N and MPa, and its fields fit CalculiX's 20 characters") {
  FeMesh mesh;
  mesh.nodes_m = {{1, {0.0, 0.0}},   {2, {0.002, 0.0}},   {3, {0.0, 0.002}},
                  {4, {0.001, 0.0}}, {5, {0.001, 0.001}}, {6, {1.0 / 3.0e3, 0.001}}};
  mesh.triangles = {{1, 2, 3, 4, 5, 6}};
  mesh.node_sets["FIXED"] = {1, 3};
  const std::string text =
      calculix_input(mesh, {206e9, 0.3, 0.01}, "FIXED", {{2, -0.5, -0.25}, {5, 1.0, 0.0}}, {5});
  CHECK(text.find("*SOLID SECTION, ELSET=BODY, MATERIAL=GEAR\n10\n") != std::string::npos);
  CHECK(text.find("*ELASTIC\n206000, 0.3\n") != std::string::npos);
  CHECK(text.find("2, 2, 0\n") != std::string::npos);  // node 2 at 2 mm
  std::size_t steps = 0;
  for (std::size_t at = text.find("*STEP"); at != std::string::npos;
       at = text.find("*STEP", at + 1))
    ++steps;
  CHECK(steps == 2);
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind("**", 0) == 0) continue;  // a comment line
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) CHECK(field.size() <= 20);
  }
}

TEST_CASE("CalculiX's printed displacements are read per step in metres") {
  // The form CalculiX 2.20 prints (*NODE PRINT, U).
  const std::string text =
      "\n                        S T E P       1\n\n\n                                INCREMENT    "
      " 1\n\n\n"
      " displacements (vx,vy,vz) for set PRINTED and time  0.1000000E+01\n\n"
      "         6  1.021019E-10 -1.624089E-03 -1.009690E-20\n"
      "         7  2.0E-04 -3.0E-04  0.0E+00\n\n"
      "                        S T E P       2\n\n"
      " displacements (vx,vy,vz) for set PRINTED and time  0.2000000E+01\n\n"
      "         6 -4.365208E-06 -6.395741E-11 -1.522012E-22\n"
      "         7  1.0E-03  0.0E+00  0.0E+00\n";
  const auto steps = read_calculix_dat(text, 2, {6, 7});
  REQUIRE(steps.size() == 2);
  CHECK(steps[0].at(6)[1] == doctest::Approx(-1.624089e-6).scale(0).epsilon(1e-12));
  CHECK(steps[1].at(7)[0] == doctest::Approx(1e-6).scale(0).epsilon(1e-12));
  CHECK_THROWS_AS(read_calculix_dat(text, 3, {6}), std::runtime_error);
  CHECK_THROWS_AS(read_calculix_dat(text, 2, {8}), std::runtime_error);
}

TEST_CASE("the compliance read from a section moving rigidly is the load point's motion along d") {
  // Rigid kinematics: u(p) = t + w z x (p - p0). Carried from C, A and B to the load point, the
  // reading must equal d . u(load) for any translation, rotation and pivot.
  ToothContact contact{};
  contact.x_m = 1.7e-3;
  contact.y_m = 20.3e-3;
  contact.tau_rad = 0.41;
  const double t[2] = {-3e-9, 2e-9};
  const double w = 4e-7;
  const double p0[2] = {0.5e-3, 11e-3};
  auto u = [&](double x, double y) {
    return std::array<double, 2>{t[0] - w * (y - p0[1]), t[1] + w * (x - p0[0])};
  };
  const FeToothReading r =
      tooth_reading(contact, u(0.0, contact.y_m), u(-0.5 * contact.x_m, contact.y_m),
                    u(0.5 * contact.x_m, contact.y_m));
  const auto load = u(contact.x_m, contact.y_m);
  const double expected =
      -std::cos(contact.tau_rad) * load[0] - std::sin(contact.tau_rad) * load[1];
  CHECK(relative_difference(r.compliance_m_per_n, expected) < 1e-12);
  // The centre line alone misses the rotation's share w x_t d_y.
  const auto centre = u(0.0, contact.y_m);
  CHECK(relative_difference(r.centre_line_m_per_n, -std::cos(contact.tau_rad) * centre[0] -
                                                       std::sin(contact.tau_rad) * centre[1]) <
        1e-12);
}

TEST_CASE(
    "a root crack's slit runs q from the flank point at r_s, its tip h_c - q sin nu from the "
    "centre line") {
  const double r_s = 0.0779;
  const double h_c = 0.00223;
  const double q = 0.0015;
  const double nu = 0.6;
  const FeSlit slit = root_crack_slit(r_s, h_c, q, nu);
  // Relative 1e-15 and absolute 1e-18 m: one or two roundings of the inputs' size.
  CHECK(relative_difference(std::hypot(slit.mouth.x_m, slit.mouth.y_m), r_s) < 1e-15);
  CHECK(slit.mouth.x_m == h_c);
  CHECK(std::fabs(slit.tip.x_m - (h_c - q * std::sin(nu))) < 1e-18);
  // The slit's length from its ends' coordinates, which are 50 times q: 1e-13 leaves room for
  // the cancellation's 50 ulps of q.
  CHECK(relative_difference(
            std::hypot(slit.tip.x_m - slit.mouth.x_m, slit.tip.y_m - slit.mouth.y_m), q) < 1e-13);
  // Towards the root: the tip lies below the mouth, at nu to the centre line.
  CHECK(slit.tip.y_m < slit.mouth.y_m);
  CHECK(std::fabs(std::atan2(slit.mouth.x_m - slit.tip.x_m, slit.mouth.y_m - slit.tip.y_m) - nu) <
        1e-12);
}

TEST_CASE("open_slit gives the triangles on the slit's left their own nodes, all but the tip's") {
  // Six-node triangles around a slit from the mouth (0, 0) on the left edge to the tip (1, 0):
  // two above it, two below, two beyond the tip. Vertices 1..7, then the mid-side nodes.
  FeMesh mesh;
  const std::map<long, std::array<double, 2>> vertices{
      {1, {0, 0}}, {2, {1, 0}}, {3, {0, 1}}, {4, {1, 1}}, {5, {0, -1}}, {6, {1, -1}}, {7, {2, 0}}};
  mesh.nodes_m = vertices;
  long next = 7;
  std::map<std::pair<long, long>, long> mid;
  const auto middle = [&](long a, long b) {
    const auto key = std::minmax(a, b);
    const auto found = mid.find(key);
    if (found != mid.end()) return found->second;
    const long n = ++next;
    mesh.nodes_m[n] = {0.5 * (mesh.nodes_m[a][0] + mesh.nodes_m[b][0]),
                       0.5 * (mesh.nodes_m[a][1] + mesh.nodes_m[b][1])};
    mid[key] = n;
    return n;
  };
  for (const auto& [a, b, c] : std::vector<std::array<long, 3>>{
           {1, 2, 3}, {2, 4, 3}, {1, 5, 2}, {2, 5, 6}, {2, 7, 4}, {2, 6, 7}}) {
    mesh.triangles.push_back({a, b, c, middle(a, b), middle(b, c), middle(c, a)});
  }
  const long slit_middle = middle(1, 2);
  mesh.node_sets["SLIT"] = {1, slit_middle, 2};
  const FeMesh before = mesh;
  const std::size_t duplicated = open_slit(mesh, FeSlit{{0, 0}, {1, 0}}, "SLIT");
  // The mouth and the slit's mid-side node are doubled; the tip is not.
  CHECK(duplicated == 2);
  CHECK(mesh.nodes_m.size() == before.nodes_m.size() + 2);
  // Above the slit (its left, looking from mouth to tip): the twins, at the same places.
  for (const std::size_t t : {0, 1}) {
    for (std::size_t k = 0; k < 6; ++k) {
      const long was = before.triangles[t][k];
      const long is = mesh.triangles[t][k];
      if (was == 1 || was == slit_middle) {
        CHECK(is > next);
        CHECK(mesh.nodes_m.at(is) == before.nodes_m.at(was));
      } else {
        CHECK(is == was);
      }
    }
  }
  // Below and beyond the tip: unchanged; the tip one node for all.
  for (const std::size_t t : {2, 3, 4, 5}) CHECK(mesh.triangles[t] == before.triangles[t]);
  CHECK(mesh.node_sets == before.node_sets);
  // Without the set, or with a tip off the set's nodes: named.
  FeMesh other = before;
  CHECK_THROWS_WITH_AS(open_slit(other, FeSlit{{0, 0}, {1, 0}}, "CRACK"),
                       doctest::Contains("CRACK"), std::runtime_error);
  CHECK_THROWS_WITH_AS(open_slit(other, FeSlit{{0, 0}, {1.5, 0}}, "SLIT"), doctest::Contains("tip"),
                       std::runtime_error);
}

TEST_CASE("a line load's consistent nodal forces integrate a quadratic exactly over its range") {
  // Four quadratic edges over b = 8 mm: corner, mid-side, corner, ...
  const double b = 0.008;
  std::vector<double> z;
  for (int k = 0; k <= 8; ++k) z.push_back(b * k / 8.0);
  // The nodal forces of a unit force spread over [from, to] reproduce the mean of any quadratic
  // q(z) over that range (Simpson's rule on each edge); relative 1e-14: a few roundings.
  const auto mean = [&](const std::vector<double>& w, int power) {
    double sum = 0.0;
    for (std::size_t k = 0; k < z.size(); ++k) sum += w[k] * std::pow(z[k], power);
    return sum;
  };
  const std::vector<double> full = line_load_weights(z, 0.0, b);
  CHECK(relative_difference(mean(full, 0), 1.0) < 1e-14);
  CHECK(relative_difference(mean(full, 1), b / 2.0) < 1e-14);
  CHECK(relative_difference(mean(full, 2), b * b / 3.0) < 1e-14);
  const std::vector<double> half = line_load_weights(z, b / 2.0, b);
  for (std::size_t k = 0; k < 4; ++k) CHECK(half[k] == 0.0);
  CHECK(half[4] > 0.0);
  CHECK(relative_difference(mean(half, 0), 1.0) < 1e-14);
  CHECK(relative_difference(mean(half, 1), 0.75 * b) < 1e-14);
  // (b^3 - (b/2)^3) / 3 / (b/2) = 7 b^2 / 12.
  CHECK(relative_difference(mean(half, 2), 7.0 * b * b / 12.0) < 1e-14);
  // Corner 1/6, mid-side 4/6 of an edge's share, corners shared by two edges.
  CHECK(relative_difference(full[1], 4.0 / 6.0 / 4.0) < 1e-14);
  CHECK(relative_difference(full[2], 2.0 / 6.0 / 4.0) < 1e-14);
  // A range that ends between layer planes, or an even count, is refused.
  CHECK_THROWS_AS(line_load_weights(z, 0.3 * b, b), std::invalid_argument);
  CHECK_THROWS_AS(line_load_weights({0.0, 1.0}, 0.0, 1.0), std::invalid_argument);
}

TEST_CASE("gmsh's solid mesh is read in metres with its wedges, and its lines of nodes found") {
  // One fifteen-node wedge, 2 mm high, as gmsh 4.8 writes a recombined extrusion (-format inp):
  // corners of the bottom triangle, of the top one, mid-sides below, above and along z.
  const std::string text =
      "*Heading\n mesh.inp\n*NODE\n"
      "1, 0, 0, 0\n2, 3, 0, 0\n3, 0, 4, 0\n4, 0, 0, 2\n5, 3, 0, 2\n6, 0, 4, 2\n"
      "7, 1.5, 0, 0\n8, 1.5, 2, 0\n9, 0, 2, 0\n10, 1.5, 0, 2\n11, 1.5, 2, 2\n12, 0, 2, 2\n"
      "13, 0, 0, 1\n14, 3, 0, 1\n15, 0, 4, 1\n"
      "******* E L E M E N T S *************\n*ELEMENT, type=CPS6, ELSET=Surface1\n"
      "1, 1, 2, 3, 7, 8, 9\n*ELEMENT, type=C3D15, ELSET=Volume1\n"
      "2, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15\n*ELSET,ELSET=BODY\n2, \n";
  const FeMesh3 mesh = read_gmsh_inp_3d(text);
  REQUIRE(mesh.nodes_m.size() == 15);
  REQUIRE(mesh.wedges.size() == 1);  // the triangle is left out
  CHECK(mesh.wedges[0][14] == 15);
  CHECK(mesh.nodes_m.at(6)[1] == doctest::Approx(0.004).epsilon(1e-15));
  CHECK(mesh.nodes_m.at(6)[2] == doctest::Approx(0.002).epsilon(1e-15));
  CHECK(nodes_on_z_line(mesh, 0.003, 0.0) == std::vector<long>{2, 14, 5});
  CHECK(nodes_on_z_line(mesh, 0.001, 0.0).empty());
  CHECK(nodes_at_radius(mesh, 0.004) == std::vector<long>{3, 6, 15});
  // A wedge without all its nodes, and text without wedges, are refused.
  CHECK_THROWS_AS(read_gmsh_inp_3d("*NODE\n1, 0, 0, 0\n"), std::runtime_error);
  CHECK_THROWS_AS(read_gmsh_inp_3d("*NODE\n1, 0, 0, 0\n*ELEMENT, type=C3D15\n"
                                   "1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15\n"),
                  std::runtime_error);
  // The solver's input: C3D15 in mm, the bore held in x, y and z, a step per load set.
  const std::string inp = calculix_input_3d(mesh, {206e9, 0.3, 0.01}, {3, 6, 15},
                                            {{{2, -0.5, -0.25}}, {{5, 1.0, 0.0}}}, {1});
  CHECK(inp.find("*ELEMENT, TYPE=C3D15, ELSET=BODY\n1, 1, 2, 3,") != std::string::npos);
  CHECK(inp.find("\n6, 0, 4, 2\n") != std::string::npos);
  CHECK(inp.find("*BOUNDARY\nFIXED, 1, 3\n") != std::string::npos);
  CHECK(inp.find("*CLOAD, OP=NEW\n2, 1, -0.5\n2, 2, -0.25\n") != std::string::npos);
  CHECK(inp.find("*CLOAD, OP=NEW\n5, 1, 1\n5, 2, 0\n") != std::string::npos);
}

TEST_CASE("the solid tooth is the surface extruded over the face width in recombined layers") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(pair_with_bores());
  const RackGearGeometry& g = pair.gear1;
  const double tau = 0.5 * (g.form_tau_rad + g.tip_tau_rad);
  const ToothOutline o = tooth_outline(g, "gears.bore_diameter1", 12, 20, {tau});
  const PairContact c =
      pair_contact(pair, 0.5 * (pair.start_of_active_profile_m + pair.end_of_active_profile_m));
  const std::string geo = tooth_geo_3d(o, {c.gear1}, {0.001, 0.004}, 0.01, 8);
  CHECK(geo.find("Extrude {0, 0, 10} { Surface{1}; Layers{8}; Recombine; };") != std::string::npos);
  CHECK(geo.find("Mesh.SecondOrderIncomplete = 1;") != std::string::npos);
  CHECK(geo.find("Physical Volume(\"BODY\")") != std::string::npos);
  // No 2-D groups: a physical surface or point would make gmsh write only those.
  CHECK(geo.find("Physical Surface") == std::string::npos);
  CHECK(geo.find("Physical Point") == std::string::npos);
}

TEST_CASE(
    "cut_chip removes the wedges above the chip's section within its width, and their nodes") {
  // Two stacked wedges along z (0 to 2 mm and 2 to 4 mm) of the triangle (0,0) (3,0) (0,4) mm,
  // and a third one shifted down by 10 mm in y, below any cut.
  FeMesh3 mesh;
  const std::array<std::array<double, 2>, 6> corners_xy{
      {{0.0, 0.0}, {3e-3, 0.0}, {0.0, 4e-3}, {1.5e-3, 0.0}, {1.5e-3, 2e-3}, {0.0, 2e-3}}};
  long next = 1;
  const auto wedge = [&](double y_shift, double z0) {
    std::array<long, 15> w{};
    // Corners below, above; mid-sides below, above; along z (gmsh's C3D15 order).
    const double z1 = z0 + 2e-3;
    const double zm = z0 + 1e-3;
    const auto add = [&](double x, double y, double z) {
      mesh.nodes_m[next] = {x, y + y_shift, z};
      return next++;
    };
    for (std::size_t i = 0; i < 3; ++i) w[i] = add(corners_xy[i][0], corners_xy[i][1], z0);
    for (std::size_t i = 0; i < 3; ++i) w[3 + i] = add(corners_xy[i][0], corners_xy[i][1], z1);
    for (std::size_t i = 0; i < 3; ++i)
      w[6 + i] = add(corners_xy[3 + i][0], corners_xy[3 + i][1], z0);
    for (std::size_t i = 0; i < 3; ++i)
      w[9 + i] = add(corners_xy[3 + i][0], corners_xy[3 + i][1], z1);
    for (std::size_t i = 0; i < 3; ++i) w[12 + i] = add(corners_xy[i][0], corners_xy[i][1], zm);
    mesh.wedges.push_back(w);
  };
  wedge(0.0, 0.0);
  wedge(0.0, 2e-3);
  wedge(-10e-3, 0.0);
  // The corners' centroids lie at y = 4/3 mm (the first two) and -8.67 mm; z at 1 and 3 mm.
  FeMesh3 cut = mesh;
  CHECK(cut_chip(cut, 1e-3, 2e-3) == 1);
  REQUIRE(cut.wedges.size() == 2);
  CHECK(cut.wedges[0] == mesh.wedges[1]);
  CHECK(cut.wedges[1] == mesh.wedges[2]);
  CHECK(cut.nodes_m.size() == 30);
  CHECK(cut.nodes_m.count(mesh.wedges[0][0]) == 0);
  // A cut above the centroids, or a width short of them, removes nothing.
  cut = mesh;
  CHECK(cut_chip(cut, 2e-3, 4e-3) == 0);
  CHECK(cut_chip(cut, 1e-3, 0.5e-3) == 0);
  CHECK(cut.nodes_m.size() == 45);
}

TEST_CASE("the solid tooth with a chip's edge: a line across the tooth at the last vertex") {
  const RackGearPairGeometry pair = rack_gear_pair_geometry(pair_with_bores());
  const RackGearGeometry& g = pair.gear1;
  const double tau = 0.5 * (g.form_tau_rad + g.tip_tau_rad);
  const double tau_edge = 0.25 * g.form_tau_rad + 0.75 * g.tip_tau_rad;
  const ToothOutline o = tooth_outline(g, "gears.bore_diameter1", 12, 20, {tau, tau_edge});
  const PairContact c =
      pair_contact(pair, 0.5 * (pair.start_of_active_profile_m + pair.end_of_active_profile_m));
  const std::string plain = tooth_geo_3d(o, {c.gear1, c.gear1}, {0.001, 0.004}, 0.01, 8);
  const std::string edged = tooth_geo_3d(o, {c.gear1}, {0.001, 0.004}, 0.01, 8, true);
  // One line more, embedded in the surface, and nothing else.
  // Points, then the line, embedded in the surface.
  const auto embedded = [](const std::string& text) {
    std::size_t count = 0;
    for (std::size_t at = text.find("} In Surface{1};"); at != std::string::npos;
         at = text.find("} In Surface{1};", at + 1)) {
      ++count;
    }
    return count;
  };
  CHECK(embedded(plain) == 1);
  CHECK(embedded(edged) == 2);
  CHECK(edged.find("Line{") != std::string::npos);
  CHECK(plain.find("Line{") == std::string::npos);
  // A contact count that does not leave exactly the edge's vertex is refused.
  CHECK_THROWS_AS(tooth_geo_3d(o, {c.gear1, c.gear1}, {0.001, 0.004}, 0.01, 8, true),
                  std::invalid_argument);
}
