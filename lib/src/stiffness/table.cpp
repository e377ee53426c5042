#include "gearimpact/stiffness/table.hpp"

#include <gsl/gsl_chebyshev.h>
#include <gsl/gsl_errno.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

struct ChebDeleter {
  void operator()(gsl_cheb_series* series) const { gsl_cheb_free(series); }
};
using ChebPtr = std::unique_ptr<gsl_cheb_series, ChebDeleter>;

// The compliances at the Chebyshev nodes of one piece. gsl_cheb_init is C: an
// exception thrown by the compliance function must not unwind through it, so
// the callback stores it and returns NaN, and fit() rethrows once GSL has
// returned. The fits of a piece use the same nodes, so the function runs once
// per node and the values are reused.
class NodeCompliances {
 public:
  explicit NodeCompliances(const ComplianceFunction& compliance) : compliance_(compliance) {}

  // A series of one term's compliance (`term`), or of Ke when `term` is empty.
  ChebPtr fit(std::optional<Term> term, double a, double b, int order) {
    ChebPtr series(gsl_cheb_alloc(static_cast<std::size_t>(order)));
    if (!series) throw std::bad_alloc();
    term_ = term;
    gsl_function f{&NodeCompliances::call, this};
    const int status = gsl_cheb_init(series.get(), &f, a, b);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    if (status != GSL_SUCCESS) {
      throw QuadratureError("gsl_cheb_init failed on [" + format_number(a) + ", " +
                            format_number(b) + "]: " + gsl_strerror(status));
    }
    return series;
  }

  // The node evaluated first (after a fit).
  const Compliances& first() const { return nodes_.front().compliance; }

  const Compliances& at(double x1_m) {
    for (const Node& node : nodes_) {
      if (node.x1_m == x1_m) return node.compliance;
    }
    nodes_.push_back({x1_m, compliance_(x1_m)});
    return nodes_.back().compliance;
  }

 private:
  struct Node {
    double x1_m;
    Compliances compliance;
  };

  static double call(double x1_m, void* params) {
    auto* self = static_cast<NodeCompliances*>(params);
    try {
      const Compliances& c = self->at(x1_m);
      // (29) for Ke.
      return self->term_ ? c.of(*self->term_) : 1.0 / c.total_m_per_n();
    } catch (...) {
      if (!self->failure_) self->failure_ = std::current_exception();
      return std::numeric_limits<double>::quiet_NaN();
    }
  }

  const ComplianceFunction& compliance_;
  std::optional<Term> term_;
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

StiffnessTableOptions StiffnessTable::checked(StiffnessTableOptions options, double start_m,
                                              double end_m) {
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
  if (!std::isfinite(start_m) || !std::isfinite(end_m) || !(start_m < end_m)) {
    throw InputError("table domain", format_number(start_m) + " to " + format_number(end_m),
                     "finite start < end, m");
  }
  return options;
}

void StiffnessTable::fit_part(double a, double b, const ComplianceFunction& compliance,
                              bool every_term) {
  const double piece_width = (b - a) / pieces_;
  ChebPtr derivative(gsl_cheb_alloc(static_cast<std::size_t>(order_)));
  if (!derivative) throw std::bad_alloc();
  for (int i = 0; i < pieces_; ++i) {
    const double p = a + i * piece_width;
    const double q = i + 1 == pieces_ ? b : a + (i + 1) * piece_width;
    NodeCompliances nodes(compliance);
    for (const TermInfo& t : kTerms) {
      if (!t.per_tooth && !every_term) continue;
      const ChebPtr series = nodes.fit(t.term, p, q, order_);
      append_polynomial(term_series_[index_of(t.term)], series.get(), stride_);
    }
    const ChebPtr stiffness = nodes.fit(std::nullopt, p, q, order_);
    append_polynomial(stiffness_, stiffness.get(), stride_);
    gsl_cheb_calc_deriv(derivative.get(), stiffness.get());
    append_polynomial(stiffness_derivative_, derivative.get(), stride_);
    if (i == 0 && !every_term) {
      const Compliances& first = nodes.first();
      for (const TermInfo& t : kTerms) {
        if (!t.per_tooth) constant_terms_.of(t.term) = first.of(t.term);
      }
    }
  }
}

void StiffnessTable::zero_part() {
  const std::size_t size = static_cast<std::size_t>(pieces_) * stride_;
  for (std::vector<double>* series : {&stiffness_, &stiffness_derivative_}) {
    series->insert(series->end(), size, 0.0);
  }
  for (const TermInfo& t : kTerms) {
    std::vector<double>& series = term_series_[index_of(t.term)];
    series.insert(series.end(), size, 0.0);
  }
}

void StiffnessTable::set_grid(double start_m, double end_m, StiffnessTableOptions options) {
  options = checked(options, start_m, end_m);
  start_ = start_m;
  end_ = end_m;
  pieces_ = options.pieces;
  order_ = options.order;
  stride_ = order_ <= 7 ? 8 : 16;
  pieces_per_m_ = 1.0 / ((end_ - start_) / pieces_);
}

void StiffnessTable::drop_zero_terms() {
  // A term that is 0 at every node (one the model does not have, or one
  // switched off) keeps no series: compliance() then reads 0 without
  // evaluating it.
  for (std::vector<double>& series : term_series_) {
    if (std::all_of(series.begin(), series.end(), [](double a) { return a == 0.0; })) {
      series.clear();
    }
  }
}

StiffnessTable::StiffnessTable(double start_m, double end_m, const ComplianceFunction& compliance,
                               StiffnessTableOptions options) {
  set_grid(start_m, end_m, options);
  fit_part(start_, end_, compliance, false);
  drop_zero_terms();
}

StiffnessTable::StiffnessTable(double start_m, double end_m, const ComplianceFunction& compliance,
                               std::vector<double> breaks_m, StiffnessTableOptions options) {
  set_grid(start_m, end_m, options);
  breaks_m.erase(std::remove_if(breaks_m.begin(), breaks_m.end(),
                                [&](double x) { return !(x > start_m && x < end_m); }),
                 breaks_m.end());
  std::sort(breaks_m.begin(), breaks_m.end());
  breaks_m.erase(std::unique(breaks_m.begin(), breaks_m.end()), breaks_m.end());
  std::vector<double> ends{start_m};
  ends.insert(ends.end(), breaks_m.begin(), breaks_m.end());
  ends.push_back(end_m);
  for (std::size_t i = 1; i < ends.size(); ++i) {
    const bool contact = compliance(0.5 * (ends[i - 1] + ends[i])).total_m_per_n() != 0.0;
    parts_.push_back({ends[i - 1], pieces_ / (ends[i] - ends[i - 1]),
                      static_cast<int>(i - 1) * pieces_, contact});
    if (contact) {
      fit_part(ends[i - 1], ends[i], compliance, true);
    } else {
      zero_part();
    }
  }
  drop_zero_terms();
}

std::vector<double> StiffnessTable::breaks_m() const {
  std::vector<double> breaks;
  for (std::size_t i = 1; i < parts_.size(); ++i) breaks.push_back(parts_[i].start_m);
  return breaks;
}

StiffnessTable::StiffnessTable(const GearPair& pair, const StiffnessModel& model,
                               StiffnessTableOptions options) {
  const ContactSegment segment = contact_segment(pair);
  set_grid(segment.start_m, segment.end_m, options);
  fit_part(
      start_, end_,
      [&](double x1_m) {
        const MeshStiffness k = mesh_stiffness(pair, x1_m, model);
        node_teeth_.push_back({x1_m, k.tooth1, k.tooth2});
        return k.included;
      },
      false);
  drop_zero_terms();
  pair_ = pair;
  model_ = model;
}

bool StiffnessTable::built_for(const GearPair& pair, const StiffnessModel& model) const {
  return pair_ && model_ && *pair_ == pair && *model_ == model;
}

void StiffnessTable::throw_outside(double x1_m) const {
  throw InputError("contact position X1", x1_m,
                   "[" + format_number(start_) + ", " + format_number(end_) +
                       "] m, the contact segment the table covers");
}

Compliances StiffnessTable::compliance(double x1_m) const {
  return compliance_at(locate(x1_m));
}

Compliances StiffnessTable::compliance_in_part(double x1_m, int part) const {
  return compliance_at(locate_in_part(x1_m, part));
}

int StiffnessTable::part_of(double x1_m) const {
  int i = part_count() - 1;
  while (i > 0 && x1_m < parts_[static_cast<std::size_t>(i)].start_m) --i;
  return i;
}

Compliances StiffnessTable::compliance_at(const Local& at) const {
  Compliances c = constant_terms_;
  for (const TermInfo& t : kTerms) {
    const std::vector<double>& series = term_series_[index_of(t.term)];
    if (!series.empty()) c.of(t.term) = polynomial(&series[at.offset], at.t);
  }
  return c;
}

}  // namespace gearimpact
