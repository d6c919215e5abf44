// Shared by the runner's tests: the configuration the scenarios run with, and scratch folders.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "config/load_params.hpp"
#include "core/params.hpp"

namespace marsokhod::runner::testing {

inline const std::filesystem::path kSourceDir = MARSOKHOD_SOURCE_DIR;
inline const std::filesystem::path kConfigFile = kSourceDir / "config" / "marsokhod.toml";

// The shipped configuration, as `marsokhod scenario` reads it, loaded once per program.
inline const Params& shipped_params() {
  static const Params params = config::load_params(kConfigFile);
  return params;
}

// A fresh folder for the running test, removed with the object.
class ScratchFolder {
 public:
  ScratchFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("marsokhod-" + std::string(info->test_suite_name()) + "-" + info->name() + "-" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Writes `text` to a file of that name in the folder and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    return write_to(path_, name, text);
  }
  static std::filesystem::path write_to(const std::filesystem::path& folder,
                                        const std::string& name, const std::string& text) {
    const auto file = folder / name;
    std::ofstream(file) << text;
    return file;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace marsokhod::runner::testing
