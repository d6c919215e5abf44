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
nlohmann::json truth_json(const sim::SimulatedRover& rover,
                          const std::optional<estimation::PlanarPose>& odometry = std::nullopt);

}  // namespace marsokhod::link
