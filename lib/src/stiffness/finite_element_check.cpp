#include "gearimpact/stiffness/finite_element_check.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

// The files' length unit: mm (and N, so MPa).
constexpr double kMm = 1e3;

std::string number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

// CalculiX reads a field of at most 20 characters: 14 digits fit with sign and exponent.
std::string short_number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.14g", value);
  return text;
}

// Writes the gmsh entities of one geometry, numbering points and curves.
class GeoWriter {
 public:
  GeoWriter() {
    text_ =
        "// Made by gearimpact fe-check: mm. Second-order triangles, node sets of the\n"
        "// physical groups (the CalculiX input reads them).\n"
        "Mesh.ElementOrder = 2;\n"
        "Mesh.SecondOrderLinear = 0;\n"
        "Mesh.SaveGroupsOfNodes = 1;\n"
        "Mesh.Algorithm = 6;\n"
        "Mesh.CharacteristicLengthExtendFromBoundary = 1;\n";
  }
  int point(double x_m, double y_m, double size_m) {
    const int id = ++points_;
    text_ += "Point(" + std::to_string(id) + ") = {" + number(x_m * kMm) + ", " +
             number(y_m * kMm) + ", 0, " + number(size_m * kMm) + "};\n";
    return id;
  }
  int line(int from, int to) {
    const int id = ++curves_;
    text_ += "Line(" + std::to_string(id) + ") = {" + std::to_string(from) + ", " +
             std::to_string(to) + "};\n";
    return id;
  }
  // An arc of less than pi about `centre`.
  int arc(int from, int centre, int to) {
    const int id = ++curves_;
    text_ += "Circle(" + std::to_string(id) + ") = {" + std::to_string(from) + ", " +
             std::to_string(centre) + ", " + std::to_string(to) + "};\n";
    return id;
  }
  static std::string list(const std::vector<int>& ids) {
    std::string out;
    for (std::size_t i = 0; i < ids.size(); ++i) out += (i ? ", " : "") + std::to_string(ids[i]);
    return out;
  }
  void add(const std::string& line) { text_ += line + "\n"; }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
  int points_ = 0;
  int curves_ = 0;
};

}  // namespace

FeSlit root_crack_slit(double start_radius_m, double start_half_thickness_m, double depth_m,
                       double angle_rad) {
  const double y =
      std::sqrt(start_radius_m * start_radius_m - start_half_thickness_m * start_half_thickness_m);
  return {
      {start_half_thickness_m, y},
      {start_half_thickness_m - depth_m * std::sin(angle_rad), y - depth_m * std::cos(angle_rad)}};
}

namespace {

// The tooth's surface (with its physical groups for the 2-D model); `geo` is
// left with the surface numbered 1.
std::string tooth_surface(GeoWriter& geo, const ToothOutline& outline,
                          const std::vector<ToothContact>& contacts, const FeMeshSizes& sizes,
                          const std::optional<FeSlit>& slit, bool chip_edge = false) {
  // A cut takes the outline's last vertex (tooth_geo_3d).
  if (contacts.size() + (chip_edge ? 1 : 0) != outline.vertex_index.size()) {
    throw std::invalid_argument("tooth_geo: one contact per outline vertex (and the cut's)");
  }
  const double fine = sizes.tooth_m;
  const double coarse = sizes.body_m;
  const int centre = geo.point(0.0, 0.0, coarse);
  // The loaded flank (x > 0) and its mirror, root to tip.
  std::vector<int> right;
  std::vector<int> left;
  for (const OutlinePoint& p : outline.flank) right.push_back(geo.point(p.x_m, p.y_m, fine));
  for (const OutlinePoint& p : outline.flank) left.push_back(geo.point(-p.x_m, p.y_m, fine));
  // The loads' nodes before a slit's mouth joins the flank's vertices.
  std::vector<int> loaded;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    loaded.push_back(right.at(outline.vertex_index[i]));
  }
  int mouth = 0;
  int tip = 0;
  if (slit) {
    // The mouth between the two flank vertices whose radii bracket its own (the radius rises
    // from root to tip along the flank); the tip's elements a quarter of the tooth's, where the
    // strain is singular.
    const double r = std::hypot(slit->mouth.x_m, slit->mouth.y_m);
    std::size_t after = 1;
    while (after < outline.flank.size() &&
           std::hypot(outline.flank[after].x_m, outline.flank[after].y_m) < r) {
      ++after;
    }
    if (after >= outline.flank.size()) {
      throw std::invalid_argument("tooth_geo: the slit's mouth lies above the flank's tip");
    }
    mouth = geo.point(slit->mouth.x_m, slit->mouth.y_m, 0.5 * fine);
    tip = geo.point(slit->tip.x_m, slit->tip.y_m, 0.25 * fine);
    right.insert(right.begin() + static_cast<std::ptrdiff_t>(after), mouth);
  }
  // The root circle from the left flank's foot round the back of the ring to
  // the right flank's foot, in arcs of less than pi.
  const double rf = outline.root_radius_m;
  const int west = geo.point(-rf, 0.0, coarse);
  const int south = geo.point(0.0, -rf, coarse);
  const int east = geo.point(rf, 0.0, coarse);
  const double ri = outline.bore_radius_m;
  const std::array<int, 4> bore{geo.point(0.0, ri, coarse), geo.point(-ri, 0.0, coarse),
                                geo.point(0.0, -ri, coarse), geo.point(ri, 0.0, coarse)};
  std::vector<int> outer;
  for (std::size_t i = 0; i + 1 < right.size(); ++i)
    outer.push_back(geo.line(right[i], right[i + 1]));
  outer.push_back(geo.arc(right.back(), centre, left.back()));
  for (std::size_t i = left.size() - 1; i > 0; --i) outer.push_back(geo.line(left[i], left[i - 1]));
  outer.push_back(geo.arc(left.front(), centre, west));
  outer.push_back(geo.arc(west, centre, south));
  outer.push_back(geo.arc(south, centre, east));
  outer.push_back(geo.arc(east, centre, right.front()));
  std::vector<int> inner;
  for (std::size_t i = 0; i < bore.size(); ++i) {
    inner.push_back(geo.arc(bore[i], centre, bore[(i + 1) % bore.size()]));
  }
  geo.add("Curve Loop(1) = {" + GeoWriter::list(outer) + "};");
  geo.add("Curve Loop(2) = {" + GeoWriter::list(inner) + "};");
  geo.add("Plane Surface(1) = {1, 2};");
  std::vector<int> embedded;
  std::string groups;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const ToothContact& c = contacts[i];
    const std::string n = std::to_string(i + 1);
    const int on_centre = geo.point(0.0, c.y_m, fine);
    const int a = geo.point(-0.5 * c.x_m, c.y_m, fine);
    const int b = geo.point(0.5 * c.x_m, c.y_m, fine);
    embedded.insert(embedded.end(), {on_centre, a, b});
    groups += "Physical Point(\"P" + n + "\") = {" + std::to_string(loaded[i]) + "};\n";
    groups += "Physical Point(\"C" + n + "\") = {" + std::to_string(on_centre) + "};\n";
    groups += "Physical Point(\"A" + n + "\") = {" + std::to_string(a) + "};\n";
    groups += "Physical Point(\"B" + n + "\") = {" + std::to_string(b) + "};\n";
  }
  if (!embedded.empty()) geo.add("Point{" + GeoWriter::list(embedded) + "} In Surface{1};");
  if (chip_edge) {
    // Across the tooth between the last vertex and its mirror: the section a chip's edge lies on.
    const std::size_t v = outline.vertex_index.back();
    geo.add("Line{" + std::to_string(geo.line(left.at(v), right.at(v))) + "} In Surface{1};");
  }
  if (slit) {
    const int cut = geo.line(mouth, tip);
    geo.add("Line{" + std::to_string(cut) + "} In Surface{1};");
    groups += "Physical Curve(\"SLIT\") = {" + std::to_string(cut) + "};\n";
    groups += "Physical Point(\"TIP\") = {" + std::to_string(tip) + "};\n";
  }
  groups += "Physical Surface(\"BODY\") = {1};\n";
  groups += "Physical Curve(\"FIXED\") = {" + GeoWriter::list(inner) + "};\n";
  return groups;
}

}  // namespace

std::string tooth_geo(const ToothOutline& outline, const std::vector<ToothContact>& contacts,
                      const FeMeshSizes& sizes, const std::optional<FeSlit>& slit) {
  GeoWriter geo;
  const std::string groups = tooth_surface(geo, outline, contacts, sizes, slit);
  return geo.text() + groups;
}

std::string tooth_geo_3d(const ToothOutline& outline, const std::vector<ToothContact>& contacts,
                         const FeMeshSizes& sizes, double face_width_m, int layers, bool cut) {
  if (layers < 1) throw std::invalid_argument("tooth_geo_3d: at least one layer");
  GeoWriter geo;
  tooth_surface(geo, outline, contacts, sizes, std::nullopt, cut);
  geo.add("Mesh.SecondOrderIncomplete = 1;");
  geo.add("Mesh.SaveGroupsOfNodes = 0;");
  geo.add("extruded[] = Extrude {0, 0, " + number(face_width_m * kMm) + "} { Surface{1}; Layers{" +
          std::to_string(layers) + "}; Recombine; };");
  geo.add("Physical Volume(\"BODY\") = {extruded[1]};");
  return geo.text();
}

std::string cantilever_geo(double length_m, double depth_m, double element_m, double measured_x_m,
                           double crack_x_m, double edge_crack_m) {
  GeoWriter geo;
  const double half = 0.5 * depth_m;
  const int p1 = geo.point(0.0, -half, element_m);
  const int p2 = geo.point(length_m, -half, element_m);
  const int load = geo.point(length_m, 0.0, element_m);
  const int p3 = geo.point(length_m, half, element_m);
  const int p4 = geo.point(0.0, half, element_m);
  const int measured = geo.point(measured_x_m, 0.0, element_m);
  std::vector<int> loop{geo.line(p1, p2), geo.line(p2, load), geo.line(load, p3)};
  int mouth = 0;
  int tip = 0;
  if (edge_crack_m > 0.0) {
    // Elements along the slit a tenth of its length at most, a quarter of that at the tip.
    const double slit_element = std::min(0.5 * element_m, 0.1 * edge_crack_m);
    mouth = geo.point(crack_x_m, half, slit_element);
    tip = geo.point(crack_x_m, half - edge_crack_m, 0.25 * slit_element);
    loop.push_back(geo.line(p3, mouth));
    loop.push_back(geo.line(mouth, p4));
  } else {
    loop.push_back(geo.line(p3, p4));
  }
  const int clamp = geo.line(p4, p1);
  geo.add("Curve Loop(1) = {" + GeoWriter::list(loop) + ", " + std::to_string(clamp) + "};");
  geo.add("Plane Surface(1) = {1};");
  geo.add("Point{" + std::to_string(measured) + "} In Surface{1};");
  if (edge_crack_m > 0.0) {
    const int cut = geo.line(mouth, tip);
    geo.add("Line{" + std::to_string(cut) + "} In Surface{1};");
    geo.add("Physical Curve(\"SLIT\") = {" + std::to_string(cut) + "};");
    geo.add("Physical Point(\"TIP\") = {" + std::to_string(tip) + "};");
  }
  geo.add("Physical Surface(\"BODY\") = {1};");
  geo.add("Physical Curve(\"FIXED\") = {" + std::to_string(clamp) + "};");
  geo.add("Physical Point(\"LOAD\") = {" + std::to_string(load) + "};");
  geo.add("Physical Point(\"MEAS\") = {" + std::to_string(measured) + "};");
  return geo.text();
}

long FeMesh::node_of(const std::string& set) const {
  const auto found = node_sets.find(set);
  if (found == node_sets.end() || found->second.size() != 1) {
    throw std::runtime_error("the mesh has no single node in the set " + set +
                             " (gmsh's physical point)");
  }
  return found->second.front();
}

namespace {

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

std::string without_spaces(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c != ' ' && c != '\t' && c != '\r') out += c;
  }
  return out;
}

// The comma-separated numbers of one data line ("1, 2.5, 3," or "1 2 3").
std::vector<double> numbers_of(const std::string& line, std::size_t line_number) {
  std::vector<double> values;
  std::string field;
  auto flush = [&] {
    if (field.empty()) return;
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(field, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != field.size()) {
      throw std::runtime_error("mesh line " + std::to_string(line_number) + ": '" + field +
                               "' is not a number");
    }
    values.push_back(v);
    field.clear();
  };
  for (const char c : line) {
    if (c == ',' || c == ' ' || c == '\t' || c == '\r') {
      flush();
    } else {
      field += c;
    }
  }
  flush();
  return values;
}

}  // namespace

FeMesh read_gmsh_inp(const std::string& text) {
  FeMesh mesh;
  enum class Block { none, nodes, triangles, set } block = Block::none;
  std::string set_name;
  std::istringstream lines(text);
  std::string line;
  std::size_t number_of_line = 0;
  while (std::getline(lines, line)) {
    ++number_of_line;
    if (line.rfind("**", 0) == 0) continue;
    if (!line.empty() && line[0] == '*') {
      const std::string key = upper(without_spaces(line));
      block = Block::none;
      if (key.rfind("*NODE", 0) == 0 && key.rfind("*NODEPRINT", 0) != 0) {
        block = Block::nodes;
      } else if (key.rfind("*ELEMENT", 0) == 0 && key.find("TYPE=CPS6") != std::string::npos) {
        block = Block::triangles;
      } else if (key.rfind("*NSET", 0) == 0) {
        const auto at = key.find("NSET=", 5);
        if (at == std::string::npos) {
          throw std::runtime_error("mesh line " + std::to_string(number_of_line) +
                                   ": a node set without a name");
        }
        set_name = without_spaces(line).substr(at + 5);
        const auto comma = set_name.find(',');
        if (comma != std::string::npos) set_name.resize(comma);
        block = Block::set;
      }
      continue;
    }
    if (without_spaces(line).empty() || block == Block::none) continue;
    const std::vector<double> v = numbers_of(line, number_of_line);
    if (block == Block::nodes) {
      if (v.size() < 3) {
        throw std::runtime_error("mesh line " + std::to_string(number_of_line) +
                                 ": a node needs a number and two coordinates");
      }
      mesh.nodes_m[static_cast<long>(v[0])] = {v[1] / kMm, v[2] / kMm};
    } else if (block == Block::triangles) {
      if (v.size() != 7) {
        throw std::runtime_error("mesh line " + std::to_string(number_of_line) +
                                 ": a six-node triangle needs its number and six nodes");
      }
      mesh.triangles.push_back({static_cast<long>(v[1]), static_cast<long>(v[2]),
                                static_cast<long>(v[3]), static_cast<long>(v[4]),
                                static_cast<long>(v[5]), static_cast<long>(v[6])});
    } else {
      for (const double n : v) mesh.node_sets[set_name].push_back(static_cast<long>(n));
    }
  }
  if (mesh.triangles.empty()) {
    throw std::runtime_error("the mesh holds no six-node triangle (gmsh -order 2 -format inp)");
  }
  for (const auto& triangle : mesh.triangles) {
    for (const long n : triangle) {
      if (!mesh.nodes_m.count(n)) {
        throw std::runtime_error("the mesh's triangles name the node " + std::to_string(n) +
                                 ", which it does not define");
      }
    }
  }
  return mesh;
}

std::size_t open_slit(FeMesh& mesh, const FeSlit& slit, const std::string& slit_set) {
  const auto found = mesh.node_sets.find(slit_set);
  if (found == mesh.node_sets.end() || found->second.empty()) {
    throw std::runtime_error("the mesh has no node set " + slit_set + " (the slit's curve)");
  }
  const double ax = slit.tip.x_m - slit.mouth.x_m;
  const double ay = slit.tip.y_m - slit.mouth.y_m;
  const double length = std::hypot(ax, ay);
  long tip = 0;
  double nearest = 0.0;
  for (const long n : found->second) {
    const auto& p = mesh.nodes_m.at(n);
    const double d = std::hypot(p[0] - slit.tip.x_m, p[1] - slit.tip.y_m);
    if (tip == 0 || d < nearest) {
      tip = n;
      nearest = d;
    }
  }
  if (!(nearest <= 1e-3 * length)) {
    throw std::runtime_error("the slit's node set " + slit_set + " has no node at its tip");
  }
  long next = mesh.nodes_m.rbegin()->first;
  std::map<long, long> twin;
  for (const long n : found->second) {
    if (n == tip || twin.count(n)) continue;
    twin[n] = ++next;
    mesh.nodes_m[next] = mesh.nodes_m.at(n);
  }
  // A triangle with a node on the slit lies wholly on one side of it (the mesh runs along the
  // slit's line); its centroid says which.
  for (auto& triangle : mesh.triangles) {
    bool touches = false;
    for (const long n : triangle) touches = touches || twin.count(n) != 0;
    if (!touches) continue;
    double cx = 0.0;
    double cy = 0.0;
    for (int k = 0; k < 3; ++k) {
      cx += mesh.nodes_m.at(triangle[static_cast<std::size_t>(k)])[0] / 3.0;
      cy += mesh.nodes_m.at(triangle[static_cast<std::size_t>(k)])[1] / 3.0;
    }
    if (ax * (cy - slit.mouth.y_m) - ay * (cx - slit.mouth.x_m) > 0.0) {
      for (long& n : triangle) {
        const auto t = twin.find(n);
        if (t != twin.end()) n = t->second;
      }
    }
  }
  return twin.size();
}

FeMesh3 read_gmsh_inp_3d(const std::string& text) {
  FeMesh3 mesh;
  enum class Block { none, nodes, wedges } block = Block::none;
  std::istringstream lines(text);
  std::string line;
  std::size_t number_of_line = 0;
  std::vector<long> pending;  // an element's numbers over continuation lines
  while (std::getline(lines, line)) {
    ++number_of_line;
    if (line.rfind("**", 0) == 0) continue;
    if (!line.empty() && line[0] == '*') {
      const std::string key = upper(without_spaces(line));
      block = Block::none;
      if (key.rfind("*NODE", 0) == 0 && key.rfind("*NODEPRINT", 0) != 0) {
        block = Block::nodes;
      } else if (key.rfind("*ELEMENT", 0) == 0 && key.find("TYPE=C3D15") != std::string::npos) {
        block = Block::wedges;
      }
      continue;
    }
    if (without_spaces(line).empty() || block == Block::none) continue;
    const std::vector<double> v = numbers_of(line, number_of_line);
    if (block == Block::nodes) {
      if (v.size() < 4) {
        throw std::runtime_error("mesh line " + std::to_string(number_of_line) +
                                 ": a node needs a number and three coordinates");
      }
      mesh.nodes_m[static_cast<long>(v[0])] = {v[1] / kMm, v[2] / kMm, v[3] / kMm};
    } else {
      for (const double n : v) pending.push_back(static_cast<long>(n));
      // An element's line ends without a comma; gmsh breaks a long one after a comma.
      const std::string bare = without_spaces(line);
      if (bare.back() == ',') continue;
      if (pending.size() != 16) {
        throw std::runtime_error("mesh line " + std::to_string(number_of_line) +
                                 ": a fifteen-node wedge needs its number and fifteen nodes");
      }
      std::array<long, 15> wedge{};
      for (std::size_t k = 0; k < 15; ++k) wedge[k] = pending[k + 1];
      mesh.wedges.push_back(wedge);
      pending.clear();
    }
  }
  if (mesh.wedges.empty()) {
    throw std::runtime_error(
        "the mesh holds no fifteen-node wedge (gmsh -3 -format inp of a recombined extrusion)");
  }
  for (const auto& wedge : mesh.wedges) {
    for (const long n : wedge) {
      if (!mesh.nodes_m.count(n)) {
        throw std::runtime_error("the mesh's wedges name the node " + std::to_string(n) +
                                 ", which it does not define");
      }
    }
  }
  return mesh;
}

std::vector<long> nodes_on_z_line(const FeMesh3& mesh, double x_m, double y_m) {
  std::vector<std::pair<double, long>> found;
  for (const auto& [id, p] : mesh.nodes_m) {
    if (std::fabs(p[0] - x_m) < 1e-9 && std::fabs(p[1] - y_m) < 1e-9) found.push_back({p[2], id});
  }
  std::sort(found.begin(), found.end());
  std::vector<long> ids;
  for (const auto& f : found) ids.push_back(f.second);
  return ids;
}

std::vector<long> nodes_at_radius(const FeMesh3& mesh, double radius_m) {
  std::vector<long> ids;
  for (const auto& [id, p] : mesh.nodes_m) {
    if (std::fabs(std::hypot(p[0], p[1]) - radius_m) < 1e-9) ids.push_back(id);
  }
  return ids;
}

std::vector<double> line_load_weights(const std::vector<double>& z_m, double from_m, double to_m) {
  if (z_m.size() < 3 || z_m.size() % 2 == 0 || !(from_m < to_m)) {
    throw std::invalid_argument(
        "line_load_weights: an odd number of nodes (corner, mid-side, ..., corner) and from < to");
  }
  std::vector<double> w(z_m.size(), 0.0);
  bool from_found = false;
  bool to_found = false;
  for (std::size_t k = 0; k < z_m.size(); k += 2) {
    from_found = from_found || std::fabs(z_m[k] - from_m) < 1e-9;
    to_found = to_found || std::fabs(z_m[k] - to_m) < 1e-9;
  }
  if (!from_found || !to_found) {
    throw std::invalid_argument("line_load_weights: the loaded range ends between layer planes");
  }
  const double length = to_m - from_m;
  for (std::size_t k = 0; k + 2 < z_m.size(); k += 2) {
    const double middle = 0.5 * (z_m[k] + z_m[k + 2]);
    if (middle < from_m || middle > to_m) continue;
    const double h = z_m[k + 2] - z_m[k];
    w[k] += h / 6.0 / length;
    w[k + 1] += 4.0 * h / 6.0 / length;
    w[k + 2] += h / 6.0 / length;
  }
  return w;
}

namespace {

// The parts of a CalculiX input both the plane and the solid model write alike.

// Elements numbered from 1, a line each (CalculiX reads at most 16 entries a line: the number
// and 15 nodes fit).
template <std::size_t N>
void append_elements(std::string& text, const char* type,
                     const std::vector<std::array<long, N>>& elements) {
  text += std::string("*ELEMENT, TYPE=") + type + ", ELSET=BODY\n";
  long element = 0;
  for (const auto& e : elements) {
    text += std::to_string(++element);
    for (const long n : e) text += ", " + std::to_string(n);
    text += "\n";
  }
}

// A node set, eight nodes a line.
void append_node_set(std::string& text, const std::string& name, const std::vector<long>& nodes) {
  text += "*NSET, NSET=" + name + "\n";
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    text += std::to_string(nodes[i]) + ((i + 1) % 8 == 0 || i + 1 == nodes.size() ? ",\n" : ", ");
  }
}

// The linear elastic material, in MPa.
void append_material(std::string& text, const FeMaterial& material) {
  text += "*MATERIAL, NAME=GEAR\n*ELASTIC\n" + short_number(material.youngs_modulus_pa / 1e6) +
          ", " + short_number(material.poisson_ratio) + "\n";
}

// A point load's two in-plane components on its node.
void append_load(std::string& text, const FeLoad& load) {
  text += std::to_string(load.node) + ", 1, " + short_number(load.fx_n) + "\n";
  text += std::to_string(load.node) + ", 2, " + short_number(load.fy_n) + "\n";
}

}  // namespace

std::size_t cut_chip(FeMesh3& mesh, double cut_y_m, double width_m) {
  std::vector<std::array<long, 15>> kept;
  for (const auto& wedge : mesh.wedges) {
    std::array<double, 3> centroid{0.0, 0.0, 0.0};
    // The six corners (gmsh's C3D15 lists them first).
    for (std::size_t i = 0; i < 6; ++i) {
      const auto& p = mesh.nodes_m.at(wedge[i]);
      for (std::size_t k = 0; k < 3; ++k) centroid[k] += p[k] / 6.0;
    }
    if (!(centroid[1] > cut_y_m && centroid[2] < width_m)) kept.push_back(wedge);
  }
  const std::size_t removed = mesh.wedges.size() - kept.size();
  mesh.wedges = std::move(kept);
  std::set<long> used;
  for (const auto& wedge : mesh.wedges) used.insert(wedge.begin(), wedge.end());
  for (auto it = mesh.nodes_m.begin(); it != mesh.nodes_m.end();) {
    it = used.count(it->first) ? std::next(it) : mesh.nodes_m.erase(it);
  }
  return removed;
}

std::string calculix_input_3d(const FeMesh3& mesh, const FeMaterial& material,
                              const std::vector<long>& fixed,
                              const std::vector<std::vector<FeLoad>>& steps,
                              const std::vector<long>& printed_nodes) {
  if (fixed.empty()) throw std::runtime_error("the 3-D mesh has no node to hold");
  std::string text =
      "** Made by gearimpact fe-check: mm, N, MPa. Solid wedges.\n*NODE, NSET=NALL\n";
  for (const auto& [id, p] : mesh.nodes_m) {
    text += std::to_string(id) + ", " + short_number(p[0] * kMm) + ", " + short_number(p[1] * kMm) +
            ", " + short_number(p[2] * kMm) + "\n";
  }
  append_elements(text, "C3D15", mesh.wedges);
  append_node_set(text, "FIXED", fixed);
  append_node_set(text, "PRINTED", printed_nodes);
  append_material(text, material);
  text += "*SOLID SECTION, ELSET=BODY, MATERIAL=GEAR\n";
  text += "*BOUNDARY\nFIXED, 1, 3\n";
  for (const auto& loads : steps) {
    text += "*STEP\n*STATIC\n*CLOAD, OP=NEW\n";
    for (const FeLoad& load : loads) append_load(text, load);
    text += "*NODE PRINT, NSET=PRINTED\nU\n*END STEP\n";
  }
  return text;
}

std::string calculix_input(const FeMesh& mesh, const FeMaterial& material,
                           const std::string& fixed_set, const std::vector<FeLoad>& loads,
                           const std::vector<long>& printed_nodes) {
  const auto fixed = mesh.node_sets.find(fixed_set);
  if (fixed == mesh.node_sets.end() || fixed->second.empty()) {
    throw std::runtime_error("the mesh has no node set " + fixed_set + " to hold");
  }
  std::string text =
      "** Made by gearimpact fe-check: mm, N, MPa. Plane stress.\n*NODE, NSET=NALL\n";
  for (const auto& [id, xy] : mesh.nodes_m) {
    text += std::to_string(id) + ", " + short_number(xy[0] * kMm) + ", " +
            short_number(xy[1] * kMm) + "\n";
  }
  append_elements(text, "CPS6", mesh.triangles);
  append_node_set(text, "FIXED", fixed->second);
  append_node_set(text, "PRINTED", printed_nodes);
  append_material(text, material);
  text += "*SOLID SECTION, ELSET=BODY, MATERIAL=GEAR\n" + short_number(material.thickness_m * kMm) +
          "\n";
  text += "*BOUNDARY\nFIXED, 1, 2\n";
  for (const FeLoad& load : loads) {
    text += "*STEP\n*STATIC\n*CLOAD, OP=NEW\n";
    append_load(text, load);
    text += "*NODE PRINT, NSET=PRINTED\nU\n*END STEP\n";
  }
  return text;
}

std::vector<FeDisplacements> read_calculix_dat(const std::string& text, std::size_t steps,
                                               const std::vector<long>& printed_nodes) {
  std::vector<FeDisplacements> result;
  std::istringstream lines(text);
  std::string line;
  bool in_block = false;
  while (std::getline(lines, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      result.emplace_back();
      in_block = true;
      continue;
    }
    if (!in_block) continue;
    std::istringstream fields(line);
    long node = 0;
    double ux = 0.0;
    double uy = 0.0;
    if (fields >> node >> ux >> uy) {
      result.back()[node] = {ux / kMm, uy / kMm};
    } else if (!without_spaces(line).empty()) {
      in_block = false;
    }
  }
  if (result.size() != steps) {
    throw std::runtime_error("CalculiX's .dat holds " + std::to_string(result.size()) +
                             " steps of displacements, not " + std::to_string(steps));
  }
  for (std::size_t s = 0; s < steps; ++s) {
    for (const long n : printed_nodes) {
      if (!result[s].count(n)) {
        throw std::runtime_error("CalculiX's .dat lacks node " + std::to_string(n) + " in step " +
                                 std::to_string(s + 1));
      }
    }
  }
  return result;
}

FeToothReading tooth_reading(const ToothContact& contact, const std::array<double, 2>& u_centre,
                             const std::array<double, 2>& u_a, const std::array<double, 2>& u_b) {
  const double dx = -std::cos(contact.tau_rad);
  const double dy = -std::sin(contact.tau_rad);
  // A at -x_t / 2, B at +x_t / 2: the section's rigid rotation moves a point
  // at x by theta x along y.
  const double theta = (u_b[1] - u_a[1]) / contact.x_m;
  const double centre = dx * u_centre[0] + dy * u_centre[1];
  return {centre + theta * contact.x_m * dy, centre};
}

}  // namespace gearimpact
