// `marsokhod soak`: bad arguments are one-line usage errors, a short soak prints its summary or
// one JSON object, and `marsokhod replay` replays a soak's violation window identically.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "cli_runner.hpp"
#include "config/load_params.hpp"
#include "runner/soak.hpp"

namespace marsokhod::app {
namespace {

using test::cli;
using test::Result;

const std::string kConfig = std::string(MARSOKHOD_SOURCE_DIR) + "/config/marsokhod.toml";

std::filesystem::path scratch(const char* name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("marsokhod-soak-cli-" + std::string(name) + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(SoakCommand, BadArgumentsAreOneLineUsageErrors) {
  for (const std::vector<const char*>& args :
       {std::vector<const char*>{"--seed", "-3"}, {"--seed", "x1"}, {"--hours", "0"},
        {"--hours", "-0.5"}, {"--hours", "nan"}}) {
    std::vector<const char*> full{"--config", kConfig.c_str(), "soak"};
    full.insert(full.end(), args.begin(), args.end());
    const Result r = cli(full);
    EXPECT_EQ(r.status, 2) << args[0] << " " << args[1];
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(args[0]), std::string::npos) << r.err;
  }
}

TEST(SoakCommand, AShortSoakPrintsOneJsonObject) {
  const auto dir = scratch("json");
  const Result r = cli({"--config", kConfig.c_str(), "soak", "--hours", "0.002", "--seed", "3",
                        "--json", "--out", dir.c_str()});
  ASSERT_NE(r.status, 2) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("seed"), 3);
  EXPECT_EQ(j.at("segments"), 2);
  EXPECT_EQ(j.at("cycles"), 2 * 231);  // 3.6 s on each ground
  EXPECT_NEAR(j.at("sim_hours").get<double>(), 0.002, 0.0001);
  EXPECT_EQ(j.at("passed").get<bool>(), r.status == 0);
  EXPECT_EQ(j.at("recording").is_null(), r.status == 0);
  for (const char* kind : {"frame-loss", "lost-pulses", "silent-controller", "battery-sag",
                           "blocked-wheel", "wheel-in-air", "brown-out"}) {
    EXPECT_TRUE(j.at("faults_injected").contains(kind)) << kind;
  }
  std::filesystem::remove_all(dir);
}

TEST(SoakCommand, ReplayReplaysASoaksWindowIdentically) {
  const Params params = config::load_params(kConfig);
  const auto dir = scratch("replay");
  runner::SoakOptions options;
  options.hours = 0.01;
  options.seed = 4;
  options.window_s = 2.0;
  options.limits.duty_ceiling = 0.1;  // fails as soon as the operator drives
  options.out = dir;
  options.config_file = kConfig;
  const runner::SoakResult soak = runner::run_soak(params, options);
  ASSERT_TRUE(soak.recording.has_value());
  const Result r = cli({"replay", dir.c_str()});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("identical to the recording, bit for bit"), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace marsokhod::app
