// The geometry table of `gearimpact report` (a spur pair's and a helical pair's): geometry.csv in
// SI units, a row per gear or for the pair, and REPORT.md's Markdown table of the same rows with
// lengths in mm (and, for a helical pair, angles in degrees).
#pragma once

#include <string>

namespace gearimpact::cli {

struct GeometryTable {
  // Angles shown in degrees in the Markdown table (the CSV keeps radians).
  bool angles_in_degrees = false;
  std::string csv = "quantity,gear,value,unit\n";
  std::string md = "| quantity | pinion | wheel | unit |\n|---|---|---|---|\n";

  // A quantity of each gear: a CSV row per gear, a table row with both.
  void both(const std::string& what, double one, double two, const std::string& unit);
  // A quantity of the pair: a CSV row and a table row.
  void pair(const std::string& what, double value, const std::string& unit);
  // A quantity of the pair in geometry.csv only.
  void pair_csv_only(const std::string& what, double value, const std::string& unit);

 private:
  std::string shown(double value, const std::string& unit) const;
  std::string shown_unit(const std::string& unit) const;
};

}  // namespace gearimpact::cli
