#include "driver/frame_intake.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace marsokhod::driver {
namespace {

std::array<bool, kMotorCount + 1> all_expected() {
  std::array<bool, kMotorCount + 1> e{};
  e.fill(true);
  return e;
}

std::vector<protocol::CanFrame> full_cycle() {
  std::vector<protocol::CanFrame> frames;
  for (std::uint8_t i = 0; i < 8; ++i) {
    frames.push_back(protocol::encode(protocol::ControlResponse{i, 100, 200, 0, false, 10}));
  }
  frames.push_back(protocol::encode(protocol::MeasurementResponse{505, {279, 251, 376}, 527, 970}));
  return frames;
}

TEST(FrameIntake, SortsAFullCycle) {
  FrameIntake intake(511);
  const auto frames = full_cycle();
  const CycleResponses r = intake.take(frames, all_expected());
  for (std::size_t i = 0; i < 8; ++i) ASSERT_TRUE(r.control[i].has_value());
  EXPECT_TRUE(r.measurement.has_value());
  EXPECT_EQ(intake.counters().frames, 9u);
  EXPECT_EQ(intake.counters().missed, 0u);
}

TEST(FrameIntake, CountsMalformedDuplicateAndForeignFrames) {
  FrameIntake intake(511);
  auto frames = full_cycle();
  frames.push_back(frames[2]);                                              // duplicate µ2
  frames.push_back(protocol::CanFrame{0x181, 8, {}});                       // low id bits set
  frames.push_back(protocol::encode(protocol::ControlRequest{4, false, false, 0}));  // µ8's stop
  const CycleResponses r = intake.take(frames, all_expected());
  EXPECT_TRUE(r.control[2].has_value());
  EXPECT_EQ(intake.counters().duplicates, 1u);
  EXPECT_EQ(intake.counters().malformed, 1u);
  EXPECT_EQ(intake.counters().foreign, 1u);
  EXPECT_NE(intake.counters().last_error.find("0x181"), std::string::npos);
}

TEST(FrameIntake, CountsConsecutiveSilence) {
  FrameIntake intake(511);
  auto frames = full_cycle();
  frames.erase(frames.begin() + 5);  // µ5 silent
  for (int k = 1; k <= 3; ++k) {
    intake.take(frames, all_expected());
    EXPECT_EQ(intake.silent_cycles()[5], k);
    EXPECT_EQ(intake.silent_cycles()[4], 0);
  }
  intake.take(full_cycle(), all_expected());
  EXPECT_EQ(intake.silent_cycles()[5], 0);
  EXPECT_EQ(intake.counters().missed, 3u);
}

TEST(FrameIntake, PwmAboveTheConfiguredIcrIsMalformed) {
  FrameIntake intake(511);
  std::vector<protocol::CanFrame> frames{
      protocol::encode(protocol::ControlRequest{1, false, true, 600})};
  intake.take(frames, {});
  EXPECT_EQ(intake.counters().malformed, 1u);
}

}  // namespace
}  // namespace marsokhod::driver
