#include "app/cli.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace marsokhod::app {
namespace {

struct Result {
  int status = 0;
  std::string out;
  std::string err;
};

Result cli(std::vector<const char*> args, const std::string& stdin_text = "") {
  args.insert(args.begin(), "marsokhod");
  std::istringstream in(stdin_text);
  std::ostringstream out;
  std::ostringstream err;
  const int status = run_cli(static_cast<int>(args.size()), args.data(), in, out, err);
  return {status, out.str(), err.str()};
}

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
}

}  // namespace
}  // namespace marsokhod::app
