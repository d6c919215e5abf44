#include "app/decode_command.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sstream>

namespace marsokhod::app {
namespace {

struct Decoded {
  int status = 0;
  std::string out;
  std::string err;
};

Decoded run(const std::string& trace, bool json = false) {
  std::istringstream in(trace);
  std::ostringstream out;
  std::ostringstream err;
  const Params params;  // the thesis' values, as config/marsokhod.toml
  const int status = decode_trace(in, "trace.log", params, DecodeOptions{json}, out, err);
  return {status, out.str(), err.str()};
}

TEST(DecodeCommand, ControlRequestShowsTheDutyCycle) {
  // 0x180 = idt 0x30 << 3: µ3, control request. Byte 0 = 0x03: drv = 1, eim = 1.
  // pwm = 0x012C = 300; d = (−1)^1 · 300/511 = −0.587.
  const Decoded d = run("(1436509052.249713) can0 180#03012C\n");
  EXPECT_EQ(d.status, 0);
  EXPECT_EQ(d.out, "1436509052.249713 can0 180 µ3 control_request drv=1 eim=1 pwm=300 d=-0.587\n");
  EXPECT_EQ(d.err, "");
}

TEST(DecodeCommand, ControlResponseShowsVelocityLikeFigure81) {
  // 0x188 = idt 0x31 << 3: µ3, control response. tim 0x1234 = 4660, enc 1, stp 2;
  // byte 6 = 0x02: dir 0, vel = 0x02FB = 763 pulses per T(0);
  // w = 763 · 25π/47104 = 1.272 rad/s (the FR speed of Figure 8.1); t = 4660/2 MHz = 0.002330 s.
  const Decoded d = run("(2.000000) can0 188#12340001000202FB\n");
  EXPECT_EQ(d.status, 0);
  EXPECT_EQ(d.out,
            "2.000000 can0 188 µ3 control_response tim=4660 enc=1 stp=2 dir=0 vel=763 "
            "t=0.002330 s enc_angle=0.0001 rad stp_angle=0.0001 rad w=+1.272 rad/s\n");
}

TEST(DecodeCommand, ConfigurationRequestChangesLaterConversions) {
  // µ3 configured with icr = 255 and con = 1: velocity halves per count (T doubles) and a
  // control request with pwm 300 > icr 255 is now rejected.
  const Decoded d = run(
      "(1.0) can0 190#00FF000001\n"
      "(1.1) can0 188#12340001000202FB\n"
      "(1.2) can0 180#00012C\n");
  EXPECT_EQ(d.status, 1);
  EXPECT_NE(d.out.find("µ3 configuration_request icr=255 pwm=0 con=1 f_pwm=31.250 kHz "
                       "d=+0.000 T=0.065536 s"),
            std::string::npos)
      << d.out;
  EXPECT_NE(d.out.find("w=+0.636 rad/s"), std::string::npos) << d.out;  // 1.272 / 2
  EXPECT_NE(d.err.find("trace.log:3: "), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("300"), std::string::npos) << d.err;
}

TEST(DecodeCommand, MeasurementResponseAtTypicalReadings) {
  // TYP readings of chapter 3.3 split into high 8 / low 2 bits (docs/design.md):
  // yaw 505 → 0x7E,1; acc 279 → 0x45,3; 251 → 0x3E,3; 376 → 0x5E,0; tltᶠ 527 → 0x83,3;
  // vcc 970 → 0xF2,2; b6 = 01 11 11 00 = 0x7C; b7 = 11 10 000 0 = 0xE0 (j = 0: front tilt).
  // (3.5): a = (0, 9.81/263 = 0.04, −9.81); θf = 0.00495·527 − 2.61 = −0.001;
  // U = 0.06768·970 − 41.0823 = 24.57 V; ω3 = 0.0170·(505 − 505) = 0.
  const Decoded d = run("(3.0) can0 408#7E453E5E83F27CE0\n");
  EXPECT_EQ(d.status, 0);
  EXPECT_EQ(d.out,
            "3.0 can0 408 µ8 measurement_response yaw=505 acc1=279 acc2=251 acc3=376 tltf=527 "
            "j=0 vcc=970 omega3=+0.000 rad/s a1=+0.00 m/s^2 a2=+0.04 m/s^2 a3=-9.81 m/s^2 "
            "theta_f=-0.001 rad U=24.57 V\n");
}

TEST(DecodeCommand, MeasurementRequestAndDeadMan) {
  // 0x400: µ8 measurement request; 0xC1 = led⁰ on + 'A', 0x42 = led¹ off + 'B'.
  // 0x410: dead man's switch, dog 4 → 4 · 0.262144 s = 1.049 s.
  const Decoded d = run("(4.0) can0 400#C142434445464748\n(4.1) can0 410#04\n(4.2) can0 418#\n");
  EXPECT_EQ(d.status, 0);
  EXPECT_EQ(d.out,
            "4.0 can0 400 µ8 measurement_request led0=1 led1=0 lcd=\"ABCDEFGH\"\n"
            "4.1 can0 410 µ8 dead_man_request dog=4 timeout=1.049 s\n"
            "4.2 can0 418 µ8 dead_man_response\n");
}

TEST(DecodeCommand, InvalidLinesAreReportedWithTheirNumberAndDecodingGoesOn) {
  const Decoded d = run(
      "(1.0) can0 180#03012C\n"
      "not a frame\n"
      "(1.1) can0 181#03012C\n"
      "(1.2) can0 12345678#00\n"
      "\n"
      "(1.3) can0 180#0301\n"
      "(1.4) can0 180#00012C\n");
  EXPECT_EQ(d.status, 1);
  std::istringstream out(d.out);
  std::string line;
  int frames = 0;
  while (std::getline(out, line)) ++frames;
  EXPECT_EQ(frames, 2);  // lines 1 and 7
  EXPECT_NE(d.err.find("trace.log:2: expected a timestamp in parentheses, e.g. (1436509052.249713), got 'not'\n"), std::string::npos)
      << d.err;
  EXPECT_NE(d.err.find("trace.log:3: "), std::string::npos) << d.err;  // low id bits set
  EXPECT_NE(d.err.find("trace.log:4: extended frame"), std::string::npos) << d.err;
  EXPECT_NE(d.err.find("trace.log:6: "), std::string::npos) << d.err;  // DLC 2 for 0xi0
  EXPECT_EQ(d.err.find("trace.log:5:"), std::string::npos);
  EXPECT_EQ(d.err.find("trace.log:7:"), std::string::npos);
}

TEST(DecodeCommand, JsonHasEveryFieldByItsThesisName) {
  const Decoded d = run("(2.000000) can0 188#12340001000282FB\n", true);
  ASSERT_EQ(d.status, 0) << d.err;
  // Byte 6 = 0x82 = 0x80 | 0x02: dir = 1, vel = 763 → w = −1.272 rad/s.
  const auto j = nlohmann::json::parse(d.out);
  EXPECT_EQ(j["node"], 3);
  EXPECT_EQ(j["type"], "control_response");
  EXPECT_EQ(j["id"], 0x188);
  EXPECT_EQ(j["timestamp"], "2.000000");
  EXPECT_EQ(j["tim"], 4660);
  EXPECT_EQ(j["enc"], 1);
  EXPECT_EQ(j["stp"], 2);
  EXPECT_EQ(j["dir"], 1);
  EXPECT_EQ(j["vel"], 763);
  EXPECT_NEAR(j["w_radps"].get<double>(), -763 * 25 * 3.14159265358979 / 47104, 1e-12);
}

}  // namespace
}  // namespace marsokhod::app
