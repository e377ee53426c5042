#include "gearimpact/stiffness/table.hpp"

#include <gsl/gsl_chebyshev.h>
#include <gsl/gsl_errno.h>

#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <utility>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

struct ChebDeleter {
  void operator()(gsl_cheb_series* series) const { gsl_cheb_free(series); }
};
using ChebPtr = std::unique_ptr<gsl_cheb_series, ChebDeleter>;

enum class Part { bending, axial, stiffness };

// The compliances of both teeth at the Chebyshev nodes. gsl_cheb_init is C:
// an exception thrown by the quadrature must not unwind through it, so the
// callback stores it and returns NaN, and fit() rethrows once GSL has
// returned. The three fits of a piece use the same nodes, so the quadrature
// runs once per node and the values are reused.
class NodeCompliances {
 public:
  NodeCompliances(const GearPair& pair, const StiffnessModel& model)
      : pair_(pair),
        model_(model),
        lp_(line_of_action_length(pair)),
        hertz_compliance_(
            included_compliance(model, 1.0 / hertz_stiffness(pair), 0.0, 0.0).hertz_m_per_n) {}

  ChebPtr fit(Part part, double a, double b, int order) {
    ChebPtr series(gsl_cheb_alloc(static_cast<std::size_t>(order)));
    if (!series) throw std::bad_alloc();
    part_ = part;
    gsl_function f{&NodeCompliances::call, this};
    const int status = gsl_cheb_init(series.get(), &f, a, b);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    if (status != GSL_SUCCESS) {
      throw QuadratureError("gsl_cheb_init failed on [" + format_number(a) + ", " +
                            format_number(b) + "]: " + gsl_strerror(status));
    }
    return series;
  }

 private:
  struct Node {
    double x1_m;
    double bending_m_per_n;
    double axial_m_per_n;
  };

  static double call(double x1_m, void* params) {
    auto* self = static_cast<NodeCompliances*>(params);
    try {
      const Node& node = self->at(x1_m);
      switch (self->part_) {
        case Part::bending:
          return node.bending_m_per_n;
        case Part::axial:
          return node.axial_m_per_n;
        case Part::stiffness:
          // (29)
          return 1.0 / (self->hertz_compliance_ + node.bending_m_per_n + node.axial_m_per_n);
      }
      return std::numeric_limits<double>::quiet_NaN();
    } catch (...) {
      if (!self->failure_) self->failure_ = std::current_exception();
      return std::numeric_limits<double>::quiet_NaN();
    }
  }

  const Node& at(double x1_m) {
    for (const Node& node : nodes_) {
      if (node.x1_m == x1_m) return node;
    }
    const double e = pair_.youngs_modulus_pa;
    const double width = pair_.face_width_m;
    const ToothCompliance c1 = tooth_compliance(tooth_of(pair_, Gear::one), x1_m, e, width, model_);
    // (25),(26): gear 2 sees the contact at lp - X1 from C2.
    const ToothCompliance c2 =
        tooth_compliance(tooth_of(pair_, Gear::two), lp_ - x1_m, e, width, model_);
    // Terms switched off in the model enter (29) as zero compliance.
    const PairCompliance included = included_compliance(
        model_, 0.0, c1.bending_m_per_n + c2.bending_m_per_n, c1.axial_m_per_n + c2.axial_m_per_n);
    nodes_.push_back({x1_m, included.bending_m_per_n, included.axial_m_per_n});
    return nodes_.back();
  }

  const GearPair& pair_;
  const StiffnessModel& model_;
  double lp_;
  double hertz_compliance_;
  Part part_ = Part::bending;
  std::vector<Node> nodes_;
  std::exception_ptr failure_;
};

// Appends the series sum' c_k T_k(t) (GSL's convention: c_0 counts half) as
// the coefficients of 1, t, t^2, ... padded with zeros to `stride`. On
// [-1, 1] the change of basis amplifies rounding by at most the sum of the
// monomial coefficients of T_k (a few hundred at order 7) times c_k, and
// these c_k fall fast: the table's measured worst error in Ke stays at the
// reference's own level, near 1e-14 (benchmarks/README.md).
void append_polynomial(std::vector<double>& out, const gsl_cheb_series* series,
                       std::size_t stride) {
  const std::size_t terms = series->order + 1;
  std::vector<double> result(stride, 0.0);
  // T_{k-1}, T_k as monomial coefficients; T_{k+1} = 2 t T_k - T_{k-1}.
  std::vector<double> previous(terms, 0.0);
  std::vector<double> current(terms, 0.0);
  previous[0] = 1.0;
  if (terms > 1) current[1] = 1.0;
  result[0] = 0.5 * series->c[0];
  for (std::size_t k = 1; k < terms; ++k) {
    for (std::size_t j = 0; j <= k; ++j) result[j] += series->c[k] * current[j];
    std::vector<double> next(terms, 0.0);
    for (std::size_t j = 0; j + 1 < terms; ++j) next[j + 1] = 2.0 * current[j];
    for (std::size_t j = 0; j < terms; ++j) next[j] -= previous[j];
    previous = std::move(current);
    current = std::move(next);
  }
  out.insert(out.end(), result.begin(), result.end());
}

}  // namespace

StiffnessTable::StiffnessTable(const GearPair& pair, const StiffnessModel& model,
                               StiffnessTableOptions options) {
  constexpr int max_pieces = 4096;
  constexpr int max_order = 15;
  if (options.pieces < 1 || options.pieces > max_pieces) {
    throw InputError("pieces", std::to_string(options.pieces),
                     "an integer in [1, " + std::to_string(max_pieces) + "]");
  }
  if (options.order < 2 || options.order > max_order) {
    throw InputError("order", std::to_string(options.order),
                     "an integer in [2, " + std::to_string(max_order) + "]");
  }
  const ContactSegment segment = contact_segment(pair);
  start_ = segment.start_m;
  end_ = segment.end_m;
  pieces_ = options.pieces;
  order_ = options.order;
  stride_ = order_ <= 7 ? 8 : 16;
  const double piece_width = (end_ - start_) / pieces_;
  pieces_per_m_ = 1.0 / piece_width;
  validate(model);
  hertz_compliance_ =
      included_compliance(model, 1.0 / hertz_stiffness(pair), 0.0, 0.0).hertz_m_per_n;

  ChebPtr derivative(gsl_cheb_alloc(static_cast<std::size_t>(order_)));
  if (!derivative) throw std::bad_alloc();
  for (int i = 0; i < pieces_; ++i) {
    const double a = start_ + i * piece_width;
    const double b = i + 1 == pieces_ ? end_ : start_ + (i + 1) * piece_width;
    NodeCompliances nodes(pair, model);
    const ChebPtr bending = nodes.fit(Part::bending, a, b, order_);
    const ChebPtr axial = nodes.fit(Part::axial, a, b, order_);
    const ChebPtr stiffness = nodes.fit(Part::stiffness, a, b, order_);
    append_polynomial(bending_, bending.get(), stride_);
    append_polynomial(axial_, axial.get(), stride_);
    append_polynomial(stiffness_, stiffness.get(), stride_);
    gsl_cheb_calc_deriv(derivative.get(), stiffness.get());
    append_polynomial(stiffness_derivative_, derivative.get(), stride_);
  }
}

void StiffnessTable::throw_outside(double x1_m) const {
  throw InputError("contact position X1", x1_m,
                   "[" + format_number(start_) + ", " + format_number(end_) +
                       "] m, the contact segment the table covers");
}

PairCompliance StiffnessTable::compliance(double x1_m) const {
  const Local at = locate(x1_m);
  return {hertz_compliance_, polynomial(&bending_[at.offset], at.t),
          polynomial(&axial_[at.offset], at.t)};
}

}  // namespace gearimpact
