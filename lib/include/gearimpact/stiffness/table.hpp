// The mesh stiffness of one pair as a precomputed function of the contact
// position, for use in the time integration where adaptive quadrature per call
// would dominate the cost. Built once from any position -> compliances
// function (by default the adaptive quadrature of mesh_stiffness.hpp): on each
// of a number of equal pieces of the domain, GSL's gsl_cheb_init fits
// Chebyshev series of Ke itself and of every per-tooth term's compliance, and
// gsl_cheb_calc_deriv differentiates the Ke series. Each series is then rewritten as a polynomial
// in the piece's local variable t in [-1, 1] and evaluated inline by Estrin's scheme, whose
// dependency chain is log2 of the degree deep instead of the degree (as in
// Clenshaw's recurrence or Horner's rule): the table sits in the force
// evaluation of every integration step, where the next step waits for it.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/terms.hpp"

namespace gearimpact {

// The default order 7 is the highest that fits the eight-coefficient
// evaluation; 64 pieces of it keep the worst relative error in Ke, over 10,000
// positions against GSL QAG at 1e-13, near 1e-14 for the paper's pair
// (benchmarks/README.md). The verify suite bounds it at 1e-12.
struct StiffnessTableOptions {
  int pieces = 64;  // equal subintervals of the contact segment, 1 to 4096
  int order = 7;    // Chebyshev order on each (order + 1 coefficients), 2 to 15
};

// Ke and dKe/dX1 at one position, from one look-up of the piece.
struct StiffnessAndDerivative {
  double stiffness_n_per_m;
  double derivative_n_per_m2;
};

// The two teeth's terms (MeshStiffness::tooth1, tooth2) at one node of a
// table.
struct NodeTeeth {
  double x1_m;
  Compliances tooth1;
  Compliances tooth2;
};

// The compliances of a pair in contact at X1, terms switched off at 0.
using ComplianceFunction = std::function<Compliances(double x1_m)>;

class StiffnessTable {
 public:
  // Fits `compliance` over [start_m, end_m]. Terms that are not per tooth (the
  // Hertzian one) are constant along the line of action and kept as the value
  // at the first node. Throws InputError for options out of range and rethrows
  // what `compliance` throws (QuadratureError when a node cannot be integrated).
  StiffnessTable(double start_m, double end_m, const ComplianceFunction& compliance,
                 StiffnessTableOptions options = {});
  // The same for a function that may jump or kink at `breaks_m` (a spall's or
  // a chip's edges, surface_faults.hpp): the domain is cut there, and each
  // part gets options.pieces pieces of its own, so that no piece straddles a
  // break. Every term is fitted as a series, the Hertzian one too (a fault
  // shortens the contact line in part of the domain). At a break the table
  // gives the part above it. Breaks outside (start_m, end_m) are ignored. A
  // part where `compliance` gives every term 0 at its middle is one where the
  // pair has no contact (a spall or a chip across the whole face): it is not
  // fitted, and Ke, dKe/dX1 and every compliance are 0 there
  // (part_in_contact false).
  StiffnessTable(double start_m, double end_m, const ComplianceFunction& compliance,
                 std::vector<double> breaks_m, StiffnessTableOptions options = {});
  // mesh_stiffness(pair, X1, model).included over the contact segment
  // [X_start, X_end]; the table remembers the pair and model it was built for.
  explicit StiffnessTable(const GearPair& pair, const StiffnessModel& model = {},
                          StiffnessTableOptions options = {});

  // The pair constructor's nodes with the teeth's terms there, so that the
  // tables of a faulted tooth (MeshTables) need not compute the healthy teeth
  // beside it again; empty for a table built from a function.
  const std::vector<NodeTeeth>& node_teeth() const { return node_teeth_; }
  // Whether the table was built by the second constructor for this pair and
  // model; a table built from a function says false.
  bool built_for(const GearPair& pair, const StiffnessModel& model) const;
  // Whether it was built by the pair constructor, so that built_for can tell.
  bool knows_origin() const { return pair_.has_value(); }

  double domain_start_m() const { return start_; }
  double domain_end_m() const { return end_; }
  // Where the domain is cut (ascending, inside it), empty for one part.
  std::vector<double> breaks_m() const;
  int pieces() const { return pieces_; }
  int order() const { return order_; }

  // The parts between the breaks: part_count() of them (1 without breaks),
  // part i over [part_start_m(i), part_end_m(i)]. part_of(x1) is the part x1
  // falls in (at a break, the one above it, as the look-ups below read it).
  int part_count() const { return parts_.empty() ? 1 : static_cast<int>(parts_.size()); }
  int part_of(double x1_m) const;
  // Inline: a mesh reads them for every loaded pair at every stage.
  double part_start_m(int part) const {
    return parts_.empty() ? start_ : parts_.at(static_cast<std::size_t>(part)).start_m;
  }
  double part_end_m(int part) const {
    return part + 1 < part_count() ? parts_[static_cast<std::size_t>(part + 1)].start_m : end_;
  }
  // Whether the pair has contact over the part (above); a table without
  // breaks has it everywhere.
  bool part_in_contact(int part) const {
    return parts_.empty() || parts_[static_cast<std::size_t>(part)].contact;
  }
  // Ke, dKe/dX1 and the compliances from part `part`'s own series, at x1 in
  // [part_start_m(part), part_end_m(part)]: at a break, from the side asked
  // for, so that a run can stay on one side of a jump up to its event.
  // Throws InputError for x1 outside the part.
  StiffnessAndDerivative stiffness_and_derivative_in_part(double x1_m, int part) const {
    const Local at = locate_in_part(x1_m, part);
    return {polynomial(&stiffness_[at.offset], at.t),
            polynomial(&stiffness_derivative_[at.offset], at.t)};
  }
  Compliances compliance_in_part(double x1_m, int part) const;

  // Each throws InputError for x1 outside the domain.
  Compliances compliance(double x1_m) const;
  // Ke, N/m, from its own series, fitted to (29) 1/Ke = total compliance.
  double stiffness(double x1_m) const {
    const Local at = locate(x1_m);
    return polynomial(&stiffness_[at.offset], at.t);
  }
  // dKe/dX1, N/m^2, from the differentiated series of Ke.
  double stiffness_derivative(double x1_m) const {
    const Local at = locate(x1_m);
    return polynomial(&stiffness_derivative_[at.offset], at.t);
  }
  StiffnessAndDerivative stiffness_and_derivative(double x1_m) const {
    const Local at = locate(x1_m);
    return {polynomial(&stiffness_[at.offset], at.t),
            polynomial(&stiffness_derivative_[at.offset], at.t)};
  }

 private:
  // Where x1 falls: the first coefficient of its piece, and x1 mapped to
  // [-1, 1] on that piece.
  struct Local {
    std::size_t offset;
    double t;
  };
  Local locate(double x1_m) const {
    if (!(x1_m >= start_ && x1_m <= end_)) {
      throw_outside(x1_m);
    }
    if (!parts_.empty()) return locate_in_parts(x1_m);
    const double u = (x1_m - start_) * pieces_per_m_;
    const int piece = std::min(static_cast<int>(u), pieces_ - 1);
    return {static_cast<std::size_t>(piece) * stride_, 2.0 * (u - piece) - 1.0};
  }
  Local locate_in_parts(double x1_m) const {
    std::size_t i = parts_.size() - 1;
    while (i > 0 && x1_m < parts_[i].start_m) --i;
    const Part& p = parts_[i];
    const double u = (x1_m - p.start_m) * p.pieces_per_m;
    const int piece = std::min(static_cast<int>(u), pieces_ - 1);
    return {static_cast<std::size_t>(p.first_piece + piece) * stride_, 2.0 * (u - piece) - 1.0};
  }
  Local locate_in_part(double x1_m, int part) const {
    if (parts_.empty()) return locate(x1_m);
    if (!(x1_m >= part_start_m(part) && x1_m <= part_end_m(part))) throw_outside(x1_m);
    const Part& p = parts_[static_cast<std::size_t>(part)];
    const double u = (x1_m - p.start_m) * p.pieces_per_m;
    const int piece = std::min(static_cast<int>(u), pieces_ - 1);
    return {static_cast<std::size_t>(p.first_piece + piece) * stride_, 2.0 * (u - piece) - 1.0};
  }
  Compliances compliance_at(const Local& at) const;
  // Fits the pieces of [a, b] (count of them) after those already fitted.
  void fit_part(double a, double b, const ComplianceFunction& compliance, bool every_term);
  // Zero series for the pieces of a part without contact.
  void zero_part();
  // The domain and the grid of the options (checked against the domain).
  void set_grid(double start_m, double end_m, StiffnessTableOptions options);
  // Clears the series of every term that is 0 at every node.
  void drop_zero_terms();
  static StiffnessTableOptions checked(StiffnessTableOptions options, double start_m, double end_m);
  // Estrin's scheme for a[0] + a[1] t + ... + a[7] t^7.
  static double estrin8(const double* a, double t) {
    const double t2 = t * t;
    const double t4 = t2 * t2;
    const double p0 = a[0] + a[1] * t;
    const double p1 = a[2] + a[3] * t;
    const double p2 = a[4] + a[5] * t;
    const double p3 = a[6] + a[7] * t;
    return (p0 + t2 * p1) + t4 * (p2 + t2 * p3);
  }
  // The polynomial of one piece: 8 coefficients up to order 7, else 16, the
  // unused ones zero.
  double polynomial(const double* a, double t) const {
    if (stride_ == 8) return estrin8(a, t);
    const double t2 = t * t;
    const double t4 = t2 * t2;
    return estrin8(a, t) + (t4 * t4) * estrin8(a + 8, t);
  }
  [[noreturn]] void throw_outside(double x1_m) const;

  double start_ = 0.0;
  double end_ = 0.0;
  double pieces_per_m_ = 0.0;
  int pieces_ = 0;
  int order_ = 0;
  std::size_t stride_ = 0;  // 8 or 16 coefficients per piece
  // The parts between breaks, each of pieces_ equal pieces; empty for a
  // table without breaks (then pieces_ equal pieces span the domain).
  struct Part {
    double start_m;
    double pieces_per_m;
    int first_piece;
    bool contact;
  };
  std::vector<Part> parts_;
  // Polynomial coefficients in t, stride_ per piece, piece after piece: one
  // series per per-tooth term (empty for the others, unless the table has
  // breaks, and for a term 0 at every node), of Ke and of dKe/dX1.
  std::array<std::vector<double>, kTermCount> term_series_;
  Compliances constant_terms_;  // the terms that are not per tooth (0 with breaks)
  std::vector<double> stiffness_;
  std::vector<double> stiffness_derivative_;
  std::vector<NodeTeeth> node_teeth_;
  // What the pair constructor was given.
  std::optional<GearPair> pair_;
  std::optional<StiffnessModel> model_;
};

}  // namespace gearimpact
