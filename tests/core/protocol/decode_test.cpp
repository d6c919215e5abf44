// Decoding: every rejection with its reason, frames built from raw bytes, the icr context.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/protocol/codec.hpp"
#include "protocol_test_util.hpp"

namespace marsokhod::protocol {
namespace {

using test::make_frame;

// Checks the code and that the reason names what was wrong.
void expect_rejected(const CanFrame& frame, DecodeErrorCode code,
                     const std::vector<std::string>& fragments,
                     const DecodeContext& context = {}) {
  const DecodeResult result = decode(frame, context);
  ASSERT_FALSE(result.ok()) << "accepted " << ::testing::PrintToString(frame) << " as "
                            << message_name(result.message());
  EXPECT_EQ(result.error().code, code) << error_code_name(result.error().code) << ": "
                                       << result.error().reason;
  for (const std::string& fragment : fragments) {
    EXPECT_NE(result.error().reason.find(fragment), std::string::npos)
        << "'" << fragment << "' missing from: " << result.error().reason;
  }
}

TEST(DecodeRejects, IdentifierAbove11Bits) {
  expect_rejected(make_frame(0x800, {0x00, 0x00, 0x00}), DecodeErrorCode::kIdOutOfRange,
                  {"0x800", "0x7FF"});
  expect_rejected(make_frame(0xFFFF, {}), DecodeErrorCode::kIdOutOfRange, {"0xFFFF"});
}

TEST(DecodeRejects, NonzeroLowIdentifierBits) {
  for (std::uint32_t low = 1; low < 8; ++low) {
    expect_rejected(make_frame(0x180 | low, {0x00, 0x00, 0x00}), DecodeErrorCode::kIdLowBitsSet,
                    {"lowest 3 identifier bits are " + std::to_string(low)});
  }
}

TEST(DecodeRejects, NodeAbove8) {
  for (std::uint8_t node = 9; node < 16; ++node) {
    expect_rejected(make_frame(can_id(node, 0), {0x00, 0x00, 0x00}),
                    DecodeErrorCode::kNodeOutOfRange,
                    {"node " + std::to_string(node), "0..8"});
  }
}

TEST(DecodeRejects, UnknownTypeForTheNode) {
  for (std::uint8_t type = 4; type < 16; ++type) {
    expect_rejected(make_frame(can_id(1, type), {}), DecodeErrorCode::kUnknownType,
                    {"type " + std::to_string(type), "µ1", "0x10..0x13"});
    expect_rejected(make_frame(can_id(8, type), {}), DecodeErrorCode::kUnknownType,
                    {"type " + std::to_string(type), "µ8", "0x80..0x83"});
  }
}

TEST(DecodeRejects, WrongDlcWithTheExpectedOne) {
  const DecodeResult result = decode(make_frame(0x188, {0, 0, 0, 0, 0, 0, 0}));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, DecodeErrorCode::kWrongDlc);
  EXPECT_EQ(result.error().reason,
            "0x188 (idt 0x31): DLC 7, expected 8 for a control response (0xi1)");

  const std::vector<std::uint8_t> expected_dlc{3, 8, 5, 2, 8, 8, 1, 0};
  for (std::uint8_t index = 0; index < 8; ++index) {
    const std::uint8_t node = index < 4 ? 2 : 8;
    const auto type = static_cast<std::uint8_t>(index % 4);
    for (std::uint8_t dlc = 0; dlc < 16; ++dlc) {
      if (dlc == expected_dlc[index]) {
        continue;
      }
      CanFrame frame = make_frame(can_id(node, type), {});
      frame.dlc = dlc;
      expect_rejected(frame, DecodeErrorCode::kWrongDlc,
                      {"DLC " + std::to_string(dlc),
                       "expected " + std::to_string(expected_dlc[index])});
    }
  }
}

TEST(DecodeRejects, ControlRequestPwmAboveTheConfiguredIcr) {
  DecodeContext context;
  context.icr[3] = 511;
  // pwm 512 = 0x0200 against icr 511 of µ3; µ4 keeps the default 2047.
  expect_rejected(make_frame(can_id(3, 0), {0x00, 0x02, 0x00}), DecodeErrorCode::kPwmAboveIcr,
                  {"pwm 512", "icr 511", "µ3", "control request (0xi0)"}, context);
  EXPECT_TRUE(decode(make_frame(can_id(3, 0), {0x00, 0x01, 0xFF}), context).ok());
  EXPECT_TRUE(decode(make_frame(can_id(4, 0), {0x00, 0x02, 0x00}), context).ok());
  // Without context the largest legal icr, 2047 = 0x07FF, bounds pwm.
  EXPECT_TRUE(decode(make_frame(can_id(4, 0), {0x00, 0x07, 0xFF})).ok());
  expect_rejected(make_frame(can_id(4, 0), {0x00, 0x08, 0x00}), DecodeErrorCode::kPwmAboveIcr,
                  {"pwm 2048", "icr 2047"});
}

TEST(DecodeRejects, ConfigurationRequestPwmAboveItsIcr) {
  // icr 511 = 0x01FF, pwm 512 = 0x0200.
  expect_rejected(make_frame(can_id(6, 2), {0x01, 0xFF, 0x02, 0x00, 0x00}),
                  DecodeErrorCode::kPwmAboveIcr, {"pwm 512", "icr 511", "configuration request"});
  EXPECT_TRUE(decode(make_frame(can_id(6, 2), {0x01, 0xFF, 0x01, 0xFF, 0x00})).ok());
}

TEST(DecodeRejects, ConfigurationRequestIcrOutside255To2047) {
  for (const std::uint16_t icr : {0, 254, 2048, 0xFFFF}) {
    const auto high = static_cast<std::uint8_t>(icr >> 8);
    const auto low = static_cast<std::uint8_t>(icr & 0xFF);
    expect_rejected(make_frame(can_id(0, 2), {high, low, 0x00, 0x00, 0x00}),
                    DecodeErrorCode::kIcrOutOfRange, {"icr " + std::to_string(icr), "255..2047"});
  }
  EXPECT_TRUE(decode(make_frame(can_id(0, 2), {0x00, 0xFF, 0x00, 0x00, 0x00})).ok());  // 255
  EXPECT_TRUE(decode(make_frame(can_id(0, 2), {0x07, 0xFF, 0x00, 0x00, 0x00})).ok());  // 2047
}

TEST(DecodeRejects, NonAsciiLcdCharacter) {
  const CanFrame spaces = make_frame(0x400, {' ', ' ', ' ', ' ', ' ', ' ', ' ', ' '});
  // Bytes 0–1 carry a LED in bit 7: only their low 7 bits must be ≥ 32.
  for (const std::uint8_t bad : {0x00, 0x1F, 0x80, 0x9F}) {
    for (std::size_t i = 0; i < 2; ++i) {
      CanFrame frame = spaces;
      frame.data[i] = bad;
      expect_rejected(frame, DecodeErrorCode::kNonAsciiLcd,
                      {"LCD character " + std::to_string(i), "low 7 bits of byte", "32..127"});
    }
  }
  for (const std::uint8_t bad : {0x00, 0x1F, 0x80, 0xFF}) {
    for (std::size_t i = 2; i < 8; ++i) {
      CanFrame frame = spaces;
      frame.data[i] = bad;
      expect_rejected(frame, DecodeErrorCode::kNonAsciiLcd,
                      {"LCD character " + std::to_string(i), "(byte " + std::to_string(i)});
    }
  }
  // 0xFF in byte 0 is led⁰ on with character 127: legal.
  CanFrame edges = spaces;
  edges.data[0] = 0xFF;
  edges.data[7] = 0x7F;
  EXPECT_TRUE(decode(edges).ok());
}

TEST(DecodeRejects, ReservedBitsOfTheControlRequest) {
  for (int bit = 2; bit < 8; ++bit) {
    const auto flags = static_cast<std::uint8_t>(1U << bit);
    expect_rejected(make_frame(0x180, {flags, 0x00, 0x00}), DecodeErrorCode::kReservedBitsSet,
                    {"reserved bits 7..2 of byte 0", "control request"});
  }
}

TEST(DecodeRejects, ReservedBitsOfTheMeasurementResponse) {
  for (int bit = 1; bit < 4; ++bit) {
    const auto b7 = static_cast<std::uint8_t>(1U << bit);
    expect_rejected(make_frame(0x408, {0, 0, 0, 0, 0, 0, 0, b7}),
                    DecodeErrorCode::kReservedBitsSet,
                    {"reserved bits 3..1 of b7", "measurement response"});
  }
}

TEST(Decode, IgnoresBytesBeyondTheDlc) {
  CanFrame frame = make_frame(0x180, {0x03, 0x01, 0x2C});
  frame.data[5] = 0xAA;
  const DecodeResult result = decode(frame);
  ASSERT_TRUE(result.ok()) << result.error().reason;
  const Message expected = ControlRequest{3, true, true, 300};
  EXPECT_EQ(result.message(), expected);
}

TEST(Decode, ErrorCodesHaveStableNames) {
  EXPECT_STREQ(error_code_name(DecodeErrorCode::kWrongDlc), "wrong_dlc");
  EXPECT_STREQ(error_code_name(DecodeErrorCode::kReservedBitsSet), "reserved_bits_set");
}

// A legal frame of the variant alternative `index`, built from random bytes with only the bits
// the layout forbids cleared — independent of encode.
CanFrame random_legal_frame(std::mt19937& rng, std::size_t index) {
  const std::uint8_t node = index < 4 ? test::u8(rng, 0, 7) : 8;
  CanFrame frame;
  frame.id = can_id(node, static_cast<std::uint8_t>(index % 4));
  frame.dlc = std::vector<std::uint8_t>{3, 8, 5, 2, 8, 8, 1, 0}[index];
  for (std::size_t i = 0; i < frame.dlc; ++i) {
    frame.data[i] = test::u8(rng);
  }
  if (index == 0) {
    frame.data[0] &= 0x03;  // drv, eim
    frame.data[1] &= 0x07;  // pwm ≤ 2047
  } else if (index == 2) {
    const std::uint16_t icr = test::u16(rng, kMinIcr, kMaxIcr);
    const std::uint16_t pwm = test::u16(rng, 0, icr);
    frame.data = {static_cast<std::uint8_t>(icr >> 8), static_cast<std::uint8_t>(icr & 0xFF),
                  static_cast<std::uint8_t>(pwm >> 8), static_cast<std::uint8_t>(pwm & 0xFF),
                  frame.data[4], 0, 0, 0};
  } else if (index == 4) {
    for (std::size_t i = 0; i < 8; ++i) {
      const std::uint8_t led = i < 2 ? static_cast<std::uint8_t>(test::u8(rng, 0, 1) << 7) : 0;
      frame.data[i] = static_cast<std::uint8_t>(led | test::u8(rng, 32, 127));
    }
  } else if (index == 5) {
    frame.data[7] &= 0xF1;  // bits 3..1 reserved
  }
  return frame;
}

// encode(decode(f)) == f for legal frames, and any frame decode accepts re-encodes to itself.
TEST(Decode, LegalFramesReencodeToTheSameBytes) {
  std::mt19937 rng(0x3A2B);
  for (std::size_t index = 0; index < 8; ++index) {
    for (int iteration = 0; iteration < 2000; ++iteration) {
      const CanFrame frame = random_legal_frame(rng, index);
      const DecodeResult result = decode(frame);
      ASSERT_TRUE(result.ok()) << result.error().reason;
      ASSERT_EQ(result.message().index(), index);
      ASSERT_EQ(encode(result.message()), frame);
    }
  }
}

TEST(Decode, AnyAcceptedRandomFrameReencodesToItself) {
  std::mt19937 rng(0x80);
  int accepted = 0;
  for (int iteration = 0; iteration < 20000; ++iteration) {
    CanFrame frame;
    frame.id = static_cast<std::uint32_t>(test::u16(rng, 0, 0x7FF) & ~7U);  // no low-bit noise
    frame.dlc = test::u8(rng, 0, 8);
    for (std::size_t i = 0; i < frame.dlc; ++i) {
      frame.data[i] = test::u8(rng);
    }
    const DecodeResult result = decode(frame);
    if (result.ok()) {
      ++accepted;
      ASSERT_EQ(encode(result.message()), frame);
    } else {
      ASSERT_FALSE(result.error().reason.empty());
    }
  }
  EXPECT_GT(accepted, 100);
}

}  // namespace
}  // namespace marsokhod::protocol
