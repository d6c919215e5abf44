// The `marsokhod` command line (CLI11). Every bad argument or missing file is a one-line error
// naming what is wrong, with exit status 2.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>

namespace marsokhod::app {

// Runs the command with its arguments (argv[0] is the program name); returns the exit status.
int run_cli(int argc, const char* const* argv, std::istream& in, std::ostream& out,
            std::ostream& err);

// The configuration file to use: the one given, else $MARSOKHOD_CONFIG, else
// ./config/marsokhod.toml, else the source tree's. std::nullopt if none of them exists.
std::optional<std::filesystem::path> find_config(const std::string& given);

// Where the console's files are: the folder given, else ./web/dist, else the source tree's;
// empty when there is no build.
std::string find_web_dist(const std::string& given);

}  // namespace marsokhod::app
