// Checks of one number that the library's sources share (internal, not
// installed): each throws InputError naming the field as the caller knows it,
// with the allowed range and, after it, `unit` (a unit or a note, may be empty).
#pragma once

#include <cmath>
#include <string>
#include <string_view>

#include "gearimpact/error.hpp"

namespace gearimpact::checks {

namespace detail {
inline std::string allowed(std::string_view range, std::string_view unit) {
  std::string text(range);
  if (!unit.empty()) text += " " + std::string(unit);
  return text;
}
}  // namespace detail

inline void require_finite(std::string_view field, double value, std::string_view unit) {
  if (!std::isfinite(value)) {
    throw InputError(std::string(field), value, detail::allowed("a finite value", unit));
  }
}

inline void require_finite_positive(std::string_view field, double value, std::string_view unit) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InputError(std::string(field), value, detail::allowed("a finite value > 0", unit));
  }
}

inline void require_finite_non_negative(std::string_view field, double value,
                                        std::string_view unit) {
  if (!std::isfinite(value) || value < 0.0) {
    throw InputError(std::string(field), value, detail::allowed("a finite value >= 0", unit));
  }
}

}  // namespace gearimpact::checks
