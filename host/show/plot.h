// Figures for reports, drawn by gnuplot (Debian gnuplot-nox) as SVG. Each figure leaves its
// data (.dat) and script (.gp) beside the SVG so that a reader can restyle it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace evms::show {

struct Series {
  std::string title;
  std::vector<double> x, y;
  std::string style = "lines";  // any gnuplot "with" clause: lines, points pt 7 ps 0.3, linespoints, ...
};

struct Plot {
  std::string title, xlabel, ylabel;
  std::vector<Series> series;
  bool log_y = false;
  std::optional<std::pair<double, double>> y_range;
  int width = 760, height = 420;
  bool png = false;  // dense scatter plots: a PNG stays small where an SVG would not
};

// Grouped bars: one group per category, one bar per series.
struct BarChart {
  std::string title, ylabel;
  std::vector<std::string> categories;
  std::vector<std::pair<std::string, std::vector<double>>> series;
  std::optional<std::pair<double, double>> y_range;
};

// Writes stem.dat, stem.gp and stem.svg (stem.png for `png` plots); throws std::runtime_error
// when gnuplot fails.
void render(const Plot& plot, const std::string& stem);
void render(const BarChart& chart, const std::string& stem);
// Several plots stacked in one figure.
void render(const std::vector<Plot>& panels, const std::string& title, const std::string& stem);

}  // namespace evms::show
