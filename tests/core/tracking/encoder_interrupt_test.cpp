#include "core/tracking/encoder_interrupt.hpp"

#include "tracking_test_support.hpp"

namespace marsokhod::tracking {
namespace {

TEST(EncoderInterrupt, EnabledBelowSixTenthsOfIcr) {
  // icr = 511: 0.6·511 = 306.6, so pwm 306 (0.5988) enables, pwm 307 (0.6008) does not.
  EXPECT_TRUE(direction_change_update_enabled(0, 511));
  EXPECT_TRUE(direction_change_update_enabled(306, 511));
  EXPECT_FALSE(direction_change_update_enabled(307, 511));
  EXPECT_FALSE(direction_change_update_enabled(511, 511));
}

TEST(EncoderInterrupt, BoundaryIsExact) {
  // icr = 510: pwm = 306 is exactly 0.6, which is not below 0.6; 305 is.
  EXPECT_FALSE(direction_change_update_enabled(306, 510));
  EXPECT_TRUE(direction_change_update_enabled(305, 510));
  // Largest registers: icr 2047, pwm 1228 = 0.59990, 1229 = 0.60039.
  EXPECT_TRUE(direction_change_update_enabled(1228, 2047));
  EXPECT_FALSE(direction_change_update_enabled(1229, 2047));
  EXPECT_FALSE(direction_change_update_enabled(65535, 2047));
}

TEST(EncoderInterrupt, RejectsNonPositiveIcr) {
  EXPECT_THAT(testing::invalid_argument_message([] { direction_change_update_enabled(0, 0); }),
              ::testing::HasSubstr("icr = 0"));
}

}  // namespace
}  // namespace marsokhod::tracking
