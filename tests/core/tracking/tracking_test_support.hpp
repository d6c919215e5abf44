// Test helpers for the tracking layer: an emulation of the registers of one motor controller
// µ0–µ7 as chapter 3.2 describes them, and a check for std::invalid_argument messages.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>

#include "../../support/invalid_argument.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/motor_position.hpp"

namespace marsokhod::tracking::testing {

// The registers of one controller. enc counts every encoder pulse regardless of direction; on a
// measured direction change (with eim = 1) stp takes the value of enc and dir flips. tim ticks
// freely. The true signed pulse count is kept beside, to compare against the tracker.
class EmulatedMotorController {
 public:
  explicit EmulatedMotorController(std::uint8_t node = 0, std::uint16_t enc = 0,
                                   std::uint16_t tim = 0)
      : node_(node), enc_(enc), stp_(enc), tim_(tim) {}

  // Turns the shaft by pulses encoder pulses (negative: the dir = 1 direction), one at a time.
  void turn(std::int64_t pulses) {
    const bool direction = pulses < 0;
    const std::int64_t count = pulses < 0 ? -pulses : pulses;
    for (std::int64_t i = 0; i < count; ++i) {
      if (direction != dir_) {
        if (eim_) {
          stp_ = enc_;
        }
        dir_ = direction;
      }
      enc_ = static_cast<std::uint16_t>(enc_ + 1);
      true_counts_ += direction ? -1 : 1;
    }
  }

  void advance_clock(std::uint32_t ticks) { tim_ = static_cast<std::uint16_t>(tim_ + ticks); }
  void set_eim(bool eim) { eim_ = eim; }

  EncoderReading reading() const { return {enc_, stp_, dir_}; }
  protocol::ControlResponse respond(std::uint16_t vel = 0) const {
    protocol::ControlResponse response;
    response.node = node_;
    response.tim = tim_;
    response.enc = enc_;
    response.stp = stp_;
    response.dir = dir_;
    response.vel = vel;
    return response;
  }
  std::int64_t true_counts() const { return true_counts_; }

 private:
  std::uint8_t node_;
  std::uint16_t enc_;
  std::uint16_t stp_;
  std::uint16_t tim_;
  bool dir_ = false;
  bool eim_ = true;
  std::int64_t true_counts_ = 0;
};

using test_support::invalid_argument_message;

}  // namespace marsokhod::tracking::testing
