// An independent check of the tooth compliances by finite elements: the
// texts that gmsh (the mesher) and CalculiX (the solver) read, the readers of
// what they write, and the reading of a compliance from the displacements
// (docs/verification.md, "Finite-element check"). The programs themselves
// are run by the `gearimpact fe-check` command; everything here is text in,
// text out, so that it is tested without them.
//
// Units in the files: mm, N and MPa (the solver has none of its own); every
// function here takes and returns SI and converts at the file's edge.
// The model is two-dimensional, plane stress with the thickness of the face
// width: the potential-energy terms use E (not E / (1 - nu^2)) with sections
// b wide, which is plane stress.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "gearimpact/geometry/rack_generation.hpp"
#include "gearimpact/geometry/tooth_outline.hpp"

namespace gearimpact {

// Element sizes: along the tooth (flanks, tip, the measured points) and on the
// rim's far side and the bore; gmsh grades between them.
struct FeMeshSizes {
  double tooth_m;
  double body_m;
};

// The gmsh geometry (.geo) of the tooth with its whole rim, a full ring from
// the root circle to the bore with this one tooth: the flanks as the
// polyline of `outline` (the other flank mirrored), the tip and root circles
// and the bore as arcs; second-order triangles. Physical groups, which gmsh
// writes as node sets: BODY (the surface), FIXED (the bore), and for the
// contact i = 1, 2, ... at outline.vertex_index[i-1]: Pi, the flank's node
// where the load acts; Ci, the centre-line point (0, y_t) of the section
// through the load; Ai and Bi, the points (-x_t/2, y_t) and (x_t/2, y_t) of
// that section. `contacts` are the loads in the same order as the outline's
// vertices.
//
// A slit (a crack of zero width, docs/verification.md, "The cracked tooth")
// is a straight line from `mouth` on the loaded flank (x > 0; made a vertex
// of the flank's polyline) to `tip` inside the body, embedded in the surface
// so that the mesh's edges run along it: the physical curve SLIT and the
// physical point TIP (its tip's node). open_slit then separates its faces.
struct FeSlit {
  OutlinePoint mouth;
  OutlinePoint tip;
};
std::string tooth_geo(const ToothOutline& outline, const std::vector<ToothContact>& contacts,
                      const FeMeshSizes& sizes, const std::optional<FeSlit>& slit = std::nullopt);

// The tooth's root crack as a slit: from the flank point at the crack's start
// (half thickness h_c, radius r_s) into the tooth at the angle nu to the
// centre line and towards the root, q long: mouth (h_c, sqrt(r_s^2 - h_c^2)),
// tip = mouth + q (-sin nu, -cos nu). The stiffness model's reading keeps only
// the tip's distance h_c - q sin nu from the centre line; the slit draws the
// crack whole.
FeSlit root_crack_slit(double start_radius_m, double start_half_thickness_m, double depth_m,
                       double angle_rad);

// A rectangular cantilever for the check of the pipeline against beam theory:
// length L along x from the clamped end x = 0 (the physical curve FIXED),
// depth h from y = -h/2 to h/2; the node LOAD at the free end's centre
// (L, 0) and the node MEAS at (x_measured, 0) on the neutral axis, away from
// the load's local field. Element size `element_m` everywhere.
// With `edge_crack_m` > 0, a slit from the top edge (y = h/2, the tension side
// under a load along -y) at x = `crack_x_m` straight down, that deep, its
// tip's elements a quarter of `element_m`: Tada's edge-cracked beam.
std::string cantilever_geo(double length_m, double depth_m, double element_m, double measured_x_m,
                           double crack_x_m = 0.0, double edge_crack_m = 0.0);

// The mesh gmsh writes in Abaqus form (-format inp), reduced to what the
// solver needs: the nodes, the six-node triangles and the node sets.
struct FeMesh {
  std::map<long, std::array<double, 2>> nodes_m;
  std::vector<std::array<long, 6>> triangles;
  std::map<std::string, std::vector<long>> node_sets;
  // The one node of a set made from a physical point; throws std::runtime_error
  // naming the set if it is absent or holds more than one node.
  long node_of(const std::string& set) const;
};
// Throws std::runtime_error naming the line for text that is not gmsh's inp
// output or holds no six-node triangle.
FeMesh read_gmsh_inp(const std::string& text);

// Separates the two faces of a slit meshed as an embedded line: every node of
// the node set `slit_set` but the tip's (the node nearest `slit.tip`) is
// duplicated, and the triangles on the left of the line from mouth to tip
// (seen along it) take the duplicates, so that the faces move apart freely; the
// tip stays one node. The duplicates are numbered after the largest node;
// node sets keep the original nodes. Returns how many nodes were duplicated.
// Throws std::runtime_error when the set is absent, or its nearest node to the
// tip lies farther than a thousandth of the slit's length from it.
std::size_t open_slit(FeMesh& mesh, const FeSlit& slit, const std::string& slit_set);

struct FeMaterial {
  double youngs_modulus_pa;
  double poisson_ratio;
  double thickness_m;  // the plane-stress elements' thickness: the face width
};

// One load case: a force on one node (N, in the model's x and y).
struct FeLoad {
  long node;
  double fx_n;
  double fy_n;
};

// The CalculiX input (.inp): the mesh as plane-stress elements (CPS6) of the
// material's thickness, the set `fixed_set` held in x and y, one linear
// static step per load (each replacing the last, OP=NEW), and the
// displacements of `printed_nodes` printed to the .dat file at every step.
std::string calculix_input(const FeMesh& mesh, const FeMaterial& material,
                           const std::string& fixed_set, const std::vector<FeLoad>& loads,
                           const std::vector<long>& printed_nodes);

// The printed displacements of each step (m, x and y), in the steps' order,
// from CalculiX's .dat. Throws std::runtime_error unless it holds `steps`
// steps with every node of `printed_nodes`.
using FeDisplacements = std::map<long, std::array<double, 2>>;
std::vector<FeDisplacements> read_calculix_dat(const std::string& text, std::size_t steps,
                                               const std::vector<long>& printed_nodes);

// The tooth's compliance at one contact from the displacements of the
// section through the load (docs/verification.md, "Finite-element check"):
// the load's direction d = (-cos tau, -sin tau) per unit force; the section's
// translation u_C at its centre-line point C and its rotation
// theta = (u_y(B) - u_y(A)) / (x_B - x_A), carried rigidly to the load point:
//   delta = d . u_C + theta x_t d_y.
// This is what the beam of the potential-energy method moves along the load
// (Castigliano: the section at y_t is rigid there), and it leaves out the
// contact's local indentation, which the Hertzian term carries (Weber's
// division of the tooth's deflection, the contact's share measured to the
// centre line). `centre_line_m_per_n` is d . u_C alone.
struct FeToothReading {
  double compliance_m_per_n;
  double centre_line_m_per_n;
};
FeToothReading tooth_reading(const ToothContact& contact, const std::array<double, 2>& u_centre,
                             const std::array<double, 2>& u_a, const std::array<double, 2>& u_b);

// The three-dimensional tooth (docs/verification.md, "The spall in 3-D"):
// tooth_geo's surface (no slit) extruded over the face width, z from 0 to b,
// in `layers` equal layers of fifteen-node wedges (gmsh's structured
// extrusion with Recombine and incomplete second order; CalculiX C3D15). The
// extrusion copies the surface's mesh to every layer plane, so the flank
// vertex of each contact and its section's points C, A, B become lines of
// nodes along z (corner nodes on the planes, mid-side nodes between), found
// by their coordinates (nodes_on_z_line); the bore's nodes are the FIXED ones.
// With `cut`, the outline's last vertex (one past the contacts') and its
// mirror are joined by a line across the tooth that the mesh follows: the
// section of a chip's edge (cut_chip).
std::string tooth_geo_3d(const ToothOutline& outline, const std::vector<ToothContact>& contacts,
                         const FeMeshSizes& sizes, double face_width_m, int layers,
                         bool cut = false);

struct FeMesh3 {
  std::map<long, std::array<double, 3>> nodes_m;
  std::vector<std::array<long, 15>> wedges;
};
// Throws std::runtime_error naming the line for text that is not gmsh's inp
// output or holds no fifteen-node wedge (C3D15).
FeMesh3 read_gmsh_inp_3d(const std::string& text);

// A chip (docs/verification.md, "The chip in 3-D"): removes the wedges whose
// corners' centroid lies above y = cut_y_m and at z below width_m (the tooth
// above the chip's section over b_k from the face z = 0), and the nodes no
// wedge keeps. Returns the count removed.
std::size_t cut_chip(FeMesh3& mesh, double cut_y_m, double width_m);

// The nodes at (x, y) (within 1e-9 m), sorted by z; the nodes at radius r
// from the z axis (within 1e-9 m).
std::vector<long> nodes_on_z_line(const FeMesh3& mesh, double x_m, double y_m);
std::vector<long> nodes_at_radius(const FeMesh3& mesh, double radius_m);

// The consistent nodal forces of a unit force spread evenly over z in
// [from, to] along a line of quadratic element edges: `z_m` the line's nodes
// sorted, corner and mid-side alternating (corner first and last); each edge
// of length h inside [from, to] gives h/6, 4h/6, h/6 of its share h / (to -
// from). Throws std::invalid_argument unless from and to are corner nodes'
// z (within 1e-9 m) with from < to, and the count is odd.
std::vector<double> line_load_weights(const std::vector<double>& z_m, double from_m, double to_m);

// The CalculiX input of the 3-D mesh: C3D15 of the material (its thickness
// unused), the nodes `fixed` held in x, y and z, one linear static step per
// entry of `steps` (each a set of nodal forces in x and y, replacing the
// last), the displacements of `printed_nodes` printed at every step.
std::string calculix_input_3d(const FeMesh3& mesh, const FeMaterial& material,
                              const std::vector<long>& fixed,
                              const std::vector<std::vector<FeLoad>>& steps,
                              const std::vector<long>& printed_nodes);

}  // namespace gearimpact
