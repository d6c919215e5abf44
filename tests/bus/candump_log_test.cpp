#include "bus/candump_log.hpp"

#include <gtest/gtest.h>

#include <random>

namespace marsokhod::bus {
namespace {

LoggedFrame frame_of(std::string_view line) {
  auto parsed = parse_candump_line(line);
  if (auto* e = std::get_if<LogParseError>(&parsed)) ADD_FAILURE() << line << ": " << e->reason;
  if (auto* f = std::get_if<LoggedFrame>(&parsed)) return *f;
  return {};
}

std::string error_of(std::string_view line) {
  auto parsed = parse_candump_line(line);
  if (auto* e = std::get_if<LogParseError>(&parsed)) return e->reason;
  ADD_FAILURE() << line << " was accepted";
  return "";
}

TEST(CandumpLog, ParsesTheIssueExample) {
  // µ8's measurement request: idt 0x80 → CAN ID 0x400.
  const LoggedFrame f = frame_of("(1436509052.249713) can0 400#C142434445464748");
  EXPECT_EQ(f.timestamp, "1436509052.249713");
  EXPECT_DOUBLE_EQ(f.time_s, 1436509052.249713);
  EXPECT_EQ(f.interface, "can0");
  EXPECT_EQ(f.frame.id, 0x400u);
  EXPECT_FALSE(f.extended);
}

TEST(CandumpLog, ParsesDataBytes) {
  const LoggedFrame f = frame_of("(0.000100) vcan0 180#03012C");
  EXPECT_EQ(f.frame.id, 0x180u);
  ASSERT_EQ(f.frame.dlc, 3);
  EXPECT_EQ(f.frame.data[0], 0x03);
  EXPECT_EQ(f.frame.data[1], 0x01);
  EXPECT_EQ(f.frame.data[2], 0x2C);
}

TEST(CandumpLog, EmptyDataAndRemoteFrames) {
  EXPECT_EQ(frame_of("(1.0) can0 418#").frame.dlc, 0);
  const LoggedFrame r = frame_of("(1.0) can0 418#R");
  EXPECT_TRUE(r.remote);
  EXPECT_EQ(frame_of("(1.0) can0 418#R3").frame.dlc, 3);
}

TEST(CandumpLog, ExtendedIdentifier) {
  const LoggedFrame f = frame_of("(2.5) can0 12345678#00");
  EXPECT_TRUE(f.extended);
  EXPECT_EQ(f.frame.id, 0x12345678u);
}

TEST(CandumpLog, AcceptsPythonCanDirectionFlag) {
  // can.CanutilsLogWriter (python-can 4) ends every line with " R" (received) or " T" (sent).
  const LoggedFrame received = frame_of("(1.500000) can0 188#0001000200030004 R");
  EXPECT_EQ(received.frame.id, 0x188u);
  EXPECT_EQ(received.frame.dlc, 8);
  EXPECT_EQ(frame_of("(1.500000) can0 418# T").frame.dlc, 0);
  EXPECT_EQ(frame_of("(1.500000) can0 418#R T").remote, true);
  EXPECT_EQ(error_of("(1.0) can0 180#00 X"),
            "unexpected 'X' after the frame; only a direction R or T may follow it");
}

TEST(CandumpLog, BlankAndCommentLinesAreNotFrames) {
  EXPECT_TRUE(std::holds_alternative<std::monostate>(parse_candump_line("")));
  EXPECT_TRUE(std::holds_alternative<std::monostate>(parse_candump_line("   ")));
  EXPECT_TRUE(std::holds_alternative<std::monostate>(parse_candump_line("# recorded on Marsokhod")));
}

TEST(CandumpLog, RejectsMalformedLines) {
  EXPECT_EQ(error_of("can0 180#00"), "expected '(time) interface ID#DATA'");
  EXPECT_EQ(error_of("1.0 can0 180#00"),
            "expected a timestamp in parentheses, e.g. (1436509052.249713), got '1.0'");
  EXPECT_EQ(error_of("(abc) can0 180#00"),
            "timestamp 'abc' is not a finite, non-negative number of seconds");
  // from_chars reads these; a trace's time never is one.
  EXPECT_EQ(error_of("(nan) can0 180#00"),
            "timestamp 'nan' is not a finite, non-negative number of seconds");
  EXPECT_EQ(error_of("(inf) can0 180#00"),
            "timestamp 'inf' is not a finite, non-negative number of seconds");
  EXPECT_EQ(error_of("(1e999) can0 180#00"),
            "timestamp '1e999' is not a finite, non-negative number of seconds");
  EXPECT_EQ(error_of("(1.0) can0 18000"), "frame '18000' has no '#' between identifier and data");
  EXPECT_EQ(error_of("(1.0) can0 18#00"),
            "identifier '18' must have 3 hex digits (standard) or 8 (extended)");
  EXPECT_EQ(error_of("(1.0) can0 1G0#00"), "identifier '1G0' is not hexadecimal");
  EXPECT_EQ(error_of("(1.0) can0 800#00"), "standard identifier 0x800 exceeds 0x7FF");
  EXPECT_EQ(error_of("(1.0) can0 180#0"), "data '0' has an odd number of hex digits");
  EXPECT_EQ(error_of("(1.0) can0 180#0Z"), "data '0Z' is not hexadecimal");
  EXPECT_EQ(error_of("(1.0) can0 180#000102030405060708"),
            "data has 9 bytes; classic CAN carries at most 8");
  EXPECT_EQ(error_of("(1.0) can0 180##100"), "CAN FD frames (##) are not supported");
}

TEST(CandumpLog, ARemoteFramesLengthSurvivesTheRoundTrip) {
  const auto parsed = parse_candump_line("(1.5) can0 090#R6");
  const auto* logged = std::get_if<LoggedFrame>(&parsed);
  ASSERT_NE(logged, nullptr);
  EXPECT_TRUE(logged->remote);
  EXPECT_EQ(logged->frame.dlc, 6);
  EXPECT_EQ(format_candump_line(*logged), "(1.5) can0 090#R6");
  EXPECT_EQ(format_candump_line(std::get<LoggedFrame>(parse_candump_line("(1.5) can0 090#R"))),
            "(1.5) can0 090#R");
}

TEST(CandumpLog, FormatParseRoundTrip) {
  std::mt19937 rng(20081);
  for (int n = 0; n < 2000; ++n) {
    LoggedFrame f;
    f.timestamp = std::to_string(rng() % 100000) + "." + std::to_string(100000 + rng() % 900000);
    f.interface = (rng() % 2) ? "can0" : "vcan1";
    f.extended = rng() % 4 == 0;
    f.frame.id = f.extended ? rng() % 0x20000000u : rng() % 0x800u;
    f.frame.dlc = static_cast<std::uint8_t>(rng() % 9);
    for (std::size_t i = 0; i < f.frame.dlc; ++i) f.frame.data[i] = static_cast<std::uint8_t>(rng());
    const std::string line = format_candump_line(f);
    const LoggedFrame back = frame_of(line);
    EXPECT_EQ(back.timestamp, f.timestamp) << line;
    EXPECT_EQ(back.interface, f.interface) << line;
    EXPECT_EQ(back.extended, f.extended) << line;
    EXPECT_EQ(back.frame, f.frame) << line;
    EXPECT_EQ(format_candump_line(back), line);
  }
}

}  // namespace
}  // namespace marsokhod::bus
