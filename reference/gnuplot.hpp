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

// An axis that shows the values from `low` to `high`, widened by `margin` of the span each way,
// with ticks at the multiples of a step of 1, 2 or 5 times a power of ten (about `count` of
// them, at least 2), each label printed with as many decimals as the step needs: the labels
// differ at any range (gnuplot's own "%g" repeats one label over a range narrow against the
// values). A range of one value is widened to 1e-3 of it (or 1 around 0), a range narrower than
// 1e-9 of the values to that, so that the step stays above the doubles' resolution.
struct Ticks {
  double from = 0.0;  // the axis' ends
  double to = 1.0;
  double step = 0.1;
  int decimals = 1;
};
Ticks nice_ticks(double low, double high, int count = 8, double margin = 0.0);

// The gnuplot commands that set `axis` ("x", "y", "x2", ...) to `ticks`: its range (unless
// `with_range` is false, for an axis linked to another), tick step and label format.
std::vector<std::string> tick_commands(const std::string& axis, const Ticks& ticks,
                                       bool with_range = true);

// `text` as a gnuplot string literal that is inert wherever it stands in a script: single
// quotes, in which gnuplot expands no backquote (`cmd`), no macro (@name) and no escape, with a
// quote doubled (the one escape there is) and each control character (a newline would end the
// command and start another) a space. Every string from outside the program (a case's name, a
// column's, a file's) reaches a script through it, as do the figure's title, labels and outputs.
std::string gnuplot_string(const std::string& text);

// Text (a key, a case's or a column's name) shown literally in gnuplot's enhanced mode, where
// "_" makes a subscript, "^" a superscript, "{...}" a group, "@", "&" and "~" boxes and "\" an
// escape: each of them escaped by a backslash. Its result goes into a script through
// gnuplot_string, like any text.
std::string literal_key(const std::string& key);

// Writes DIR/NAME.gp and runs gnuplot to make DIR/NAME.png and DIR/NAME.svg.
// Throws std::runtime_error naming the script if gnuplot is missing or fails.
void render(const std::filesystem::path& dir, const Figure& figure);

}  // namespace gearimpact::cli
