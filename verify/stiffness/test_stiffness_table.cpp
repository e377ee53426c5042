// The precomputed stiffness against the quadrature it is built from, computed
// independently here at every position (mesh_stiffness, GSL QAG), for the
// paper's pair and for a pair of other proportions.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "gearimpact/case/schema.hpp"
#include "gearimpact/error.hpp"
#include "gearimpact/geometry/gear_pair.hpp"
#include "gearimpact/stiffness/mesh_stiffness.hpp"
#include "gearimpact/stiffness/table.hpp"

using namespace gearimpact;

namespace {

GearPair other_pair() {
  GearPair pair = paper_gear_pair();
  pair.teeth1 = 17;
  pair.teeth2 = 43;
  pair.pressure_angle_rad = 25.0 * std::numbers::pi / 180.0;
  return pair;
}

// Evenly spread over the segment, both ends exactly included.
std::vector<double> positions(const ContactSegment& segment, int n) {
  std::vector<double> xs;
  for (int i = 0; i < n; ++i) {
    xs.push_back(segment.start_m + (segment.end_m - segment.start_m) * i / (n - 1));
  }
  xs.front() = segment.start_m;
  xs.back() = segment.end_m;
  return xs;
}

double relative(double value, double expected) {
  return std::abs(value / expected - 1.0);
}

// Requested of every direct quadrature below: the adaptive reference of the
// benchmarks. Two independent rules (GSL QAG and CQUAD) at this tolerance
// agree to 3e-15 in Ke, so the comparisons measure the table, not the
// reference.
StiffnessModel reference_model() {
  StiffnessModel model;
  model.relative_tolerance = 1e-13;
  return model;
}

}  // namespace

TEST_CASE("table Ke and compliances match direct quadrature over the whole segment") {
  for (const GearPair& pair : {paper_gear_pair(), other_pair()}) {
    validate(pair);
    const StiffnessTable table(pair);
    const ContactSegment segment = contact_segment(pair);
    CHECK(table.domain_start_m() == segment.start_m);
    CHECK(table.domain_end_m() == segment.end_m);
    // 1001 points put several in every one of the 64 pieces, and both ends.
    double worst_ke = 0.0;
    double worst_compliance = 0.0;
    for (double x : positions(segment, 1001)) {
      const MeshStiffness k = mesh_stiffness(pair, x, reference_model());
      worst_ke = std::max(worst_ke, relative(table.stiffness(x), k.ke));
      const Compliances c = table.compliance(x);
      CHECK(c.of(Term::hertz) ==
            doctest::Approx(1.0 / k.stiffness(Term::hertz)).scale(0).epsilon(1e-15));
      worst_compliance =
          std::max({worst_compliance,
                    relative(c.of(Term::bending), 1.0 / k.stiffness(Term::bending, Gear::one) +
                                                      1.0 / k.stiffness(Term::bending, Gear::two)),
                    relative(c.of(Term::axial), 1.0 / k.stiffness(Term::axial, Gear::one) +
                                                    1.0 / k.stiffness(Term::axial, Gear::two))});
    }
    // 1e-12: the accuracy the simulation is promised, a hundred
    // times the measured worst error (near 1e-14, benchmarks/README.md), so
    // that only a real loss of accuracy fails here.
    CHECK(worst_ke <= 1e-12);
    CHECK(worst_compliance <= 1e-12);
  }
}

TEST_CASE("table dKe/dX1 matches a five-point difference of the quadrature") {
  for (const GearPair& pair : {paper_gear_pair(), other_pair()}) {
    const StiffnessTable table(pair);
    const ContactSegment segment = contact_segment(pair);
    const double length = segment.end_m - segment.start_m;
    const auto ke = [&](double x) { return mesh_stiffness(pair, x, reference_model()).ke; };
    // The fourth-order difference errs by h^4 Ke^(5)/30 plus the quadrature's
    // own noise, ~1e-15 Ke per value, times 3/(2h). With h = 3e-4 of the
    // segment the noise term is 5e-12 of Ke/L, and the truncation, which a
    // look at steps 1e-3 and 3e-4 showed falling as h^4 (the three-point
    // difference's h^2 term was 1e-7 of Ke/L at this step, too coarse), is
    // below 1e-11 of it.
    const double h = 3e-4 * length;
    // Ke/L is the scale of the slope; 1e-9 of it is a hundred times the error
    // terms above and still far below any fault of the series. The slope
    // changes sign along the segment, so a relative bound per point would be
    // meaningless near its zeros.
    double scale = 0.0;
    double worst = 0.0;
    for (double x : positions(segment, 41)) {
      const double difference =
          (8.0 * (ke(x + h) - ke(x - h)) - (ke(x + 2.0 * h) - ke(x - 2.0 * h))) / (12.0 * h);
      scale = std::max(scale, ke(x) / length);
      worst = std::max(worst, std::abs(table.stiffness_derivative(x) - difference));
      // One evaluation returns exactly what the two separate ones do.
      const StiffnessAndDerivative both = table.stiffness_and_derivative(x);
      CHECK(both.stiffness_n_per_m == table.stiffness(x));
      CHECK(both.derivative_n_per_m2 == table.stiffness_derivative(x));
    }
    CHECK(worst <= 1e-9 * scale);
  }
}

TEST_CASE("positions outside the contact segment are an InputError") {
  const StiffnessTable table(paper_gear_pair());
  const double below = std::nextafter(table.domain_start_m(), 0.0);
  const double above = std::nextafter(table.domain_end_m(), 1.0);
  for (double x : {below, above, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    CHECK_THROWS_AS(table.stiffness(x), InputError);
    CHECK_THROWS_AS(table.stiffness_derivative(x), InputError);
    CHECK_THROWS_AS(table.stiffness_and_derivative(x), InputError);
    CHECK_THROWS_AS(table.compliance(x), InputError);
  }
  CHECK_NOTHROW(table.stiffness(table.domain_start_m()));
  CHECK_NOTHROW(table.stiffness(table.domain_end_m()));
}

TEST_CASE("bad options are an InputError, a failing quadrature a QuadratureError") {
  const GearPair pair = paper_gear_pair();
  CHECK_THROWS_AS(StiffnessTable(pair, {}, {0, 7}), InputError);
  CHECK_THROWS_AS(StiffnessTable(pair, {}, {64, 1}), InputError);
  CHECK_THROWS_AS(StiffnessTable(pair, {}, {64, 16}), InputError);
  // GSL QAG refuses a relative tolerance below 50 machine epsilons (1.1e-14):
  // the error arises inside gsl_cheb_init's callback and must reach the
  // caller intact. Below 1e-14 the model itself is refused where it enters
  // (the schema's stiffness_tolerance row, which validate checks).
  StiffnessModel unreachable;
  unreachable.relative_tolerance = 1e-14;
  CHECK_THROWS_AS(StiffnessTable(pair, unreachable), QuadratureError);
  unreachable.relative_tolerance = 1e-20;
  CHECK_THROWS_AS(validate(unreachable), InputError);
}

TEST_CASE("orders above 7 (sixteen-coefficient evaluation) are as accurate") {
  const GearPair pair = paper_gear_pair();
  const StiffnessTable table(pair, {}, {16, 12});
  double worst = 0.0;
  for (double x : positions(contact_segment(pair), 201)) {
    worst = std::max(worst,
                     relative(table.stiffness(x), mesh_stiffness(pair, x, reference_model()).ke));
  }
  // The same bound and reason as the default table's.
  CHECK(worst <= 1e-12);
}

TEST_CASE("a term of (29) switched off is left out of the table as out of mesh_stiffness") {
  const GearPair pair = paper_gear_pair();
  StiffnessModel no_axial;
  no_axial.terms.set(Term::axial, false);
  const StiffnessTable table(pair, no_axial);
  const ContactSegment segment = contact_segment(pair);
  for (int i = 0; i <= 50; ++i) {
    const double x = segment.start_m + (segment.end_m - segment.start_m) * i / 50.0;
    CAPTURE(x);
    CHECK(table.compliance(x).of(Term::axial) == 0.0);
    // The table's own accuracy bound of the tests above.
    const double direct = mesh_stiffness(pair, x, no_axial).ke;
    CHECK(std::abs(table.stiffness(x) - direct) <= 1e-12 * direct);
  }
}

TEST_CASE("a table cut at its breaks fits a compliance that jumps there, Hertz included") {
  // Hertz steps from 1e-9 to 2e-9 m/N at X = 0.3 and back at 0.6 (a contact
  // line halved inside a band); bending is a smooth cubic.
  const auto compliance = [](double x) {
    Compliances c;
    c.of(Term::hertz) = x >= 0.3 && x <= 0.6 ? 2e-9 : 1e-9;
    c.of(Term::bending) = 1e-9 * (1.0 + x * x * x);
    return c;
  };
  const StiffnessTable table(0.0, 1.0, compliance, std::vector<double>{0.6, 0.3, 1.5}, {4, 7});
  // Breaks outside the domain are left out, the others sorted.
  CHECK(table.breaks_m() == std::vector<double>{0.3, 0.6});
  for (double x : {0.0, 0.1, 0.2999, 0.3, 0.3001, 0.45, 0.5999, 0.6001, 0.8, 1.0}) {
    CAPTURE(x);
    // At a break the part above it: [0.3, 0.6) in the band, 0.6 above it.
    const double hertz = x >= 0.3 && x < 0.6 ? 2e-9 : 1e-9;
    const double expected = 1.0 / (hertz + 1e-9 * (1.0 + x * x * x));
    // Ke is analytic on each part: order-7 pieces 0.075 wide or less fit it
    // far below 1e-9; a piece across a step would miss by a third of Ke.
    const double scale = std::max(std::fabs(table.stiffness(x)), std::fabs(expected));
    CHECK(std::fabs(table.stiffness(x) - expected) < 1e-9 * scale);
    CHECK(std::fabs(table.compliance(x).of(Term::hertz) - hertz) < 1e-14 * hertz);
  }
  // A table without breaks has none.
  CHECK(StiffnessTable(0.0, 1.0, compliance).breaks_m().empty());
}
