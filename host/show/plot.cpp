#include "host/show/plot.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace evms::show {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

void run_gnuplot(const std::string& script_path) {
  const std::string cmd = "gnuplot " + quoted(script_path) + " 2>&1";
  std::FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("cannot run gnuplot (install gnuplot-nox)");
  std::string output;
  char buf[256];
  while (std::fgets(buf, sizeof buf, p)) output += buf;
  const int status = pclose(p);
  if (status != 0) {
    throw std::runtime_error(status == 127 * 256 ? "gnuplot not found: install gnuplot-nox"
                                                 : script_path + ": gnuplot failed: " + output.substr(0, output.find('\n')));
  }
}

// One data block per series, separated by two blank lines (gnuplot's "index").
void write_series(std::ostream& dat, const std::vector<Series>& series) {
  for (const Series& s : series) {
    for (size_t i = 0; i < s.x.size(); ++i) dat << s.x[i] << ' ' << s.y[i] << '\n';
    if (s.x.empty()) dat << "nan nan\n";
    dat << "\n\n";
  }
}

void panel_commands(std::ostream& gp, const Plot& p, const std::string& dat, size_t first_index) {
  gp << "set title " << quoted(p.title) << "\nset xlabel " << quoted(p.xlabel) << "\nset ylabel " << quoted(p.ylabel) << "\n";
  gp << (p.log_y ? "set logscale y\n" : "unset logscale y\n");
  if (p.y_range) gp << "set yrange [" << p.y_range->first << ":" << p.y_range->second << "]\n";
  else gp << "set autoscale y\n";
  gp << "plot ";
  for (size_t i = 0; i < p.series.size(); ++i) {
    gp << (i ? ", \\\n     " : "") << quoted(dat) << " index " << first_index + i << " using 1:2 with " << p.series[i].style
       << " title " << quoted(p.series[i].title);
  }
  gp << "\n";
}

const char* kStyle =
    "set grid lc rgb '#dddddd'\nset key outside right top box\nset border lc rgb '#555555'\n"
    "set colorsequence podo\n";

std::string terminal(bool png, int width, int height) {
  const std::string size = " size " + std::to_string(width) + "," + std::to_string(height);
  return png ? "set terminal pngcairo" + size + " font 'sans,10' background '#ffffff'\n"
             : "set terminal svg" + size + " dynamic font 'sans,11' background '#ffffff'\n";
}

}  // namespace

void render(const Plot& p, const std::string& stem) {
  std::ofstream dat(stem + ".dat");
  write_series(dat, p.series);
  dat.close();
  std::ofstream gp(stem + ".gp");
  gp << terminal(p.png, p.width, p.height) << "set output " << quoted(stem + (p.png ? ".png" : ".svg")) << "\n" << kStyle;
  panel_commands(gp, p, stem + ".dat", 0);
  gp.close();
  run_gnuplot(stem + ".gp");
}

void render(const std::vector<Plot>& panels, const std::string& title, const std::string& stem) {
  std::ofstream dat(stem + ".dat");
  std::vector<size_t> first;
  size_t index = 0;
  for (const Plot& p : panels) {
    first.push_back(index);
    write_series(dat, p.series);
    index += p.series.size();
  }
  dat.close();
  const int width = panels.empty() ? 760 : panels[0].width;
  const int height = panels.empty() ? 420 : panels[0].height;
  const bool png = !panels.empty() && panels[0].png;
  std::ofstream gp(stem + ".gp");
  gp << terminal(png, width, height * static_cast<int>(panels.size())) << "set output " << quoted(stem + (png ? ".png" : ".svg"))
     << "\n" << kStyle;
  gp << "set multiplot layout " << panels.size() << ",1 title " << quoted(title) << "\n";
  for (size_t i = 0; i < panels.size(); ++i) panel_commands(gp, panels[i], stem + ".dat", first[i]);
  gp << "unset multiplot\n";
  gp.close();
  run_gnuplot(stem + ".gp");
}

void render(const BarChart& c, const std::string& stem) {
  std::ofstream dat(stem + ".dat");
  dat << "category";
  for (const auto& [name, values] : c.series) dat << ' ' << quoted(name);
  dat << '\n';
  for (size_t i = 0; i < c.categories.size(); ++i) {
    dat << quoted(c.categories[i]);
    for (const auto& [name, values] : c.series) dat << ' ' << values[i];
    dat << '\n';
  }
  dat.close();
  std::ofstream gp(stem + ".gp");
  gp << terminal(false, 760, 420) << "set output " << quoted(stem + ".svg") << "\n" << kStyle;
  gp << "set title " << quoted(c.title) << "\nset ylabel " << quoted(c.ylabel) << "\n";
  if (c.y_range) gp << "set yrange [" << c.y_range->first << ":" << c.y_range->second << "]\n";
  gp << "set style data histograms\nset style histogram clustered gap 1\nset style fill solid 0.8 border -1\n"
        "set xtics rotate by -30\nset key autotitle columnhead\n";
  gp << "plot ";
  for (size_t i = 0; i < c.series.size(); ++i) {
    gp << (i ? ", " : "") << quoted(stem + ".dat") << " using " << i + 2 << (i == 0 ? ":xtic(1)" : "");
  }
  gp << "\n";
  gp.close();
  run_gnuplot(stem + ".gp");
}

}  // namespace evms::show
