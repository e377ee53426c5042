// Range checks shared by the steady-state sources (private to lib/src/steady): each throws
// InputError naming the field as the caller knows it, with the allowed range and unit.
#pragma once

#include <cmath>
#include <string>

#include "gearimpact/error.hpp"

namespace gearimpact::steady_checks {

inline void require_finite(const char* field, double value, const char* unit) {
  if (!std::isfinite(value)) {
    throw InputError(field, value, std::string("a finite value ") + unit);
  }
}

inline void require_finite_positive(const char* field, double value, const char* unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(field, value, std::string("a finite value > 0 ") + unit);
  }
}

inline void require_finite_non_negative(const char* field, double value, const char* unit) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError(field, value, std::string("a finite value >= 0 ") + unit);
  }
}

}  // namespace gearimpact::steady_checks
