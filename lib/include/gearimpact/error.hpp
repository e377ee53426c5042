// Errors the library reports. Each names what went wrong in the user's terms:
// an input field with its value and allowed range, or a quadrature that did not
// reach its requested tolerance.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

// One refusal of an input, as the user wrote it: the field (a key, a flag, the
// library's parameter), the value, what is allowed and, where one exists, a
// fix (a value that works and the key or flag that sets it). `where` is
// "file:line" (or "file") when the value came from a file, else empty.
struct Problem {
  std::string field;
  std::string value;
  std::string allowed;
  std::string fix;
  std::string where;
  // Empty for a value outside its range; else why it is refused (an unknown unit).
  std::string reason;
  // The line without `where`: "field = value is outside the allowed range:
  // allowed; fix: ...", or a reason in place of the range's words (an unknown
  // unit, an unknown key).
  std::string message;

  // "where: message", or the message alone.
  std::string line() const;
  // The same problem under another name and value (the flag a user typed for
  // a key), its message rebuilt.
  Problem renamed(std::string new_field, std::string new_value) const;
};

// "field = value is outside the allowed range: allowed[; fix: fix]".
Problem range_problem(std::string field, std::string value, std::string allowed,
                      std::string fix = {});
// "field = value: reason; allowed[; fix: fix]", for a value refused for what it
// is rather than where it lies (an unknown unit, a unit of another quantity).
Problem refused_problem(std::string field, std::string value, const std::string& reason,
                        std::string allowed, std::string fix = {});

// The text of several problems: one line each, the first line saying how many
// there are so that a program reading one line still reads a whole sentence.
std::string problems_text(const std::vector<Problem>& problems);

// Bad input: one value outside the range the model allows, or every problem
// of an input found at once (problems(), one line each in what()). field(),
// value(), allowed() and fix() are the first problem's, so that a caller can
// name the field as its user wrote it (a flag, a file's key).
class InputError : public Error {
 public:
  InputError(std::string field, const std::string& value, const std::string& allowed,
             const std::string& fix = {});
  InputError(std::string field, double value, const std::string& allowed);
  // At least one problem.
  explicit InputError(std::vector<Problem> problems);

  const std::string& field() const noexcept { return problems_.front().field; }
  const std::string& value() const noexcept { return problems_.front().value; }
  const std::string& allowed() const noexcept { return problems_.front().allowed; }
  const std::string& fix() const noexcept { return problems_.front().fix; }
  const std::vector<Problem>& problems() const noexcept { return problems_; }

 private:
  std::vector<Problem> problems_;
};

// The problems an input's checks find, gathered so that every one is reported
// at once: add() them, then throw_if_any().
class Problems {
 public:
  void add(Problem problem) { list_.push_back(std::move(problem)); }
  // Every problem of the error (one or several).
  void add(const InputError& error);
  // Runs `check`, adding the problems of an InputError it throws; true when
  // it threw none.
  template <typename Check>
  bool collect(Check check) {
    try {
      check();
      return true;
    } catch (const InputError& e) {
      add(e);
      return false;
    }
  }
  bool empty() const noexcept { return list_.empty(); }
  const std::vector<Problem>& list() const noexcept { return list_; }
  // Throws InputError with every problem, if there is one.
  void throw_if_any() const;

 private:
  std::vector<Problem> list_;
};

// A numerical integration that did not converge to the requested tolerance.
class QuadratureError : public Error {
 public:
  using Error::Error;
};

// A double in messages: the shortest text that reads back to it ("0.04", not
// "0.040000000000000001"), plain for decimal exponents in [-4, 15], else "1e-7".
// Data files keep their own fixed form (format_data_number of io/results.hpp).
std::string format_number(double value);

}  // namespace gearimpact
