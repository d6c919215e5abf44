// runner/joint_memory_file.hpp: the kept joint state as JSON round-trips exactly, the file of
// `drive --joint-memory` is found when recent and ignored when stale, and a damaged file is an
// error naming the file and the field.
#include "runner/joint_memory_file.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::ScratchFolder;

driver::JointMemory sample() {
  driver::JointMemory m;
  m.joints[0] = {{65535, 12, true}, -2.4600498747938166, -2.4312345678901234, -0.0411, 0.0};
  m.joints[1] = {{0, 40000, false}, 1.2864999999999999, 1.2602, 0.0, 0.012349999999999999};
  return m;
}

TEST(JointMemoryFile, JsonRoundTripsBitForBit) {
  const driver::JointMemory m = sample();
  EXPECT_EQ(joint_memory_from_json(joint_memory_json(m), "test"), m);
  driver::JointMemory unknown = m;
  unknown.known = false;
  EXPECT_EQ(joint_memory_from_json(nlohmann::json::parse(joint_memory_json(unknown).dump()), "t"),
            unknown);
}

TEST(JointMemoryFile, ARecentFileIsLoadedAndAStaleOneIgnored) {
  const ScratchFolder folder;
  JointMemoryFile file(folder.path() / "joints.json", 300.0);
  std::string note;
  EXPECT_FALSE(file.load(1000.0, note).has_value());
  EXPECT_NE(note.find("none in "), std::string::npos) << note;
  file.keep(std::nullopt, 1000.0);  // nothing known yet: nothing written
  EXPECT_FALSE(std::filesystem::exists(file.path()));
  file.keep(sample(), 1000.0);
  const auto loaded = file.load(1030.0, note);
  ASSERT_TRUE(loaded.has_value()) << note;
  EXPECT_EQ(*loaded, sample());
  EXPECT_EQ(note.rfind("30 s old from ", 0), 0U) << note;
  EXPECT_FALSE(file.load(1301.0, note).has_value());
  EXPECT_NE(note.find("stale (301 s old"), std::string::npos) << note;
  // An unchanged state is written again after max_age/4, so that a still rover's stays recent.
  file.keep(sample(), 1074.0);
  EXPECT_FALSE(file.load(1301.0, note).has_value());
  file.keep(sample(), 1076.0);
  EXPECT_TRUE(file.load(1301.0, note).has_value()) << note;
}

TEST(JointMemoryFile, ADamagedFileNamesTheFileAndTheField) {
  const ScratchFolder folder;
  const auto path = folder.write("joints.json",
                                 R"({"written_unix_s": 10, "known": true, "joints": [)"
                                 R"({"enc": 70000, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0},)"
                                 R"({"enc": 0, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0}]})");
  JointMemoryFile file(path, 300.0);
  std::string note;
  try {
    file.load(20.0, note);
    FAIL() << "a register out of range was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("joints[0].enc must be an integer in 0..65535"),
              std::string::npos)
        << e.what();
  }
  // A state kept before the driver counted its joints' uncertainty carries none; a negative one
  // is refused.
  folder.write("joints.json",
               R"({"written_unix_s": 10, "known": true, "joints": [)"
               R"({"enc": 7, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0},)"
               R"({"enc": 0, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0}]})");
  const auto old = file.load(20.0, note);
  ASSERT_TRUE(old.has_value()) << note;
  EXPECT_EQ(old->joints[0].uncertainty_rad, 0.0);
  EXPECT_EQ(old->joints[0].reading.enc, 7);
  folder.write("joints.json",
               R"({"written_unix_s": 10, "known": true, "joints": [)"
               R"({"enc": 7, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0},)"
               R"({"enc": 0, "stp": 0, "dir": false, "shaft_rad": 0, "joint_rad": 0, "duty": 0,)"
               R"( "uncertainty_rad": -0.01}]})");
  try {
    file.load(20.0, note);
    FAIL() << "a negative uncertainty was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("joints[1].uncertainty_rad must be a finite number ≥ 0"),
              std::string::npos)
        << e.what();
  }
  folder.write("joints.json", "{\"written_unix_s\": 10, \"known\": true}");
  EXPECT_THROW(file.load(20.0, note), std::runtime_error);
  folder.write("joints.json", "not json");
  EXPECT_THROW(file.load(20.0, note), std::runtime_error);
}

}  // namespace
}  // namespace marsokhod::runner
