// recording.mcap of a scenario's --out (mcap_recording.hpp) and `export-mcap` (export_mcap.hpp):
// every channel, its counts against can.log, operator.jsonl and telemetry.csv, a few values, the
// same bytes for the same seed, and the channels an export rebuilds from an old recording.
#include "runner/mcap_recording.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mcap_test_reader.hpp"
#include "runner/export_mcap.hpp"
#include "runner/scenario_runner.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::kConfigFile;
using testing::ScratchFolder;
using testing::shipped_params;
using Json = nlohmann::json;

constexpr const char* kScenario = R"(
duration_s = 4.5
[[input]]
t = 0.0
targets = { v1 = 0.0 }
[[input]]
t = 2.5
targets = { v1 = 1.5, v2 = 0.3 }
[[input]]
t = 3.5
targets = { gait = "worm-like", gait_speed = 0.5 }
)";

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::filesystem::path record(const std::filesystem::path& folder) {
  const Scenario scenario =
      load_scenario(ScratchFolder::write_to(folder, "mcap.toml", kScenario));
  RunOptions options;
  options.out = folder / "run";
  options.config_file = kConfigFile;
  options.plots = false;
  run_scenario(scenario, shipped_params(), options);
  return folder / "run";
}

// Messages by topic.
std::map<std::string, std::vector<test::Message>> by_topic(const test::McapFile& f) {
  std::map<std::string, std::vector<test::Message>> out;
  for (const test::Message& m : f.messages) out[f.channels.at(m.channel).at("topic")].push_back(m);
  return out;
}

std::vector<std::string> column(const std::filesystem::path& csv, const std::string& name) {
  const auto lines = lines_of(csv);
  std::vector<std::string> header;
  std::stringstream h(lines.at(0));
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const auto index = static_cast<std::size_t>(
      std::find(header.begin(), header.end(), name) - header.begin());
  EXPECT_LT(index, header.size()) << name;
  std::vector<std::string> out;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::stringstream row(lines[i]);
    std::string cell;
    for (std::size_t k = 0; k <= index; ++k) std::getline(row, cell, ',');
    out.push_back(cell);
  }
  return out;
}

TEST(McapRecording, AScenarioRecordsEveryChannel) {
  const ScratchFolder folder;
  const auto run = record(folder.path());
  const test::McapFile f = test::read_mcap(bytes_of(run / "recording.mcap"));
  EXPECT_EQ(f.library, "marsokhod");
  std::set<std::string> topics;
  for (const auto& [id, channel] : f.channels) {
    topics.insert(channel.at("topic"));
    EXPECT_EQ(channel.at("encoding"), "json");
    const auto& schema = f.schemas.at(static_cast<std::uint16_t>(std::stoi(channel.at("schema"))));
    EXPECT_EQ(schema.at("encoding"), "jsonschema");
    EXPECT_EQ(Json::parse(schema.at("data")).at("type"), "object");
  }
  EXPECT_EQ(topics, (std::set<std::string>{"/status", "/imu", "/joint_states", "/pose",
                                           "/pose/estimate", "/can/raw", "/can/decoded",
                                           "/operator/input", "/operator/runtime", "/tf",
                                           "/tf/links"}));
  const auto topic = by_topic(f);
  const auto can = lines_of(run / "can.log");
  const auto cycles = lines_of(run / "operator.jsonl");
  EXPECT_EQ(topic.at("/can/raw").size(), can.size());
  EXPECT_EQ(topic.at("/can/decoded").size(), can.size());
  EXPECT_EQ(topic.at("/status").size(), cycles.size());
  EXPECT_EQ(topic.at("/tf").size(), cycles.size());
  EXPECT_EQ(topic.at("/tf/links").size(), cycles.size());
  EXPECT_EQ(topic.at("/operator/runtime").size(), 1u);
  std::size_t inputs = 0;
  for (const std::string& line : cycles) inputs += Json::parse(line).at("input").is_null() ? 0 : 1;
  EXPECT_EQ(topic.at("/operator/input").size(), inputs);

  // Values against telemetry.csv, cycle by cycle; log time = mission time in ns.
  const auto t = column(run / "telemetry.csv", "t_s");
  const auto supply = column(run / "telemetry.csv", "supply_v");
  const auto p6 = column(run / "telemetry.csv", "AF_p_rad");
  const auto true_x = column(run / "telemetry.csv", "true_x_m");
  const auto true_p6 = column(run / "telemetry.csv", "true_p6_rad");
  ASSERT_EQ(t.size(), cycles.size());
  // /tf/links: the front lever turns about y by the true p6 (from its layout value, which the
  // joint's origin takes back: compare changes).
  const auto lever_angle = [&](std::size_t k) {
    const Json links = Json::parse(topic.at("/tf/links")[k].data);
    for (const Json& transform : links.at("transforms")) {
      if (transform.at("child_frame_id") != "front_lever") continue;
      EXPECT_EQ(transform.at("parent_frame_id"), "front_strut");
      const Json& q = transform.at("rotation");
      return 2.0 * std::atan2(q.at("y").get<double>(), q.at("w").get<double>());
    }
    ADD_FAILURE() << "no front_lever in /tf/links";
    return 0.0;
  };
  for (std::size_t k = 0; k < cycles.size(); k += 37) {
    const Json status = Json::parse(topic.at("/status")[k].data);
    EXPECT_EQ(topic.at("/status")[k].log_time, static_cast<std::uint64_t>(std::llround(std::stod(t[k]) * 1e9)));
    EXPECT_NEAR(status.at("mission_time_s").get<double>(), std::stod(t[k]), 1e-9);
    EXPECT_NEAR(status.at("supply_v").get<double>(), std::stod(supply[k]), 1e-6);
    EXPECT_TRUE(status.contains("truth"));
    const Json joints = Json::parse(topic.at("/joint_states")[k].data);
    EXPECT_EQ(joints.at("name")[6], "joint_AF");
    EXPECT_NEAR(joints.at("position")[6].get<double>(), std::stod(p6[k]), 1e-6);
    const Json tf = Json::parse(topic.at("/tf")[k].data);
    EXPECT_EQ(tf.at("child_frame_id"), "base_link");
    EXPECT_NEAR(tf.at("translation").at("x").get<double>(), std::stod(true_x[k]), 1e-6);
    EXPECT_NEAR(lever_angle(k) - lever_angle(0), std::stod(true_p6[k]) - std::stod(true_p6[0]), 1e-6);
  }
  // Every frame of can.log at its bus time, in the same order.
  for (std::size_t i = 0; i < can.size(); i += 101) {
    const Json raw = Json::parse(topic.at("/can/raw")[i].data);
    const std::string stamp = can[i].substr(1, can[i].find(')') - 1);
    EXPECT_EQ(raw.at("timestamp"), stamp);
    EXPECT_NE(can[i].find("#" + raw.at("data").get<std::string>()), std::string::npos) << can[i];
    EXPECT_EQ(Json::parse(topic.at("/can/decoded")[i].data).at("timestamp"), stamp);
  }
}

TEST(McapRecording, TheSameSeedGivesTheSameBytes) {
  const ScratchFolder a, b;
  const std::string first = bytes_of(record(a.path()) / "recording.mcap");
  EXPECT_GT(first.size(), 100000u);
  EXPECT_EQ(first, bytes_of(record(b.path()) / "recording.mcap"));
}

TEST(McapRecording, ExportRebuildsTheChannelsFromTheRecording) {
  const ScratchFolder folder;
  const auto run = record(folder.path());
  const test::McapFile live = test::read_mcap(bytes_of(run / "recording.mcap"));
  EXPECT_THROW(export_mcap(run, shipped_params()), std::runtime_error);  // exists
  std::filesystem::rename(run / "recording.mcap", folder.path() / "live.mcap");
  const ExportResult r = export_mcap(run, shipped_params());
  EXPECT_TRUE(r.identical) << r.first_difference;
  EXPECT_TRUE(r.true_pose);
  EXPECT_EQ(r.cycles, lines_of(run / "operator.jsonl").size());
  const test::McapFile exported = test::read_mcap(bytes_of(run / "recording.mcap"));
  EXPECT_FALSE(std::filesystem::exists(run / "recording.mcap.partial"));
  const auto a = by_topic(live);
  const auto b = by_topic(exported);
  for (const char* name : {"/can/raw", "/can/decoded", "/imu", "/joint_states", "/pose",
                           "/pose/estimate", "/operator/input", "/operator/runtime"}) {
    ASSERT_EQ(a.at(name).size(), b.at(name).size()) << name;
    for (std::size_t i = 0; i < a.at(name).size(); ++i) {
      EXPECT_EQ(a.at(name)[i].data, b.at(name)[i].data) << name << " " << i;
      EXPECT_EQ(a.at(name)[i].log_time, b.at(name)[i].log_time) << name << " " << i;
    }
  }
  // /status without the simulator's truth, else the same; /tf from telemetry.csv's 9 digits.
  ASSERT_EQ(a.at("/status").size(), b.at("/status").size());
  Json live_status = Json::parse(a.at("/status").back().data);
  live_status.erase("truth");
  EXPECT_EQ(live_status, Json::parse(b.at("/status").back().data));
  ASSERT_EQ(a.at("/tf").size(), b.at("/tf").size());
  const Json tf_live = Json::parse(a.at("/tf").back().data);
  const Json tf_export = Json::parse(b.at("/tf").back().data);
  EXPECT_NEAR(tf_live["translation"]["x"].get<double>(), tf_export["translation"]["x"].get<double>(), 1e-6);
  EXPECT_NEAR(tf_live["rotation"]["w"].get<double>(), tf_export["rotation"]["w"].get<double>(), 1e-6);
}

TEST(McapRecording, ExportRefusesWhatIsNoRecording) {
  const ScratchFolder folder;
  try {
    export_mcap(folder.path(), shipped_params());
    FAIL() << "exported an empty folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no can.log: not a recording"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(export_mcap(folder.path() / "missing", shipped_params()), std::runtime_error);
  // A broken line names its file and line, and leaves no recording.mcap behind.
  folder.write("can.log", "(0.000000) can0 180#03012C\nnot a frame\n");
  folder.write("operator.jsonl", "{\"t\":\"0.000000\",\"rx\":0,\"tx\":2,\"running\":true,\"input\":null}\n");
  try {
    export_mcap(folder.path(), shipped_params());
    FAIL() << "exported a broken can.log";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("can.log:2"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "recording.mcap"));
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "recording.mcap.partial"));
}

TEST(JsonSchemaOf, DescribesTheShapeOfAValue) {
  const Json schema = json_schema_of(Json::parse(R"({"a":1.5,"b":[1,2],"c":"x","d":null,"e":{"f":true}})"));
  EXPECT_EQ(schema.dump(),
            R"({"properties":{"a":{"type":"number"},"b":{"items":{"type":"number"},"type":"array"},)"
            R"("c":{"type":"string"},"d":{},"e":{"properties":{"f":{"type":"boolean"}},"type":"object"}},)"
            R"("type":"object"})");
}

}  // namespace
}  // namespace marsokhod::runner
