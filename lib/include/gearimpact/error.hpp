// Errors the library reports. Each names what went wrong in the user's terms:
// an input field with its value and allowed range, or a quadrature that did not
// reach its requested tolerance.
#pragma once

#include <stdexcept>
#include <string>

namespace gearimpact {

// The one base of every exception the library throws, so that a caller can
// catch the library's failures apart from its own: a bad input (InputError,
// CaseFileError), a quadrature that misses its tolerance (QuadratureError), a
// run that cannot go on (SimulationError), a Newton iteration or continuation
// that does not converge (ShootingError).
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A value outside the range the model allows. `field` is the name the user
// wrote (or the library's parameter name), `allowed` the range in words.
class InputError : public Error {
 public:
  InputError(std::string field, const std::string& value, const std::string& allowed);
  InputError(std::string field, double value, const std::string& allowed);

  const std::string& field() const noexcept { return field_; }
  // The value and the allowed range as they appear in the message, so that a
  // caller can name the field as its user wrote it (a flag, a file's key).
  const std::string& value() const noexcept { return value_; }
  const std::string& allowed() const noexcept { return allowed_; }

 private:
  std::string field_;
  std::string value_;
  std::string allowed_;
};

// A numerical integration that did not converge to the requested tolerance.
class QuadratureError : public Error {
 public:
  using Error::Error;
};

// Formats a double with enough digits to round-trip, for messages.
std::string format_number(double value);

}  // namespace gearimpact
