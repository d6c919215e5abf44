// One telemetry.csv row per cycle: the driver's status (Figure 8.1 and more) and the simulator's
// ground truth, with units in the column names.
#pragma once

#include <string>

#include "driver/status.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::runner {

std::string telemetry_header();
std::string telemetry_row(double time_s, bool driver_running, const driver::DriverStatus& status,
                          const sim::SimulatedRover* rover);  // nullptr: no truth (empty)

}  // namespace marsokhod::runner
