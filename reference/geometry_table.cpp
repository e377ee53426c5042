#include "geometry_table.hpp"

#include "gearimpact/constants.hpp"
#include "gearimpact/error.hpp"
#include "reproduce.hpp"

namespace gearimpact::cli {

void GeometryTable::both(const std::string& what, double one, double two, const std::string& unit) {
  csv += what + ",pinion," + format_number(one) + "," + unit + "\n";
  csv += what + ",wheel," + format_number(two) + "," + unit + "\n";
  md += "| " + what + " | " + shown(one, unit) + " | " + shown(two, unit) + " | " +
        shown_unit(unit) + " |\n";
}

void GeometryTable::pair(const std::string& what, double value, const std::string& unit) {
  pair_csv_only(what, value, unit);
  md += "| " + what + " | " + shown(value, unit) + " | | " + shown_unit(unit) + " |\n";
}

void GeometryTable::pair_csv_only(const std::string& what, double value, const std::string& unit) {
  csv += what + ",pair," + format_number(value) + "," + unit + "\n";
}

std::string GeometryTable::shown(double value, const std::string& unit) const {
  if (unit == "m") return number(value * 1e3, 6);
  if (unit == "rad" && angles_in_degrees) return number(value * 180.0 / pi, 6);
  return number(value, 6);
}

std::string GeometryTable::shown_unit(const std::string& unit) const {
  if (unit == "m") return "mm";
  if (unit == "rad" && angles_in_degrees) return "deg";
  return unit;
}

}  // namespace gearimpact::cli
