// PNG plots of a recording with gnuplot (Debian's gnuplot-nox), from telemetry.csv by column name.
#include <cstdlib>
#include <fstream>

#include "runner/scenario_runner.hpp"

namespace marsokhod::runner {
namespace {

constexpr const char* kScript = R"GP(set datafile separator ","
set terminal pngcairo size 1000,700 font ",10"
set key outside right
set grid
set xlabel "t [s]"
set output "duty-and-speed.png"
set multiplot layout 2,1 title "Duty cycles and wheel speeds (cf. Figure 3.5)"
set ylabel "d"
plot for [m in "FL FR CL CR BL BR"] "telemetry.csv" using "t_s":m."_duty" with lines title m
set ylabel "w [rad/s]"
plot for [m in "FL FR CL CR BL BR"] "telemetry.csv" using "t_s":m."_w_radps" with lines title m
unset multiplot
set output "voltage.png"
set multiplot layout 2,1 title "Supply voltage U, reference U-bar and duty bound D (cf. Figure 6.1)"
set ylabel "[V]"
plot "telemetry.csv" using "t_s":"supply_v" with lines title "U", \
     "telemetry.csv" using "t_s":"reference_supply_v" with lines title "U-bar"
set ylabel "D"
set yrange [0:1.05]
plot "telemetry.csv" using "t_s":"max_duty" with lines title "D"
unset multiplot
set autoscale y
set output "joints.png"
set multiplot layout 2,1 title "Joint motor position p-bar and joint inclination p (cf. Figure 4.11)"
set ylabel "[rad]"
plot "telemetry.csv" using "t_s":"AF_shaft_rad" with lines title "p-bar 6", \
     "telemetry.csv" using "t_s":"AF_p_rad" with lines title "p 6"
plot "telemetry.csv" using "t_s":"AR_shaft_rad" with lines title "p-bar 7", \
     "telemetry.csv" using "t_s":"AR_p_rad" with lines title "p 7"
unset multiplot
)GP";

}  // namespace

std::optional<std::string> make_plots(const std::filesystem::path& folder) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    return "plots skipped: gnuplot is not installed (apt-get install gnuplot-nox)";
  }
  const std::filesystem::path script = folder / "plots.gnuplot";
  {
    std::ofstream out(script);
    if (!out) return "plots skipped: cannot write " + script.string();
    out << kScript;
  }
  const std::string command = "cd '" + folder.string() + "' && gnuplot plots.gnuplot 2>plots.log";
  if (std::system(command.c_str()) != 0) {
    return "plots failed: see " + (folder / "plots.log").string();
  }
  return std::nullopt;
}

}  // namespace marsokhod::runner
