#include "gearimpact/error.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

namespace gearimpact {

std::string format_number(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  // The shortest digits that read back to `value`; plain notation for decimal exponents in
  // [-4, 15], as shortest_decimal writes case files, else d.ddde-7 without the sign or zeros
  // of the exponent that C adds.
  std::array<char, 64> buffer{};
  char* const first = buffer.data();
  char* const last = first + buffer.size();
  const std::string_view scientific(
      first, static_cast<std::size_t>(
                 std::to_chars(first, last, value, std::chars_format::scientific).ptr - first));
  const std::size_t e = scientific.find('e');
  int exponent = 0;
  std::string_view exponent_text = scientific.substr(e + 1);
  if (!exponent_text.empty() && exponent_text.front() == '+') exponent_text.remove_prefix(1);
  std::from_chars(exponent_text.data(), exponent_text.data() + exponent_text.size(), exponent);
  if (exponent >= -4 && exponent <= 15) {
    const auto fixed = std::to_chars(first, last, value, std::chars_format::fixed);
    return std::string(first, fixed.ptr);
  }
  return std::string(scientific.substr(0, e)) + "e" + std::to_string(exponent);
}

std::string Problem::line() const {
  return where.empty() ? message : where + ": " + message;
}

Problem Problem::renamed(std::string new_field, std::string new_value) const {
  Problem p =
      reason.empty()
          ? range_problem(std::move(new_field), std::move(new_value), allowed, fix)
          : refused_problem(std::move(new_field), std::move(new_value), reason, allowed, fix);
  p.where = where;
  return p;
}

Problem range_problem(std::string field, std::string value, std::string allowed, std::string fix) {
  Problem p{std::move(field), std::move(value), std::move(allowed), std::move(fix), {}, {}, {}};
  p.message = p.field + " = " + p.value + " is outside the allowed range: " + p.allowed;
  if (!p.fix.empty()) p.message += "; fix: " + p.fix;
  return p;
}

Problem refused_problem(std::string field, std::string value, const std::string& reason,
                        std::string allowed, std::string fix) {
  Problem p{std::move(field), std::move(value), std::move(allowed), std::move(fix), {}, reason, {}};
  p.message = p.field + " = " + p.value + ": " + reason + "; " + p.allowed;
  if (!p.fix.empty()) p.message += "; fix: " + p.fix;
  return p;
}

std::string problems_text(const std::vector<Problem>& problems) {
  if (problems.empty()) return {};
  std::string text = problems.front().line();
  if (problems.size() == 1) return text;
  text += " (1 of " + std::to_string(problems.size()) + " problems, one per line)";
  for (std::size_t i = 1; i < problems.size(); ++i) text += "\n" + problems[i].line();
  return text;
}

InputError::InputError(std::string field, const std::string& value, const std::string& allowed,
                       const std::string& fix)
    : InputError(std::vector<Problem>{range_problem(std::move(field), value, allowed, fix)}) {}

InputError::InputError(std::string field, double value, const std::string& allowed)
    : InputError(std::move(field), format_number(value), allowed) {}

InputError::InputError(std::vector<Problem> problems)
    : Error(problems_text(problems)), problems_(std::move(problems)) {
  if (problems_.empty()) problems_.push_back(range_problem("input", "", "no problem given"));
}

void Problems::add(const InputError& error) {
  for (const Problem& p : error.problems()) list_.push_back(p);
}

void Problems::throw_if_any() const {
  if (!list_.empty()) throw InputError(list_);
}

}  // namespace gearimpact
