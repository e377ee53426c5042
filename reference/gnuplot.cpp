#include "gnuplot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "gearimpact/io/atomic_file.hpp"
#include "run_program.hpp"

namespace gearimpact::cli {

namespace {

std::string script_text(const Figure& figure) {
  // The comment holds the title quoted too: a line ending in a backslash would continue it.
  std::string text =
      "# " + gnuplot_string(figure.title) + "\n" + "# Made by gearimpact; run `gnuplot " +
      figure.name + ".gp` in this folder to redraw.\n" + "set datafile separator ','\n" +
      "set key autotitle columnhead\n" + "set title " + gnuplot_string(figure.title) + "\n" +
      "set xlabel " + gnuplot_string(figure.x_label) + "\n" + "set ylabel " +
      gnuplot_string(figure.y_label) + "\n" + "set grid\n";
  for (const std::string& line : figure.setup) text += line + "\n";
  std::string plot = "plot ";
  for (std::size_t i = 0; i < figure.series.size(); ++i) {
    plot += (i ? ", \\\n     " : "") + figure.series[i];
  }
  text += "set terminal pngcairo size 1000,650 font 'Sans,11'\n";
  text += "set output " + gnuplot_string(figure.name + ".png") + "\n";
  text += plot + "\n";
  text += "set terminal svg size 1000,650 font 'Sans,11'\n";
  text += "set output " + gnuplot_string(figure.name + ".svg") + "\n";
  text += "replot\n";
  return text;
}

}  // namespace

std::string gnuplot_string(const std::string& text) {
  std::string out = "'";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\'')
      out += "''";
    else if (byte < 0x20 || byte == 0x7f)
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

std::string literal_key(const std::string& key) {
  std::string out;
  for (const char c : key) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&' || c == '~' ||
        c == '\\')
      out += '\\';
    out += c;
  }
  return out;
}

Ticks nice_ticks(double low, double high, int count, double margin) {
  if (low > high) std::swap(low, high);
  const double size = std::max(std::fabs(low), std::fabs(high));
  const double least_span = size > 0.0 ? 1e-9 * size : 0.0;
  if (high - low <= least_span) {
    const double half = high == low ? (size > 0.0 ? 1e-3 * size : 1.0) : 0.5 * least_span;
    const double middle = 0.5 * (low + high);
    low = middle - half;
    high = middle + half;
  }
  const double pad = margin * (high - low);
  low -= pad;
  high += pad;
  const double raw = (high - low) / std::max(1, count);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * power;
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) {
      step = m * power;
      break;
    }
  }
  Ticks t;
  t.step = step;
  t.from = low;
  t.to = high;
  // The decimals of the step (2e-4: 4), none for a step of 1 or more.
  t.decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  return t;
}

std::vector<std::string> tick_commands(const std::string& axis, const Ticks& ticks,
                                       bool with_range) {
  char range[160];
  std::snprintf(range, sizeof range, "set %srange [%.15g:%.15g]", axis.c_str(), ticks.from,
                ticks.to);
  char tics[96];
  std::snprintf(tics, sizeof tics, "set %stics %.15g", axis.c_str(), ticks.step);
  std::vector<std::string> commands;
  if (with_range) commands.emplace_back(range);
  commands.emplace_back(tics);
  commands.push_back("set format " + axis + " \"%." + std::to_string(ticks.decimals) + "f\"");
  return commands;
}

void render(const std::filesystem::path& dir, const Figure& figure) {
  const std::filesystem::path script = dir / (figure.name + ".gp");
  write_file_atomically(script.string(), script_text(figure));
  // gnuplot SCRIPT in `dir`, from an argument vector: no shell sees the folder's or the
  // script's name; a failure names the script with gnuplot's own message.
  ProgramCall call;
  call.argv = {"gnuplot", figure.name + ".gp"};
  call.dir = dir.empty() ? std::filesystem::path(".") : dir;
  call.shown = script.string();
  call.missing_hint = "Debian's gnuplot-nox; scripts/setup.sh installs it";
  run_program(call);
}

}  // namespace gearimpact::cli
