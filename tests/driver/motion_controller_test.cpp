// The motion controller's tracking (observe): l = w − ν of Definition 4.9 and the torque τ of
// (4.6) in the status, with Procedure 4.13's weight.
#include "driver/motion_controller.hpp"

#include <gtest/gtest.h>

namespace marsokhod::driver {
namespace {

// The front-left wheel held at d = 0.5 at U = Ū = 24 V: ŵ = ζ0·W₅₁₁(0.5) = 0.9896·1.50 = 1.4844
// rad/s, and after five cycles ν of (4.4) is ŵ (the δ of h = 0.0157 s sum to 1). A measured w
// 0.1653 rad/s above it is the load of Procedure 4.13's 5.51 N·m pushing along d (B⁺(0.5) =
// 0.030); 0.08265 below it, the same torque against d (B⁻(0.5) = 0.015).
TEST(MotionControllerTracking, StatusCarriesTheTorqueOfProcedure4_13sWeight) {
  const Params params;
  for (const auto& [defect_radps, torque_nm] : {std::pair{0.1653, 5.51}, {-0.08265, -5.51}}) {
    MotionController controller(params);
    MotorVector duty{};
    duty[kFrontLeft] = 0.5;
    for (int k = 0; k < 6; ++k) controller.record_sent(duty, 24.0);
    MotionInput input;
    input.period_s = params.cycle.period_s;
    input.shaft_velocity_radps[kFrontLeft] = 0.9896 * 1.50 + defect_radps;
    DriverStatus status;
    controller.observe(input, status);
    const MotorStatus& m = status.motors[kFrontLeft];
    EXPECT_NEAR(m.no_load_velocity_radps, 1.4844, 1e-9);
    EXPECT_NEAR(m.load_radps, defect_radps, 1e-9);
    EXPECT_NEAR(m.torque_nm, torque_nm, 1e-6);
    // A still motor at d = 0: no load, no torque.
    EXPECT_EQ(status.motors[kCenterLeft].torque_nm, 0.0);
  }
}

}  // namespace
}  // namespace marsokhod::driver
