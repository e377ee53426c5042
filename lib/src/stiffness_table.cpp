#include "gearimpact/stiffness_table.hpp"

#include <gsl/gsl_chebyshev.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

struct ChebDeleter {
  void operator()(gsl_cheb_series* series) const { gsl_cheb_free(series); }
};
using ChebPtr = std::unique_ptr<gsl_cheb_series, ChebDeleter>;

struct CompliancePart {
  const GearPair* pair;
  const StiffnessModel* model;
  bool bending;
};

double compliance_part(double x1, void* params) {
  const auto* part = static_cast<const CompliancePart*>(params);
  const GearPair& pair = *part->pair;
  const double lp = line_of_action_length(pair);
  const ToothCompliance c1 = tooth_compliance(tooth_of(pair, Gear::one), x1,
                                              pair.youngs_modulus_pa, pair.face_width_m, *part->model);
  const ToothCompliance c2 = tooth_compliance(tooth_of(pair, Gear::two), lp - x1,
                                              pair.youngs_modulus_pa, pair.face_width_m, *part->model);
  return part->bending ? c1.bending_m_per_n + c2.bending_m_per_n
                       : c1.axial_m_per_n + c2.axial_m_per_n;
}

ChebPtr fit(const CompliancePart& part, double a, double b, int order) {
  ChebPtr series(gsl_cheb_alloc(static_cast<std::size_t>(order)));
  gsl_function f{&compliance_part, const_cast<CompliancePart*>(&part)};
  gsl_cheb_init(series.get(), &f, a, b);
  return series;
}

ChebPtr derivative_of(const gsl_cheb_series* series, int order) {
  ChebPtr derivative(gsl_cheb_alloc(static_cast<std::size_t>(order)));
  gsl_cheb_calc_deriv(derivative.get(), series);
  return derivative;
}

}  // namespace

struct StiffnessTable::Series {
  ChebPtr bending;
  ChebPtr axial;
  ChebPtr bending_derivative;
  ChebPtr axial_derivative;
};

StiffnessTable::StiffnessTable(const GearPair& pair, const StiffnessModel& model,
                               StiffnessTableOptions options) {
  if (options.pieces < 1) {
    throw InputError("pieces", std::to_string(options.pieces), "an integer >= 1");
  }
  if (options.order < 2) {
    throw InputError("order", std::to_string(options.order), "an integer >= 2");
  }
  const ContactSegment segment = contact_segment(pair);
  start_ = segment.start_m;
  end_ = segment.end_m;
  piece_width_ = (end_ - start_) / options.pieces;
  hertz_compliance_ = 1.0 / hertz_stiffness(pair);
  const CompliancePart bending{&pair, &model, true};
  const CompliancePart axial{&pair, &model, false};
  for (int i = 0; i < options.pieces; ++i) {
    const double a = start_ + i * piece_width_;
    const double b = i + 1 == options.pieces ? end_ : a + piece_width_;
    auto series = std::make_unique<Series>();
    series->bending = fit(bending, a, b, options.order);
    series->axial = fit(axial, a, b, options.order);
    series->bending_derivative = derivative_of(series->bending.get(), options.order);
    series->axial_derivative = derivative_of(series->axial.get(), options.order);
    pieces_.push_back(std::move(series));
  }
}

StiffnessTable::StiffnessTable(StiffnessTable&&) noexcept = default;
StiffnessTable& StiffnessTable::operator=(StiffnessTable&&) noexcept = default;
StiffnessTable::~StiffnessTable() = default;

std::size_t StiffnessTable::piece_of(double x1_m) const {
  if (!(x1_m >= start_ && x1_m <= end_)) {
    throw InputError("contact position X1", x1_m,
                     "[" + format_number(start_) + ", " + format_number(end_) +
                         "] m, the contact segment the table covers");
  }
  const auto index = static_cast<std::size_t>((x1_m - start_) / piece_width_);
  return std::min(index, pieces_.size() - 1);
}

PairCompliance StiffnessTable::compliance(double x1_m) const {
  const Series& s = *pieces_[piece_of(x1_m)];
  return {hertz_compliance_, gsl_cheb_eval(s.bending.get(), x1_m),
          gsl_cheb_eval(s.axial.get(), x1_m)};
}

double StiffnessTable::stiffness(double x1_m) const {
  return 1.0 / compliance(x1_m).total_m_per_n();
}

double StiffnessTable::stiffness_derivative(double x1_m) const {
  const Series& s = *pieces_[piece_of(x1_m)];
  const double total = hertz_compliance_ + gsl_cheb_eval(s.bending.get(), x1_m) +
                       gsl_cheb_eval(s.axial.get(), x1_m);
  const double d_total = gsl_cheb_eval(s.bending_derivative.get(), x1_m) +
                         gsl_cheb_eval(s.axial_derivative.get(), x1_m);
  // d(1/c)/dx = -c'/c^2
  return -d_total / (total * total);
}

}  // namespace gearimpact
