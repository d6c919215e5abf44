// The driver's status as the console, the logs and the 3-D view read it, and the simulator's
// ground truth beside it. The status: every field of
// DriverStatus, units in the key names, motors keyed by their names in (3.1) (FL FR CL CR BL BR
// AF AR). docs/operator-protocol.md lists the keys. A number that is not finite becomes null
// (JSON has no NaN); strings are passed through as they are — the server replaces any invalid
// UTF-8 when it writes the text.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "core/estimation/odometry_frame.hpp"
#include "driver/status.hpp"
#include "sim/rover/simulated_rover.hpp"
#include "sim/soil/soft_soil.hpp"

namespace marsokhod::link {

// `truth`: the simulator's ground truth for the 3-D view, attached as "truth" unless it is null.
// Throws std::invalid_argument if `truth` is neither null nor an object.
nlohmann::json status_json(const driver::DriverStatus& status,
                           const nlohmann::json& truth = nullptr);

// The status' `pose` object (the dead reckoning, its keys in docs/operator-protocol.md): also the
// recordings' /pose/estimate channel.
nlohmann::json pose_json(const estimation::Pose& pose);

// The simulated rover's ground truth for the 3-D view (docs/console.md lists the keys it reads):
// position_m, roll_pitch_yaw_rad, velocity_mps, joint_angle_rad (8, motor order),
// wheel_angle_rad (6), wheel_position_m (6 × [x, y, z]), wheel_slip_mps, supply_v, computer_on;
// with `odometry` (the true pose in the driver's odometry frame, estimation/odometry_frame.hpp),
// also odometry: {x_m, y_m, heading_rad} for the console's map beside the dead-reckoned pose.
// With `with_soil` on a soft soil (sim/soil), also soil: soil_patch_json around the rover.
nlohmann::json truth_json(const sim::SimulatedRover& rover,
                          const std::optional<estimation::PlanarPose>& odometry = std::nullopt,
                          bool with_soil = false);

// The soil's surface around (x, y) for the 3-D view's ruts (issue #14): every second cell of the
// grid (4 cm on the rover's 2 cm grid), kSoilPatchSpanM / 4 cm of them each way (80 × 50), from
// the first within half the span before (x, y) — the corner on those cells, so that the patch
// does not shimmer as the rover moves — clipped to the grid (empty off it or for a position
// that is not finite):
//   {"origin_m": [x0, y0], "cell_m": h, "columns": C, "rows": R, "height_mm": [R·C integers]}
// height_mm[r·C + c] is the surface (world z, mm, rounded) at the cell centre
// (x0 + c·h, y0 + r·h): rows along +y, columns along +x. The undisturbed ground included, so on
// a slope the patch is tilted like the ground.
inline constexpr double kSoilPatchSpanM[2] = {3.2, 2.0};  // along x, along y
nlohmann::json soil_patch_json(const sim::soil::SoilGrid& grid, double x_m, double y_m);

}  // namespace marsokhod::link
