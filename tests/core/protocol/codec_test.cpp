// Encoding: identifiers, golden frames worked out by hand, round trips over random fields, and
// the out-of-range fields encode refuses.
#include "core/protocol/codec.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../support/invalid_argument.hpp"
#include "protocol_test_util.hpp"

namespace marsokhod::protocol {
namespace {

using test::make_frame;

// docs/design.md: CAN ID = idt << 3, idt = 0xiT.
static_assert(can_id(3, kControlRequestType) == 0x180);  // idt 0x30
static_assert(can_id(8, kMeasurementRequestType) == 0x400);  // idt 0x80
static_assert(can_id(0, kControlRequestType) == 0x000);
static_assert(can_id(7, kConfigurationResponseType) == 0x398);  // idt 0x73: 0x73·8 = 0x398
static_assert(can_id(8, kDeadManResponseType) == 0x418);        // idt 0x83: 0x83·8 = 0x418
static_assert(can_id(15, 15) == 0x7F8);                         // the largest idt still fits 11 bits

TEST(CanId, RejectsArgumentsWiderThanANibble) {
  EXPECT_THROW((void)can_id(16, 0), std::invalid_argument);
  EXPECT_THROW((void)can_id(0, 16), std::invalid_argument);
}

struct Golden {
  Message message;
  CanFrame frame;
};

// Every byte below is worked out by hand from the tables of chapter 3.2–3.3 and docs/design.md.
std::vector<Golden> golden_frames() {
  MeasurementRequest lcd{true, false, {'2', '4', '.', '0', 'V', ' ', 'o', 'k'}};
  return {
      // µ3 control request drv=1 eim=1 pwm=300: idt 0x30 → id 0x30·8 = 0x180;
      // byte 0 = drv(bit0) | eim(bit1) = 0x03; 300 = 0x012C → 01 2C.
      {ControlRequest{3, true, true, 300}, make_frame(0x180, {0x03, 0x01, 0x2C})},
      // µ7 control request drv=0 eim=1 pwm=2047 (0x07FF): idt 0x70 → 0x380; byte 0 = 0x02.
      {ControlRequest{7, false, true, 2047}, make_frame(0x380, {0x02, 0x07, 0xFF})},
      // µ5 control response tim=0x1234 enc=40000 (0x9C40) stp=513 (0x0201) dir=1 vel=6844
      // (0x1ABC): idt 0x51 → 0x51·8 = 0x288; byte 6 = 0x80 | 0x1A = 0x9A, byte 7 = 0xBC.
      {ControlResponse{5, 0x1234, 40000, 513, true, 6844},
       make_frame(0x288, {0x12, 0x34, 0x9C, 0x40, 0x02, 0x01, 0x9A, 0xBC})},
      // µ0 control response dir=0 vel=32767 (0x7FFF): byte 6 = 0x7F, byte 7 = 0xFF; id 0x008.
      {ControlResponse{0, 0, 0, 0, false, 32767},
       make_frame(0x008, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x7F, 0xFF})},
      // µ6 configuration request icr=511 (0x01FF) pwm=0 con=1: idt 0x62 → 0x62·8 = 0x310.
      {ConfigurationRequest{6, 511, 0, 1}, make_frame(0x310, {0x01, 0xFF, 0x00, 0x00, 0x01})},
      // µ0 configuration response tim=65535: idt 0x03 → 0x018, bytes FF FF.
      {ConfigurationResponse{0, 65535}, make_frame(0x018, {0xFF, 0xFF})},
      // µ8 measurement request led0=1 led1=0 "24.0V ok": '2' = 0x32 | 0x80 (led0) = 0xB2,
      // '4' = 0x34, '.' = 0x2E, '0' = 0x30, 'V' = 0x56, ' ' = 0x20, 'o' = 0x6F, 'k' = 0x6B.
      {lcd, make_frame(0x400, {0xB2, 0x34, 0x2E, 0x30, 0x56, 0x20, 0x6F, 0x6B})},
      // µ8 measurement response at the TYP readings of chapter 3.3, tilt channel front (j=0):
      // yaw 505 = 4·126+1 → 0x7E,1; acc¹ 279 = 4·69+3 → 0x45,3; acc² 251 = 4·62+3 → 0x3E,3;
      // acc³ 376 = 4·94+0 → 0x5E,0; tltᶠ 527 = 4·131+3 → 0x83,3; vcc 970 = 4·242+2 → 0xF2,2.
      // b6 = 01 11 11 00 = 0x7C; b7 = 11 10 000 0 = 0xE0. idt 0x81 → 0x408.
      {MeasurementResponse{505, {279, 251, 376}, 527, 970, TiltChannel::kFront},
       make_frame(0x408, {0x7E, 0x45, 0x3E, 0x5E, 0x83, 0xF2, 0x7C, 0xE0})},
      // Same with tltʳ 520 = 4·130+0 → 0x82,0 and j=1: b7 = 00 10 000 1 = 0x21.
      {MeasurementResponse{505, {279, 251, 376}, 520, 970, TiltChannel::kRear},
       make_frame(0x408, {0x7E, 0x45, 0x3E, 0x5E, 0x82, 0xF2, 0x7C, 0x21})},
      // µ8 dead man request dog=4 (1.05 s): idt 0x82 → 0x410, byte 04.
      {DeadManRequest{4}, make_frame(0x410, {0x04})},
      // µ8 dead man response: idt 0x83 → 0x418, no data.
      {DeadManResponse{}, make_frame(0x418, {})},
  };
}

TEST(Golden, EncodeGivesTheHandWrittenBytes) {
  for (const Golden& golden : golden_frames()) {
    EXPECT_EQ(encode(golden.message), golden.frame) << message_name(golden.message);
  }
}

TEST(Golden, DecodeGivesTheMessage) {
  for (const Golden& golden : golden_frames()) {
    const DecodeResult result = decode(golden.frame);
    ASSERT_TRUE(result.ok()) << result.error().reason;
    EXPECT_EQ(result.message(), golden.message) << message_name(golden.message);
  }
}

// Each 10-bit reading alone at 1023 (high byte 0xFF, low bits 11) lands in its own byte and bits.
TEST(Layout, MeasurementResponseReadingsLandInTheirBits) {
  struct Case {
    MeasurementResponse message;
    std::size_t high_byte;
    std::uint8_t b6;
    std::uint8_t b7;
  };
  const std::vector<Case> cases{
      {{1023, {0, 0, 0}, 0, 0, TiltChannel::kFront}, 0, 0xC0, 0x00},
      {{0, {1023, 0, 0}, 0, 0, TiltChannel::kFront}, 1, 0x30, 0x00},
      {{0, {0, 1023, 0}, 0, 0, TiltChannel::kFront}, 2, 0x0C, 0x00},
      {{0, {0, 0, 1023}, 0, 0, TiltChannel::kFront}, 3, 0x03, 0x00},
      {{0, {0, 0, 0}, 1023, 0, TiltChannel::kFront}, 4, 0x00, 0xC0},
      {{0, {0, 0, 0}, 0, 1023, TiltChannel::kFront}, 5, 0x00, 0x30},
  };
  for (const Case& c : cases) {
    CanFrame expected = make_frame(0x408, {0, 0, 0, 0, 0, 0, c.b6, c.b7});
    expected.data[c.high_byte] = 0xFF;
    EXPECT_EQ(encode(c.message), expected) << "reading in byte " << c.high_byte;
  }
}

class RoundTrip : public ::testing::TestWithParam<std::size_t> {};

// decode(encode(m)) == m and encode(decode(f)) == f for thousands of random legal messages.
TEST_P(RoundTrip, RandomMessagesSurviveEncodeAndDecode) {
  std::mt19937 rng(20080601U + static_cast<unsigned>(GetParam()));
  for (int iteration = 0; iteration < 5000; ++iteration) {
    const Message message = test::random_message(rng, GetParam());
    ASSERT_EQ(message.index(), GetParam());
    const CanFrame frame = encode(message);
    ASSERT_EQ(frame.id, can_id(node_of(message), type_of(message)));
    const DecodeResult result = decode(frame);
    ASSERT_TRUE(result.ok()) << result.error().reason;
    ASSERT_EQ(result.message(), message) << "iteration " << iteration;
    ASSERT_EQ(encode(result.message()), frame) << "iteration " << iteration;
  }
}

std::string alternative_name(const ::testing::TestParamInfo<std::size_t>& info) {
  static constexpr const char* kNames[] = {
      "ControlRequest",     "ControlResponse",     "ConfigurationRequest", "ConfigurationResponse",
      "MeasurementRequest", "MeasurementResponse", "DeadManRequest",       "DeadManResponse"};
  return kNames[info.param];
}

INSTANTIATE_TEST_SUITE_P(EveryMessageType, RoundTrip, ::testing::Range<std::size_t>(0, 8),
                         alternative_name);

TEST(Helpers, NodeTypeAndNameOfEveryMessage) {
  EXPECT_EQ(node_of(ControlRequest{5, false, false, 0}), 5);
  EXPECT_EQ(node_of(ConfigurationResponse{7, 0}), 7);
  EXPECT_EQ(node_of(MeasurementRequest{}), 8);
  EXPECT_EQ(node_of(DeadManResponse{}), 8);
  EXPECT_EQ(type_of(ConfigurationRequest{}), kConfigurationRequestType);
  EXPECT_EQ(type_of(DeadManRequest{}), kDeadManRequestType);
  EXPECT_STREQ(message_name(ControlResponse{}), "control response");
  EXPECT_STREQ(message_name(MeasurementResponse{}), "measurement response");
  EXPECT_STREQ(message_name(DeadManRequest{}), "dead man request");
}

// encode must refuse what the wire cannot carry, naming the field, its value and the range.
constexpr auto expect_refused = &test_support::expect_invalid_argument;

TEST(EncodeRefuses, MotorNodeAbove7) {
  expect_refused([] { encode(ControlRequest{8, false, false, 0}); }, {"node = 8", "0..7"});
  expect_refused([] { encode(ControlResponse{9, 0, 0, 0, false, 0}); }, {"node = 9", "0..7"});
  expect_refused([] { encode(ConfigurationRequest{8, 511, 0, 0}); }, {"node = 8", "0..7"});
  expect_refused([] { encode(ConfigurationResponse{255, 0}); }, {"node = 255", "0..7"});
}

TEST(EncodeRefuses, VelocityWiderThan15Bits) {
  expect_refused([] { encode(ControlResponse{0, 0, 0, 0, false, 0x8000}); },
                 {"control response", "vel = 32768", "0..32767"});
}

TEST(EncodeRefuses, PwmAboveIcr) {
  expect_refused([] { encode(ConfigurationRequest{1, 511, 512, 0}); },
                 {"configuration request", "pwm = 512", "0..511"});
  expect_refused([] { encode(ControlRequest{1, false, false, 2048}); },
                 {"control request", "pwm = 2048", "0..2047"});
  EXPECT_NO_THROW(encode(ConfigurationRequest{1, 511, 511, 0}));
}

TEST(EncodeRefuses, IcrOutsideItsRange) {
  expect_refused([] { encode(ConfigurationRequest{1, 254, 0, 0}); }, {"icr = 254", "255..2047"});
  expect_refused([] { encode(ConfigurationRequest{1, 2048, 0, 0}); }, {"icr = 2048", "255..2047"});
}

TEST(EncodeRefuses, AdcReadingAbove1023) {
  const std::vector<std::pair<std::string, std::function<void(MeasurementResponse&)>>> fields{
      {"yaw", [](MeasurementResponse& m) { m.yaw = 1024; }},
      {"acc[0]", [](MeasurementResponse& m) { m.acc[0] = 1024; }},
      {"acc[1]", [](MeasurementResponse& m) { m.acc[1] = 1024; }},
      {"acc[2]", [](MeasurementResponse& m) { m.acc[2] = 1024; }},
      {"tlt", [](MeasurementResponse& m) { m.tlt = 1024; }},
      {"vcc", [](MeasurementResponse& m) { m.vcc = 0xFFFF; }},
  };
  for (const auto& [field, spoil] : fields) {
    MeasurementResponse message;
    spoil(message);
    expect_refused([&message] { encode(message); }, {field + " = ", "0..1023"});
  }
  MeasurementResponse bad_channel;
  bad_channel.tilt_channel = static_cast<TiltChannel>(2);
  expect_refused([&bad_channel] { encode(bad_channel); }, {"tilt_channel = 2", "0..1"});
}

TEST(EncodeRefuses, LcdCharacterOutsideAscii32To127) {
  MeasurementRequest newline;
  newline.lcd[3] = '\n';
  expect_refused([&newline] { encode(newline); }, {"lcd[3] = 10", "32..127"});
  MeasurementRequest high;
  high.lcd[0] = static_cast<char>(0xC4);
  expect_refused([&high] { encode(high); }, {"lcd[0] = 196", "32..127"});
  MeasurementRequest edges;
  edges.lcd = {' ', '\x7F', 'A', 'z', '~', '0', '9', ' '};
  EXPECT_NO_THROW(encode(edges));
}

}  // namespace
}  // namespace marsokhod::protocol
