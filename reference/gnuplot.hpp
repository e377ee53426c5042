// Plots through gnuplot (Debian's gnuplot-nox): each figure is a gnuplot
// script written beside its data, run once for PNG and once for SVG, so a
// reader can re-run or restyle it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gearimpact::cli {

struct Figure {
  std::string name;  // file stem: DIR/NAME.png, DIR/NAME.svg, DIR/NAME.gp
  std::string title;
  std::string x_label;
  std::string y_label;
  // gnuplot commands placed before `plot` (ranges, shaded zones, keys).
  std::vector<std::string> setup;
  // The comma-separated series of the `plot` command.
  std::vector<std::string> series;
};

// Writes DIR/NAME.gp and runs gnuplot to make DIR/NAME.png and DIR/NAME.svg.
// Throws std::runtime_error naming the script if gnuplot is missing or fails.
void render(const std::filesystem::path& dir, const Figure& figure);

}  // namespace gearimpact::cli
