#include "app/cli.hpp"
#include "cli_runner.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <thread>
#include <utility>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../runner/mcap_test_reader.hpp"
#include "bus/socketcand_server.hpp"
#include "config/load_params.hpp"
#include "runner/sweep.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::app {
namespace {

using test::cli;
using test::Result;

const std::string kConfig = std::string(MARSOKHOD_SOURCE_DIR) + "/config/marsokhod.toml";

TEST(Cli, DecodeFromStandardInput) {
  const Result r = cli({"--config", kConfig.c_str(), "decode", "-"}, "(1.0) can0 180#03012C\n");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "1.0 can0 180 µ3 control_request drv=1 eim=1 pwm=300 d=-0.587\n");
}

TEST(Cli, InvalidLineGivesExitStatusOne) {
  const Result r = cli({"--config", kConfig.c_str(), "decode", "-"}, "garbage\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "<stdin>:1: expected '(time) interface ID#DATA'\n");
}

TEST(Cli, MissingTraceFileIsAUsageError) {
  const Result r = cli({"--config", kConfig.c_str(), "decode", "/nonexistent/trace.log"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err,
            "marsokhod decode: cannot open '/nonexistent/trace.log': no such file or not readable\n");
}

TEST(Cli, UnknownSubcommandAndMissingArgumentsAreUsageErrors) {
  Result r = cli({"fly"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("marsokhod: "), std::string::npos);
  r = cli({"decode"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("FILE is required"), std::string::npos) << r.err;
  r = cli({});
  EXPECT_EQ(r.status, 2);
}

TEST(Cli, MissingConfigFileIsAUsageError) {
  const Result r = cli({"--config", "/nonexistent/marsokhod.toml", "decode", "-"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/nonexistent/marsokhod.toml"), std::string::npos) << r.err;
}

TEST(Cli, AnUnknownScenarioIsAOneLineUsageError) {
  const Result r = cli({"--config", kConfig.c_str(), "scenario", "no-such-scenario"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("'no-such-scenario'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("marsokhod scenario --list"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.back(), '\n');
}

TEST(Cli, ABrokenScenarioFileIsAUsageErrorNamingTheKey) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("marsokhod-cli-broken-" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file) << "duration_s = 5.0\n[[check]]\nmetric = \"distance_m\"\nmaxx = 1.0\n";
  const Result r = cli({"--config", kConfig.c_str(), "scenario", file.c_str()});
  std::filesystem::remove(file);
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("check[0].maxx: unknown key (line 4)"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(Cli, ANegativeSeedIsRefusedNotWrapped) {
  for (const char* command : {"scenario", "run", "sim", "slope-sweep"}) {
    std::vector<const char*> args = {"--config", kConfig.c_str(), command};
    if (std::string(command) == "scenario") args.push_back("straight-and-spin");
    args.push_back("--seed");
    args.push_back("-1");
    const Result r = cli(args);
    EXPECT_EQ(r.status, 2) << command;
    EXPECT_NE(r.err.find("-1 is negative; a seed is an integer ≥ 0"), std::string::npos)
        << command << ": " << r.err;
  }
}

TEST(Cli, ANaNInAScenarioIsAOneLineUsageError) {
  const auto file = std::filesystem::temp_directory_path() /
                    ("marsokhod-cli-nan-" + std::to_string(::getpid()) + ".toml");
  std::ofstream(file) << "duration_s = 5.0\n[[fault]]\nt = 1.0\nframe_loss = nan\n";
  const Result r = cli({"--config", kConfig.c_str(), "scenario", file.c_str()});
  std::filesystem::remove(file);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("fault[0].frame_loss: is not a finite number (line 4)"), std::string::npos)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// The slope sweep needs a soft soil (its angle of repose bounds the sweep) and sane numbers.
TEST(Cli, SlopeSweepRefusesRigidGroundAndBadNumbers) {
  Result r = cli({"--config", kConfig.c_str(), "slope-sweep", "--ground", "hard"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--ground hard is not a soft soil; use sand or lunar-soil"),
            std::string::npos)
      << r.err;
  // A retired name says what became of it, as a terrain file's material does.
  for (const auto& [name, note] :
       {std::pair{"soft-sand", "(\"soft-sand\" is now called \"sand\")"},
        {"rigid-sand",
         "(\"rigid-sand\", the rigid contact sand had before the soil model, is gone"}}) {
    r = cli({"--config", kConfig.c_str(), "slope-sweep", "--ground", name});
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find(std::string("--ground ") + name +
                         " is not a soft soil; use sand or lunar-soil " + note),
              std::string::npos)
        << r.err;
  }
  r = cli({"--config", kConfig.c_str(), "slope-sweep", "--drive", "3.0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("exceeds max_drive_speed_radps 2.25"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "slope-sweep", "--step", "0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--step"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "slope-sweep", "--time", "40", "--window", "25"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--window 25 is longer than half of --time 40"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "slope-sweep", "--window", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--window"), std::string::npos) << r.err;
}

// --modes sweeps the modes named, each once, in the order given; an unknown one is refused. Without
// driving the table says nothing of wheel walking against it. (Coarse steps and 1 s climbs: only
// the rows are looked at here.)
TEST(Cli, SlopeSweepSweepsTheModesNamed) {
  Result r = cli({"--config", kConfig.c_str(), "slope-sweep", "--modes", "rolking,walking"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--modes: unknown mode \"walking\"; use driving, rolking"),
            std::string::npos)
      << r.err;
  r = cli({"--config", kConfig.c_str(), "slope-sweep", "--modes", "worm-like,rolking,worm-like",
           "--step", "10", "--time", "1", "--distance", "0.001"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t worm = r.out.find("| worm-like |");
  const std::size_t rolking = r.out.find("| rolking |");
  EXPECT_NE(worm, std::string::npos) << r.out;
  EXPECT_NE(rolking, std::string::npos) << r.out;
  EXPECT_LT(worm, rolking) << r.out;
  EXPECT_EQ(r.out.find("| worm-like |", worm + 1), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("| driving |"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("out-climbs driving"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nothing climbed past the angle of repose: yes"), std::string::npos)
      << r.out;
}

// --shear-reload-memory climbs on the soil whose tangential shear reloads along the line it
// unloaded on, and says so in the table's heading; without it the heading says nothing of it.
TEST(Cli, SlopeSweepCanClimbWithTheShearsReloadMemory) {
  const std::vector<const char*> quick = {"--config", kConfig.c_str(), "slope-sweep", "--modes",
                                          "driving", "--step", "10", "--time", "1",
                                          "--distance", "0.001"};
  std::vector<const char*> with = quick;
  with.push_back("--shear-reload-memory");
  const Result on = cli(with);
  ASSERT_EQ(on.status, 0) << on.err;
  EXPECT_NE(on.out.find("slope sweep on sand with the shear's reload memory"), std::string::npos)
      << on.out;
  const Result off = cli(quick);
  ASSERT_EQ(off.status, 0) << off.err;
  EXPECT_EQ(off.out.find("reload memory"), std::string::npos) << off.out;
}

// CLI11's range checks compare, and every comparison with NaN is false: "--duration nan" ran
// without an end and "--distance nan" swept for nothing. Every real-valued option refuses a
// number that is not finite, naming the option, and one out of its bounds with the bounds.
TEST(Cli, RealValuedOptionsRefuseNaNAndInfinity) {
  struct Case {
    std::vector<const char*> words;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"run", "--duration", "nan"}, "--duration: nan is not a finite number"},
      {{"sim", "--duration", "inf"}, "--duration: inf is not a finite number"},
      {{"drive", "--can", "socketcan:vcan0", "--duration", "-nan"},
       "--duration: -nan is not a finite number"},
      {{"calibrate", "motor-scale", "--sim", "--duration", "nan"},
       "--duration: nan is not a finite number"},
      {{"run", "--status-rate", "nan"}, "--status-rate: nan is not a finite number"},
      {{"scenario", "straight-and-spin", "--physics-step-ms", "nan"},
       "--physics-step-ms: nan is not a finite number"},
      {{"slope-sweep", "--distance", "nan"}, "--distance: nan is not a finite number"},
      {{"slope-sweep", "--time", "inf"}, "--time: inf is not a finite number"},
      {{"slope-sweep", "--step", "nan"}, "--step: nan is not a finite number"},
      {{"slope-sweep", "--drive", "1e999"}, "--drive: 1e999 is not a finite number"},
      // Underflow is a number near 0, not an infinity: out of range here, not "not finite".
      {{"slope-sweep", "--distance", "1e-400"},
       "--distance: 1e-400 is out of range; a number in [0.001, 100]"},
      {{"slope-sweep", "--distance", "0"},
       "--distance: 0 is out of range; a number in [0.001, 100]"},
      {{"run", "--duration", "-1"}, "--duration: -1 is out of range; a finite number ≥ 0"},
      {{"calibrate", "motor-scale", "--sim", "--duration", "0"},
       "--duration: 0 is out of range; a finite number > 0"},
      {{"slope-sweep", "--distance", "abc"}, "--distance: abc is not a number"},
      {{"slope-sweep", "--distance", " 1"}, "--distance:  1 is not a number"},
      // A finite number inside the bounds passes on to the command (which refuses the ground).
      {{"slope-sweep", "--distance", "5e-1", "--ground", "hard"},
       "--ground hard is not a soft soil"},
  };
  for (const Case& c : cases) {
    std::vector<const char*> args = {"--config", kConfig.c_str()};
    args.insert(args.end(), c.words.begin(), c.words.end());
    const Result r = cli(args);
    EXPECT_EQ(r.status, 2) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.message << ": " << r.err;
  }
}

TEST(Cli, TheShippedScenariosAreListed) {
  const Result r = cli({"--config", kConfig.c_str(), "scenario", "--list"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("straight-and-spin  Figures 3.5/3.8"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dead-man  "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("(invalid"), std::string::npos) << r.out;
}

TEST(Cli, HelpListsTheCommands) {
  const Result r = cli({"--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("decode"), std::string::npos);
  EXPECT_NE(r.out.find("calibrate"), std::string::npos);
}

// A temporary folder of its own per test.
class CliCalibrate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("marsokhod-cli-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;
};

TEST_F(CliCalibrate, BadArgumentsAreOneLineUsageErrors) {
  Result r = cli({"--config", kConfig.c_str(), "calibrate", "voltmeter", "--sim"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no procedure 'voltmeter'; one of "), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--sim (the simulated rover) or --can URL"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--sim", "--can", "socketcan:can0"});
  EXPECT_EQ(r.status, 2);
  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--can", "tcp://rover"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("marsokhod calibrate voltage: "), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--sim", "--icr", "9"});
  EXPECT_EQ(r.status, 2);
  r = cli({"--config", kConfig.c_str(), "calibrate", "spin", "--sim", "--ground", "mud"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--ground mud is unknown; use hard, sand, grass or lunar-soil"),
            std::string::npos)
      << r.err;
  // A retired name says what became of it, as a terrain file's material does.
  r = cli({"--config", kConfig.c_str(), "calibrate", "spin", "--sim", "--ground", "rigid-sand"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("\"rigid-sand\", the rigid contact sand had before the soil model, is gone"),
            std::string::npos)
      << r.err;
  r = cli({"--config", kConfig.c_str(), "calibrate", "spin", "--sim", "--ground", "soft-sand"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("(\"soft-sand\" is now called \"sand\")"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "calibrate", "spin", "--can", "socketcan:can0",
           "--ground", "sand"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--ground is for the simulated rover (--sim) only"), std::string::npos)
      << r.err;
  r = cli({"--config", kConfig.c_str(), "--calibration", "/nonexistent.toml", "run"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/nonexistent.toml"), std::string::npos) << r.err;
}

TEST_F(CliCalibrate, WritesTheFileRefusesToOverwriteItAndTheDriverLoadsIt) {
  const std::string file = path("rover.toml");
  const std::string plots = path("plots");
  Result r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--sim", "--seed", "3",
                  "--out", file.c_str(), "--plot", plots.c_str()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Procedure 3.5 on simulator (seed 3, tether)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("supply_v_per_count = "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rms_residual_v = "), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(file));
  EXPECT_TRUE(std::filesystem::exists(path("plots/voltage.csv")));
  const auto written = std::filesystem::last_write_time(file);

  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--sim", "--seed", "4", "--out",
           file.c_str()});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("exists; pass --force"), std::string::npos) << r.err;
  EXPECT_EQ(std::filesystem::last_write_time(file), written);

  // The driver reports the calibration it runs with.
  r = cli({"--config", kConfig.c_str(), "--calibration", file.c_str(), "run", "--no-console",
           "--quiet", "--duration", "0.1"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("calibration: " + file + " (voltage)"), std::string::npos) << r.out;
  r = cli({"--config", kConfig.c_str(), "run", "--no-console", "--quiet", "--duration", "0.1"});
  EXPECT_NE(r.out.find("calibration: none (nominal configuration)"), std::string::npos) << r.out;
}

TEST_F(CliCalibrate, ARecordingKeepsTheCalibrationAndReplaysBitForBit) {
  // A calibration that changes what the driver sends: ζ of every motor 3 % up.
  const std::string file = path("zeta.toml");
  std::ofstream(file) << "[motors]\nscale = [1.02, 1.01, 1.0, 0.97, 1.0, 1.0, 1.01, 1.0]\n";
  const std::string scenario = path("short.toml");
  std::ofstream(scenario) << "name = \"short\"\ndescription = \"a short drive\"\n"
                             "duration_s = 4.0\nseed = 2\n[terrain]\nkind = \"flat\"\n"
                             "material = \"hard\"\n[[input]]\nt = 0.0\n"
                             "targets = { v1 = 0.0 }\n[[input]]\nt = 2.0\n"
                             "targets = { v1 = 1.0 }\n";
  const std::string out = path("run");
  Result r = cli({"--config", kConfig.c_str(), "--calibration", file.c_str(), "scenario",
                  scenario.c_str(), "--out", out.c_str(), "--no-plots"});
  ASSERT_NE(r.status, 2) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("run/calibration.toml")));
  // Replay reads the recording's configuration and calibration, whatever the command line says.
  r = cli({"--config", kConfig.c_str(), "replay", out.c_str()});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("identical to the recording, bit for bit"), std::string::npos) << r.out;
  // Without the calibration the driver would have sent other duty cycles.
  std::filesystem::remove(path("run/calibration.toml"));
  r = cli({"--config", kConfig.c_str(), "replay", out.c_str()});
  EXPECT_EQ(r.status, 1) << r.out << r.err;
}

// A simulated rover served over socketcand in real time, as `marsokhod sim` serves it: what a
// real rover looks like to `calibrate --can`.
class ServedRover {
 public:
  ServedRover()
      : params_(config::load_params(kConfig)),
        rover_(params_, sim::SimOptions{}),
        server_(bus::SocketcandServer::Config{"127.0.0.1", 0, "can0"},
                [this](const protocol::CanFrame& f) {
                  const std::lock_guard lock(mutex_);
                  inbox_.push_back(f);
                }) {
    server_.start();
    thread_ = std::thread([this] {
      const auto start = std::chrono::steady_clock::now();
      for (std::int64_t k = 1; !stop_; ++k) {
        std::this_thread::sleep_until(start + std::chrono::milliseconds(k));
        std::vector<protocol::CanFrame> frames;
        {
          const std::lock_guard lock(mutex_);
          frames.swap(inbox_);
        }
        for (const auto& f : frames) rover_.send(f, rover_.time_s());
        for (const sim::TimedFrame& f : rover_.advance_to(static_cast<double>(k) * 1e-3)) {
          server_.broadcast(f.frame, f.time_s);
        }
      }
    });
  }
  ~ServedRover() {
    stop_ = true;
    thread_.join();
    server_.stop();
  }
  std::string url() const {
    return "socketcand://127.0.0.1:" + std::to_string(server_.port()) + "/can0";
  }

 private:
  Params params_;
  sim::SimulatedRover rover_;
  std::mutex mutex_;
  std::vector<protocol::CanFrame> inbox_;
  bus::SocketcandServer server_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// On a real bus the command tells the operator what to do, waits for Enter and reads the
// multimeter from the keyboard. Here nobody turns the supply's knob (the rover behind socketcand
// has its battery): the procedure runs through and refuses to write, saying why.
TEST_F(CliCalibrate, OnABusTheOperatorIsGuidedAndAPoorFitIsRefused) {
  const ServedRover rover;
  const std::string url = rover.url();
  const std::string file = path("bus.toml");
  std::string operator_input;
  for (int point = 0; point < 8; ++point) operator_input += "\n24.1\n";
  operator_input += "\n";
  Result r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--can", url.c_str(),
                  "--duration", "1.6", "--out", file.c_str()},
                 operator_input);
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("Set the laboratory supply to 27 V."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Type the multimeter's reading"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("the voltages span only 0.00 V"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(file));

  // q gives up: nothing is written, and the reason is said.
  r = cli({"--config", kConfig.c_str(), "calibrate", "voltage", "--can", url.c_str(), "--out",
           file.c_str()},
          "q\n");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("given up by the operator"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(file));
}

std::vector<std::string> lines_in(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// `drive --record`: the driver on a bus writes a recording that replays bit for bit, with its
// recording.mcap (no truth: no /tf, telemetry.csv's truth columns empty); export-mcap refuses
// to write over it, and a folder without can.log.
TEST(CliDrive, ARecordingOfDriveReplaysAndHasItsMcap) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("marsokhod-drive-record-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  {
    const ServedRover rover;
    const std::string url = rover.url();
    const Result r = cli({"--config", kConfig.c_str(), "drive", "--can", url.c_str(),
                          "--no-console", "--quiet", "--duration", "1.5", "--record", dir.c_str()});
    ASSERT_EQ(r.status, 0) << r.out << r.err;
  }
  Result r = cli({"--config", kConfig.c_str(), "replay", dir.c_str()});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("identical to the recording, bit for bit"), std::string::npos) << r.out;

  std::ifstream in(dir / "recording.mcap", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const runner::test::McapFile f = runner::test::read_mcap(bytes);
  std::map<std::string, std::size_t> counts;
  for (const auto& m : f.messages) ++counts[f.channels.at(m.channel).at("topic")];
  const auto cycles = lines_in(dir / "operator.jsonl").size();
  EXPECT_GT(cycles, 90u);
  EXPECT_EQ(counts["/status"], cycles);
  EXPECT_EQ(counts["/joint_states"], cycles);
  EXPECT_EQ(counts["/can/raw"], lines_in(dir / "can.log").size());
  EXPECT_EQ(counts.count("/tf"), 0u);
  const auto telemetry = lines_in(dir / "telemetry.csv");
  ASSERT_EQ(telemetry.size(), cycles + 1);
  EXPECT_NE(telemetry[1].find(",,,,,"), std::string::npos) << telemetry[1];

  r = cli({"--config", kConfig.c_str(), "export-mcap", dir.c_str()});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("recording.mcap exists (--force writes over it)"), std::string::npos) << r.err;
  r = cli({"--config", kConfig.c_str(), "export-mcap", "--force", dir.c_str()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(std::to_string(cycles) + " cycles"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no /tf"), std::string::npos) << r.out;
  std::filesystem::remove(dir / "can.log");
  r = cli({"--config", kConfig.c_str(), "export-mcap", dir.c_str()});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "marsokhod export-mcap: '" + dir.string() +
                       "' has no can.log: not a recording (scenario --out, run --record, drive "
                       "--record)\n");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace marsokhod::app

namespace marsokhod::app {
namespace {

TEST(CliSweep, BadSeedRangesAndMixedOptionsAreUsageErrors) {
  const Result reversed = cli({"--config", kConfig.c_str(), "scenario", "dead-man", "--seeds", "5-2"});
  EXPECT_EQ(reversed.status, 2);
  EXPECT_EQ(reversed.err, "marsokhod scenario: --seeds: '5-2': the first seed is larger than the last\n");
  const Result both = cli({"--config", kConfig.c_str(), "scenario", "dead-man", "--seed", "3", "--seeds", "1-2"});
  EXPECT_EQ(both.status, 2);
  EXPECT_EQ(both.err, "marsokhod scenario: --seed names one run; a sweep takes --seeds A-B\n");
  const Result name_and_all = cli({"--config", kConfig.c_str(), "scenario", "dead-man", "--all", "--seeds", "1"});
  EXPECT_EQ(name_and_all.status, 2);
  EXPECT_EQ(name_and_all.err, "marsokhod scenario: a sweep takes either a scenario NAME or --all\n");
  const Result jobs = cli({"--config", kConfig.c_str(), "scenario", "dead-man", "--seeds", "1", "--jobs", "0"});
  EXPECT_EQ(jobs.status, 2);
  const Result step = cli({"--config", kConfig.c_str(), "scenario", "dead-man", "--physics-step-ms", "10"});
  EXPECT_EQ(step.status, 2);
  EXPECT_NE(step.err.find("--physics-step-ms"), std::string::npos) << step.err;
}

}  // namespace
}  // namespace marsokhod::app


namespace marsokhod::app {
namespace {

// The sweep end to end: the real executable as child processes, two at a time, its JSON read
// back into the table.
TEST(CliSweep, RunsTheExecutableOncePerSeedAndTablesTheResults) {
  runner::SweepPlan plan;
  plan.program = MARSOKHOD_BIN;
  plan.common_args = {"--config", kConfig};
  plan.scenarios.push_back(
      {"dead-man", std::string(MARSOKHOD_SOURCE_DIR) + "/scenarios/dead-man.toml", 1});
  plan.seeds = runner::SeedRange{2, 3};
  plan.jobs = 2;
  std::vector<std::size_t> progress;
  const auto runs = runner::run_sweep(plan, [&progress](const runner::SweepProgress& p) {
    progress.push_back(p.done);
  });
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(progress, (std::vector<std::size_t>{1, 2}));
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(runs[k].scenario, "dead-man");
    EXPECT_EQ(runs[k].seed, 2 + k);
    EXPECT_TRUE(runs[k].error.empty()) << runs[k].error;
    EXPECT_NEAR(runs[k].sim_time_s, 9.0, 0.0156);  // whole cycles of h
    EXPECT_FALSE(runs[k].checks.empty());
  }
  const runner::SweepSummary summary = runner::summarize(runs);
  EXPECT_EQ(summary.runs, 2);
  EXPECT_EQ(summary.scenarios.size(), 1u);
}

}  // namespace
}  // namespace marsokhod::app
