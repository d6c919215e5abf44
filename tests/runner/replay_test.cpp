// A scenario's recording (recorder.hpp) and `marsokhod replay` (replay.hpp): the recording
// replays bit for bit, a tampered one does not, its telemetry has what the plots read, and a
// CAN tool nobody here wrote (python-can) reads its can.log.
#include "runner/replay.hpp"
#include "link/command_json.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../bus/child_process.hpp"
#include "bus/candump_log.hpp"
#include "runner/scenario_runner.hpp"
#include "runner/telemetry.hpp"
#include "runner_test_support.hpp"

namespace marsokhod::runner {
namespace {

using testing::kConfigFile;
using testing::kSourceDir;
using testing::ScratchFolder;
using testing::shipped_params;

// Start-up, a second of driving, a gait step and a fault cleared: the driver sends every kind of
// request.
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
[[check]]
metric = "driver_faults"
max = 0
)";

std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Records kScenario into `folder` and returns the result.
ScenarioResult record(const std::filesystem::path& folder) {
  const Scenario scenario = load_scenario(ScratchFolder::write_to(folder, "replay.toml", kScenario));
  RunOptions options;
  options.out = folder / "run";
  options.config_file = kConfigFile;
  options.plots = false;
  return run_scenario(scenario, shipped_params(), options);
}

TEST(Replay, ARecordingReplaysBitForBit) {
  const ScratchFolder folder;
  const ScenarioResult r = record(folder.path());
  ASSERT_TRUE(r.passed);
  const auto run = folder.path() / "run";
  for (const char* file : {"can.log", "operator.jsonl", "telemetry.csv", "config.toml"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(run / file)) << file;
  }
  const ReplayResult replayed = replay(run, shipped_params());
  EXPECT_TRUE(replayed.identical) << replayed.first_difference;
  EXPECT_EQ(replayed.cycles, lines_of(run / "operator.jsonl").size());
  EXPECT_GT(replayed.frames_compared, 9u * 200u);  // 8 motor requests and µ8's, each cycle
}

TEST(Replay, ARestartAfterABrownOutReplaysWithTheKeptJointState) {
  // The recording says with which kept joint state the driver restarted (operator.jsonl's
  // "kept_joints" on that cycle), so that replay restarts it the same way.
  const ScratchFolder folder;
  const Scenario scenario = load_scenario(kSourceDir / "scenarios" / "brownout-mid-gait.toml");
  RunOptions options;
  options.out = folder.path() / "run";
  options.config_file = kConfigFile;
  options.plots = false;
  ASSERT_TRUE(run_scenario(scenario, shipped_params(), options).passed);
  int restarts = 0;
  for (const std::string& line : lines_of(folder.path() / "run" / "operator.jsonl")) {
    if (line.find("\"kept_joints\"") != std::string::npos) ++restarts;
  }
  EXPECT_EQ(restarts, 1);
  const ReplayResult replayed = replay(folder.path() / "run", shipped_params());
  EXPECT_TRUE(replayed.identical) << replayed.first_difference;
}

TEST(Replay, AStopKeepsItsReasonInTheRecording) {
  // The driver shows who stopped (DriverStatus::stop_reason): operator.jsonl keeps it, so a
  // replayed run holds the same stop for the same reason.
  driver::OperatorInput stop;
  stop.stop = true;
  stop.stop_reason = "client 3 pressed STOP; client 1 lost control";
  const nlohmann::json line = link::operator_input_json(stop);
  EXPECT_EQ(line["stop_reason"], stop.stop_reason);
  const driver::OperatorInput back = link::operator_input_from_json(line);
  EXPECT_TRUE(back.stop);
  EXPECT_EQ(back.stop_reason, stop.stop_reason);
  EXPECT_FALSE(link::operator_input_json(driver::OperatorInput{}).contains("stop_reason"));
}

TEST(Replay, ATamperedCanLogIsDifferent) {
  const ScratchFolder folder;
  record(folder.path());
  const auto can_log = folder.path() / "run" / "can.log";
  std::vector<std::string> lines = lines_of(can_log);
  // The last request to µ8 (idt 0x80, CAN ID 0x400): one bit of its LCD text flipped.
  std::size_t tampered = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find(" 400#") != std::string::npos) tampered = i;
  }
  ASSERT_LT(tampered, lines.size());
  char& last = lines[tampered].back();
  last = last == '0' ? '1' : '0';
  {
    std::ofstream out(can_log);
    for (const std::string& line : lines) out << line << '\n';
  }
  const ReplayResult replayed = replay(folder.path() / "run", shipped_params());
  EXPECT_FALSE(replayed.identical);
  EXPECT_NE(replayed.first_difference.find("400#"), std::string::npos) << replayed.first_difference;
}

// The columns plots.cpp's gnuplot script reads: "using "t_s":"supply_v"" and, in its loops over
// motors, "using "t_s":m."_duty"".
std::set<std::string> plotted_columns() {
  std::ifstream in(kSourceDir / "src" / "runner" / "plots.cpp");
  std::stringstream text;
  text << in.rdbuf();
  const std::string script = text.str();
  std::set<std::string> columns;
  const std::regex pair(R"re(using "([A-Za-z0-9_]+)":"([A-Za-z0-9_]+)")re");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), pair); it != std::sregex_iterator(); ++it) {
    columns.insert((*it)[1]);
    columns.insert((*it)[2]);
  }
  const std::regex loop(R"re(for \[m in "([A-Z ]+)"\] "telemetry.csv" using "([A-Za-z0-9_]+)":m\."([A-Za-z0-9_]+)")re");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), loop); it != std::sregex_iterator(); ++it) {
    columns.insert((*it)[2]);
    std::istringstream motors((*it)[1]);
    for (std::string motor; motors >> motor;) columns.insert(motor + std::string((*it)[3]));
  }
  return columns;
}

TEST(Replay, TelemetryHasTheColumnsThePlotsUse) {
  const std::set<std::string> wanted = plotted_columns();
  ASSERT_GE(wanted.size(), 15u) << "plots.cpp's script no longer matches this test's patterns";
  const ScratchFolder folder;
  record(folder.path());
  const std::vector<std::string> lines = lines_of(folder.path() / "run" / "telemetry.csv");
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines.front(), telemetry_header());
  std::set<std::string> header;
  std::istringstream cells(lines.front());
  for (std::string cell; std::getline(cells, cell, ',');) header.insert(cell);
  for (const std::string& column : wanted) EXPECT_TRUE(header.contains(column)) << column;
  for (const char* column : {"t_s", "true_x_m", "true_p6_rad", "true_p7_rad", "energy_j"}) {
    EXPECT_TRUE(header.contains(column)) << column;
  }
}

constexpr const char* kPython = "/usr/bin/python3";
constexpr std::chrono::milliseconds kPythonDeadline{60000};

TEST(Replay, PythonCanReadsTheCanLog) {
  if (::access(kPython, X_OK) != 0) GTEST_SKIP() << kPython << " not found: apt-get install python3";
  if (bus::testing::run_program({kPython, "-c", "import can"}, kPythonDeadline) != 0) {
    GTEST_SKIP() << "python-can is not installed for " << kPython << ": apt-get install python3-can";
  }
  const ScratchFolder folder;
  record(folder.path());
  const auto can_log = folder.path() / "run" / "can.log";
  const auto count_file = folder.path() / "count.txt";
  // can.LogReader picks python-can's CanutilsLogReader for a .log file.
  const char* script =
      "import can, sys\n"
      "n = sum(1 for m in can.LogReader(sys.argv[1]) if not m.is_extended_id)\n"
      "open(sys.argv[2], 'w').write(str(n))\n";
  ASSERT_EQ(bus::testing::run_program({kPython, "-c", script, can_log.string(), count_file.string()},
                                      kPythonDeadline),
            0);
  std::size_t ours = 0;
  for (const std::string& line : lines_of(can_log)) {
    ours += std::holds_alternative<bus::LoggedFrame>(bus::parse_candump_line(line)) ? 1 : 0;
  }
  ASSERT_GT(ours, 0u);
  EXPECT_EQ(std::to_string(ours), lines_of(count_file).at(0));
}

}  // namespace
}  // namespace marsokhod::runner
