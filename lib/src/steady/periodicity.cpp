#include "gearimpact/steady/periodicity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact {

namespace {

void validate(const std::vector<Eigen::VectorXd>& samples, const Eigen::VectorXd& scale,
              const PeriodicitySettings& settings) {
  if (!std::isfinite(settings.tolerance) || settings.tolerance <= 0.0) {
    throw InputError("tolerance", settings.tolerance, "a finite value > 0 (fraction of scale)");
  }
  if (settings.max_period < 1) {
    throw InputError("max_period", static_cast<double>(settings.max_period), ">= 1");
  }
  const auto max_period = static_cast<std::size_t>(settings.max_period);
  if (settings.window < 2 * max_period) {
    throw InputError("window", static_cast<double>(settings.window),
                     ">= 2 max_period = " + std::to_string(2 * max_period));
  }
  if (settings.trend_window < settings.window) {
    throw InputError("trend_window", static_cast<double>(settings.trend_window),
                     ">= window = " + std::to_string(settings.window));
  }
  if (scale.size() == 0) throw InputError("scale", "an empty vector", "one value per component");
  for (Eigen::Index i = 0; i < scale.size(); ++i) {
    if (!std::isfinite(scale[i]) || scale[i] <= 0.0) {
      throw InputError("scale[" + std::to_string(i) + "]", scale[i], "a finite value > 0");
    }
  }
  for (std::size_t n = 0; n < samples.size(); ++n) {
    const std::string field = "poincare sample " + std::to_string(n);
    if (samples[n].size() != scale.size()) {
      throw InputError(field, std::to_string(samples[n].size()) + " components",
                       std::to_string(scale.size()) + " components, as many as scale has");
    }
    if (!samples[n].allFinite()) {
      throw InputError(field, "a non-finite component", "finite components");
    }
  }
}

double scaled_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                       const Eigen::VectorXd& scale) {
  return ((a - b).cwiseAbs().array() / scale.array()).maxCoeff();
}

struct Trend {
  double slope = 0.0;           // of log(residual) per period
  double standard_error = 0.0;  // of that slope
};

// Least-squares line through (n, y_n), n = 0, 1, ...
Trend fit_line(const std::vector<double>& y) {
  const auto m = static_cast<double>(y.size());
  const double x_mean = 0.5 * (m - 1.0);
  double y_mean = 0.0;
  for (double v : y) y_mean += v;
  y_mean /= m;
  double sxx = 0.0;
  double sxy = 0.0;
  for (std::size_t n = 0; n < y.size(); ++n) {
    const double dx = static_cast<double>(n) - x_mean;
    sxx += dx * dx;
    sxy += dx * (y[n] - y_mean);
  }
  Trend t;
  t.slope = sxy / sxx;
  double ss = 0.0;
  for (std::size_t n = 0; n < y.size(); ++n) {
    const double e = y[n] - y_mean - t.slope * (static_cast<double>(n) - x_mean);
    ss += e * e;
  }
  // Two points fit any line exactly: no evidence of a trend.
  t.standard_error =
      y.size() > 2 ? std::sqrt(ss / (m - 2.0) / sxx) : std::numeric_limits<double>::infinity();
  return t;
}

}  // namespace

PeriodicityResult classify_poincare_samples(const std::vector<Eigen::VectorXd>& samples,
                                            const Eigen::VectorXd& scale,
                                            const PeriodicitySettings& settings) {
  validate(samples, scale, settings);
  const std::size_t count = samples.size();
  const auto max_period = static_cast<std::size_t>(settings.max_period);
  const std::size_t window = settings.window;

  PeriodicityResult result;
  const std::size_t kept = std::min(window, count);
  result.window_samples.assign(samples.end() - static_cast<std::ptrdiff_t>(kept), samples.end());

  if (count < window + max_period) {
    result.verdict = PeriodicityVerdict::not_converged;
    result.residual = std::numeric_limits<double>::infinity();
    result.explanation = std::to_string(count) + " samples, fewer than window + max_period = " +
                         std::to_string(window + max_period) + " needed to judge a period";
    return result;
  }

  // residuals[p - 1][j]: scaled distance between sample n and sample n - p for the last
  // `span` samples n, oldest first; the window is their last `window`.
  const std::size_t span = std::min(settings.trend_window, count - max_period);
  std::vector<std::vector<double>> residuals(max_period, std::vector<double>(span));
  std::vector<double> window_max(max_period, 0.0);
  for (std::size_t p = 1; p <= max_period; ++p) {
    for (std::size_t j = 0; j < span; ++j) {
      const std::size_t n = count - span + j;
      residuals[p - 1][j] = scaled_distance(samples[n], samples[n - p], scale);
      if (j + window >= span) window_max[p - 1] = std::max(window_max[p - 1], residuals[p - 1][j]);
    }
  }
  // The trend of log(residual) of period p over the span. Zero residuals (points that coincide
  // by chance) are floored far below the tolerance so that the logarithm is finite.
  const double floor = 1e-6 * settings.tolerance;
  const auto trend_of = [&](std::size_t p) {
    std::vector<double> log_residual(span);
    for (std::size_t j = 0; j < span; ++j) {
      log_residual[j] = std::log(std::max(residuals[p - 1][j], floor));
    }
    return fit_line(log_residual);
  };
  // Rising steadily: by at least 10 % (1/0.9) over the span with a slope above 5 standard errors;
  // falling steadily the same way down.
  const auto rises = [&](const Trend& trend) {
    return trend.slope * static_cast<double>(span - 1) > std::log(1.0 / 0.9) &&
           trend.slope > 5.0 * trend.standard_error;
  };
  const auto falls = [&](const Trend& trend) {
    return trend.slope * static_cast<double>(span - 1) < std::log(0.9) &&
           trend.slope < -5.0 * trend.standard_error;
  };
  // Not converged: the period-p residual still changes by exp(slope) a period.
  const auto still_moving = [&](std::size_t p, const Trend& trend, const std::string& how,
                                const std::string& why) {
    result.verdict = PeriodicityVerdict::not_converged;
    result.closest_period = static_cast<int>(p);
    result.residual = window_max[p - 1];
    result.contraction_per_period = std::exp(trend.slope);
    result.explanation = "not converged: the period-" + std::to_string(p) + " residual " +
                         format_number(result.residual) + how + " by a factor " +
                         format_number(result.contraction_per_period) +
                         " per period over the last " + std::to_string(span) + " samples" + why;
    return result;
  };
  const std::string tolerance = format_number(settings.tolerance);
  const std::string leaving = " (leaving an unstable orbit)";
  for (std::size_t p = 1; p <= max_period; ++p) {
    if (window_max[p - 1] <= settings.tolerance) {
      // Below the tolerance but growing steadily is a perturbation still small that leaves an
      // unstable orbit (a multiplier near -1.03 makes samples two periods apart agree long
      // before they part): not periodic yet. Residuals below 1e-3 of the tolerance are left
      // alone, since rounding there grows with the angles of a long run.
      const Trend trend = trend_of(p);
      if (window_max[p - 1] > 1e-3 * settings.tolerance && rises(trend)) {
        return still_moving(p, trend, " is within the tolerance " + tolerance + " but grows",
                            leaving);
      }
      result.verdict = PeriodicityVerdict::periodic;
      result.period = static_cast<int>(p);
      result.closest_period = result.period;
      result.residual = window_max[p - 1];
      result.explanation = "period " + std::to_string(p) + ": every one of the last " +
                           std::to_string(window) + " samples is within " +
                           format_number(result.residual) + " <= tolerance " + tolerance +
                           " (scaled) of the sample " + std::to_string(p) + " periods before it";
      return result;
    }
  }
  // The multiples of a period repeat about as well as the period itself, so the closest period
  // is the smallest whose residual is within a factor 2 of the smallest residual.
  const double smallest = *std::min_element(window_max.begin(), window_max.end());
  for (std::size_t p = max_period; p >= 1; --p) {
    if (window_max[p - 1] <= 2.0 * smallest) {
      result.closest_period = static_cast<int>(p);
      result.residual = window_max[p - 1];
    }
  }

  // No period repeats within the tolerance: still settling, or aperiodic?
  for (std::size_t p = 1; p <= max_period; ++p) {
    const Trend trend = trend_of(p);
    // Rising is not settled either: the samples are leaving an unstable orbit (a multiplier
    // outside the unit circle), towards whatever attracts them.
    if (rises(trend)) return still_moving(p, trend, " grows", leaving);
    if (falls(trend))
      return still_moving(p, trend, " > tolerance " + tolerance + " still shrinks", "");
  }
  result.verdict = PeriodicityVerdict::aperiodic;
  result.explanation = "aperiodic: no period up to " + std::to_string(max_period) +
                       " repeats within tolerance " + tolerance + " (closest: period " +
                       std::to_string(result.closest_period) + ", residual " +
                       format_number(result.residual) +
                       ") and no residual is still shrinking or growing over the last " +
                       std::to_string(span) + " samples";
  return result;
}

}  // namespace gearimpact
