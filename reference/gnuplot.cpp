#include "gnuplot.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace gearimpact::cli {

namespace {

std::string quoted(const std::string& text) {
  return "\"" + text + "\"";
}

}  // namespace

void render(const std::filesystem::path& dir, const Figure& figure) {
  const std::filesystem::path script = dir / (figure.name + ".gp");
  {
    std::ofstream out(script);
    out << "# " << figure.title << "\n"
        << "# Made by gearimpact reproduce; run `gnuplot " << figure.name
        << ".gp` in this folder to redraw.\n"
        << "set datafile separator ','\n"
        << "set key autotitle columnhead\n"
        << "set title " << quoted(figure.title) << "\n"
        << "set xlabel " << quoted(figure.x_label) << "\n"
        << "set ylabel " << quoted(figure.y_label) << "\n"
        << "set grid\n";
    for (const std::string& line : figure.setup) out << line << "\n";
    std::string plot = "plot ";
    for (std::size_t i = 0; i < figure.series.size(); ++i) {
      plot += (i ? ", \\\n     " : "") + figure.series[i];
    }
    out << "set terminal pngcairo size 1000,650 font 'Sans,11'\n"
        << "set output " << quoted(figure.name + ".png") << "\n"
        << plot << "\n"
        << "set terminal svg size 1000,650 font 'Sans,11'\n"
        << "set output " << quoted(figure.name + ".svg") << "\n"
        << "replot\n";
    if (!out) throw std::runtime_error("cannot write " + script.string());
  }
  const std::string command = "cd " + quoted(dir.string()) + " && gnuplot " +
                              quoted(figure.name + ".gp") + " > /dev/null 2>&1";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed on " + script.string() +
                             " (is Debian's gnuplot-nox installed? scripts/setup.sh installs it)");
  }
}

}  // namespace gearimpact::cli
