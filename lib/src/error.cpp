#include "gearimpact/error.hpp"

#include <cstdio>

namespace gearimpact {

std::string format_number(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

InputError::InputError(std::string field, const std::string& value, const std::string& allowed)
    : Error(field + " = " + value + " is outside the allowed range: " + allowed),
      field_(std::move(field)),
      value_(value),
      allowed_(allowed) {}

InputError::InputError(std::string field, double value, const std::string& allowed)
    : InputError(std::move(field), format_number(value), allowed) {}

}  // namespace gearimpact
