// The scenario file format of runner/scenario.hpp: what it reads, and that every mistake names
// the key and its line.
#include "runner/scenario.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::ScratchFolder;

// The message load_scenario throws for `text`, or "" when it loads.
std::string error_of(const std::string& text) {
  const ScratchFolder folder;
  try {
    load_scenario(folder.write("broken.toml", text));
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

::testing::AssertionResult names(const std::string& message, const std::string& key, int line) {
  const std::string where = "(line " + std::to_string(line) + ")";
  if (message.find(key + ":") != std::string::npos && message.find(where) != std::string::npos &&
      message.find("broken.toml") != std::string::npos) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "expected the file, \"" << key << ":\" and \"" << where
                                       << "\" in: " << message;
}

TEST(Scenario, ReadsPhasesAndChecks) {
  const ScratchFolder folder;
  const Scenario s = load_scenario(folder.write("spin.toml", R"(
description = "two spins"
duration_s = 12.0
seed = 7
[[input]]
t = 1.0
targets = { v2 = 1.0, front_joint_target = -1.5 }
[[phase]]
name = "short"
from_s = 2.0
to_s = 5.5
[[phase]]
name = "long_2"
from_s = 6.0
to_s = 12.0
[[check]]
metric = "short.yaw_rate_mean_radps"
min = 0.1
[[check]]
name = "faster"
ratio_of = ["short.yaw_rate_mean_radps", "long_2.yaw_rate_mean_radps"]
min = 1.2
max = 9
)"));
  EXPECT_EQ(s.name, "spin");  // the file's name when the file gives none
  EXPECT_EQ(s.seed, 7u);
  ASSERT_EQ(s.phases.size(), 2u);
  EXPECT_EQ(s.phases[0].name, "short");
  EXPECT_EQ(s.phases[0].from_s, 2.0);
  EXPECT_EQ(s.phases[0].to_s, 5.5);
  ASSERT_EQ(s.checks.size(), 2u);
  EXPECT_EQ(s.checks[0].name, "short.yaw_rate_mean_radps");
  EXPECT_FALSE(s.checks[0].ratio_of);
  ASSERT_TRUE(s.checks[1].ratio_of);
  EXPECT_EQ(s.checks[1].ratio_of->first, "short.yaw_rate_mean_radps");
  EXPECT_EQ(s.checks[1].ratio_of->second, "long_2.yaw_rate_mean_radps");
  EXPECT_EQ(s.checks[1].metric, "short.yaw_rate_mean_radps / long_2.yaw_rate_mean_radps");
  EXPECT_EQ(*s.checks[1].min, 1.2);
  EXPECT_EQ(*s.checks[1].max, 9.0);
  ASSERT_EQ(s.inputs.size(), 1u);
  EXPECT_EQ(*s.inputs[0].input->targets->front_joint_target_rad, -1.5);
}

TEST(Scenario, AnUnknownTerrainKindNamesTheKeyAndLine) {
  const std::string e = error_of("duration_s = 5.0\n[terrain]\nkind = \"lava\"\n");
  EXPECT_NE(e.find("broken.toml: terrain"), std::string::npos) << e;
  EXPECT_NE(e.find("terrain.kind (line 3)"), std::string::npos) << e;
  EXPECT_NE(e.find("\"flat\""), std::string::npos) << e;  // what is allowed
}

TEST(Scenario, AnUnknownKeyNamesTheKeyAndLine) {
  EXPECT_TRUE(names(error_of("duration_s = 5.0\nspeed = 3\n"), "speed", 2));
  EXPECT_TRUE(names(error_of("[[check]]\nmetric = \"distance_m\"\nmaxx = 1.0\n"), "check[0].maxx", 3));
  EXPECT_TRUE(names(error_of("[[phase]]\nname = \"a\"\nfrom_s = 0.0\nto_s = 1.0\nuntil = 2.0\n"),
                    "phase[0].until", 5));
  EXPECT_TRUE(names(error_of("[[fault]]\nt = 1.0\nwheel_stuck = [0]\n"), "fault[0].wheel_stuck", 3));
}

TEST(Scenario, AnUnknownRuntimeSettingNamesTheKeyAndLine) {
  const std::string e = error_of("duration_s = 5.0\n[runtime]\nbehaviours = { slant = false }\n");
  EXPECT_TRUE(names(e, "runtime", 2));
  EXPECT_NE(e.find("runtime.behaviours.slant"), std::string::npos) << e;
  EXPECT_TRUE(names(error_of("[[runtime_change]]\nt = 1.0\nload_distribution = \"x\"\n"),
                    "runtime_change[0]", 1));
}

TEST(Scenario, ACheckWithoutAMetricNamesTheKeyAndLine) {
  EXPECT_TRUE(names(error_of("[[check]]\nname = \"far\"\nmin = 1.0\n"), "check[0].metric", 1));
  EXPECT_TRUE(names(error_of("[[check]]\nmetric = \"distance_m\"\n"), "check[0].min", 1));
}

TEST(Scenario, AnUnknownMetricNamesTheKeyAndLine) {
  const std::string e = error_of("[[check]]\nmetric = \"distance_km\"\nmin = 1.0\n");
  EXPECT_TRUE(names(e, "check[0].metric", 2));
  EXPECT_NE(e.find("distance_km"), std::string::npos) << e;
  // A phase metric needs its phase.
  EXPECT_TRUE(names(error_of("[[check]]\nmetric = \"climb.distance_m\"\nmin = 1.0\n"),
                    "check[0].metric", 2));
  EXPECT_TRUE(names(error_of("[[phase]]\nname = \"climb\"\nfrom_s = 0.0\nto_s = 1.0\n"
                             "[[check]]\nmetric = \"climb.top_speed_mps\"\nmin = 1.0\n"),
                    "check[0].metric", 6));
}

TEST(Scenario, ARatioNeedsTwoMetrics) {
  EXPECT_TRUE(names(error_of("[[check]]\nratio_of = [\"distance_m\"]\nmin = 1.0\n"),
                    "check[0].ratio_of", 2));
  EXPECT_TRUE(names(error_of("[[check]]\nmetric = \"distance_m\"\n"
                             "ratio_of = [\"distance_m\", \"climb_m\"]\nmin = 1.0\n"),
                    "check[0].ratio_of", 3));
  EXPECT_TRUE(names(error_of("[[check]]\nratio_of = [\"distance_m\", \"nothing\"]\nmin = 1.0\n"),
                    "check[0].ratio_of", 2));
}

TEST(Scenario, ABadFaultIndexNamesTheKeyAndLine) {
  const std::string e = error_of("[[fault]]\nt = 1.0\nwheel_blocked = [6]\n");
  EXPECT_TRUE(names(e, "fault[0].wheel_blocked", 3));
  EXPECT_NE(e.find("0..5"), std::string::npos) << e;
  EXPECT_TRUE(names(error_of("[[fault]]\nsilent = [9]\n"), "fault[0].silent", 2));
  const std::string joint = error_of("[[fault]]\njoint_jammed = [2]\n");  // 0 front, 1 rear
  EXPECT_TRUE(names(joint, "fault[0].joint_jammed", 2));
  EXPECT_NE(joint.find("0..1"), std::string::npos) << joint;
  EXPECT_TRUE(names(error_of("[[fault]]\nlost_pulses = { motor = 8, fraction = 0.5 }\n"),
                    "fault[0].lost_pulses", 2));
}

TEST(Scenario, BadPhasesNameTheKeyAndLine) {
  EXPECT_TRUE(names(error_of("duration_s = 5.0\n[[phase]]\nname = \"a\"\nfrom_s = 1.0\nto_s = 6.0\n"),
                    "phase[0].to_s", 2));
  EXPECT_TRUE(names(error_of("[[phase]]\nname = \"a\"\nfrom_s = 2.0\nto_s = 1.0\n"),
                    "phase[0].to_s", 1));
  EXPECT_TRUE(names(error_of("[[phase]]\nname = \"a.b\"\nfrom_s = 0.0\nto_s = 1.0\n"),
                    "phase[0].name", 1));
  EXPECT_TRUE(names(error_of("[[phase]]\nname = \"a\"\nfrom_s = 0.0\nto_s = 1.0\n"
                             "[[phase]]\nname = \"a\"\nfrom_s = 1.0\nto_s = 2.0\n"),
                    "phase[1].name", 5));
  EXPECT_TRUE(names(error_of("phase = 3\n"), "phase", 1));
}

TEST(Scenario, NaNOrInfinityAnywhereNamesTheKeyAndLine) {
  // toml reads nan and inf; none of them means anything in a scenario.
  EXPECT_TRUE(names(error_of("[[fault]]\nt = nan\n"), "fault[0].t", 2));
  EXPECT_TRUE(names(error_of("[sim]\nstate_of_charge = inf\n"), "sim.state_of_charge", 2));
  EXPECT_TRUE(names(error_of("[[fault]]\nt = 1.0\nbattery_sag_ohm = -inf\n"),
                    "fault[0].battery_sag_ohm", 3));
  EXPECT_TRUE(names(error_of("[[input]]\nt = 1.0\ntargets = { v1 = nan }\n"),
                    "input[0].targets.v1", 3));
  EXPECT_TRUE(names(error_of("[[input]]\nt = 1.0\ngamepad = { axes = [0.0, nan, 0.0, 0.0] }\n"),
                    "input[0].gamepad.axes[1]", 3));
  const std::string e = error_of("[[input]]\nt = nan\n");
  EXPECT_NE(e.find("is not a finite number"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;  // one line
}

TEST(Scenario, OutOfRangeFaultValuesNameTheKeyTheRangeAndTheLine) {
  std::string e = error_of("[[fault]]\nt = 1.0\nframe_loss = 1.5\n");
  EXPECT_TRUE(names(e, "fault[0].frame_loss", 3));
  EXPECT_NE(e.find("1.5 is out of range; allowed [0, 1]"), std::string::npos) << e;
  EXPECT_TRUE(names(error_of("[[fault]]\nt = 1.0\nbattery_sag_ohm = -0.5\n"),
                    "fault[0].battery_sag_ohm", 3));
  EXPECT_TRUE(names(error_of("[[fault]]\nlost_pulses = { motor = 2, fraction = 2.0 }\n"),
                    "fault[0].lost_pulses.fraction", 2));
  EXPECT_TRUE(names(error_of("duration_s = 5.0\n[[fault]]\nt = 9.0\n"), "fault[0].t", 3));
  EXPECT_TRUE(names(error_of("[sim]\nstate_of_charge = 1.2\n"), "sim.state_of_charge", 2));
}

TEST(Scenario, ANegativeSeedIsRefused) {
  EXPECT_TRUE(names(error_of("seed = -3\n"), "seed", 1));
  EXPECT_TRUE(names(error_of("seed = 1.5\n"), "seed", 1));
}

TEST(Scenario, ABadInputNamesItsLine) {
  const std::string e = error_of("[[input]]\nt = 1.0\ntargets = { gait = \"hop\" }\n");
  EXPECT_TRUE(names(e, "input[0]", 1));
  EXPECT_NE(e.find("hop"), std::string::npos) << e;
}

TEST(Scenario, ListsTheTomlFilesOfAFolderByName) {
  const ScratchFolder folder;
  folder.write("b.toml", "");
  folder.write("a.toml", "");
  folder.write("notes.txt", "");
  const auto listed = list_scenarios(folder.path());
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].first, "a");
  EXPECT_EQ(listed[1].first, "b");
  EXPECT_EQ(listed[1].second, folder.path() / "b.toml");
}

}  // namespace
}  // namespace marsokhod::runner
