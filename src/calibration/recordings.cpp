#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "calibration/procedure.hpp"

namespace marsokhod::calibration {

std::optional<std::string> write_recordings(const std::vector<Recording>& recordings,
                                            const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create " + dir.string() + ": " + ec.message());
  bool any_plot = false;
  for (const Recording& r : recordings) {
    const std::filesystem::path csv = dir / (r.name + ".csv");
    std::ofstream out(csv);
    if (!out) throw std::runtime_error("cannot write " + csv.string());
    for (std::size_t c = 0; c < r.columns.size(); ++c) out << (c ? "," : "") << r.columns[c];
    out << '\n' << std::setprecision(9);
    for (const std::vector<double>& row : r.rows) {
      for (std::size_t c = 0; c < row.size(); ++c) out << (c ? "," : "") << row[c];
      out << '\n';
    }
    if (!out) throw std::runtime_error("cannot write " + csv.string());
    any_plot = any_plot || !r.gnuplot.empty();
  }
  if (!any_plot) return std::nullopt;
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    return "plots skipped: gnuplot is not installed (apt-get install gnuplot-nox); the CSVs are "
           "written";
  }
  for (const Recording& r : recordings) {
    if (r.gnuplot.empty()) continue;
    const std::filesystem::path script = dir / (r.name + ".gnuplot");
    {
      std::ofstream out(script);
      if (!out) throw std::runtime_error("cannot write " + script.string());
      out << "set datafile separator \",\"\n"
          << "set terminal pngcairo size 1000,700 font \",10\"\n"
          << "set output \"" << r.name << ".png\"\n"
          << "set title \"" << r.title << "\"\n"
          << "set grid\nset key outside right\n"
          << r.gnuplot << '\n';
    }
    const std::string command = "cd '" + dir.string() + "' && gnuplot '" + r.name +
                                ".gnuplot' 2>'" + r.name + ".log'";
    if (std::system(command.c_str()) != 0) {
      return "plot " + r.name + " failed: see " + (dir / (r.name + ".log")).string();
    }
  }
  return std::nullopt;
}

}  // namespace marsokhod::calibration
