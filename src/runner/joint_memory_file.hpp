// The kept joint state (driver/joint_memory.hpp) outside the driver: as JSON in recordings (the
// cycle a restarted driver started with it, so that replay restarts it the same way) and as the
// file `marsokhod drive --joint-memory FILE` keeps on the onboard computer:
//   {"written_unix_s": 1795500000.25, "known": true,
//    "joints": [{"enc": 1234, "stp": 1200, "dir": false, "shaft_rad": -1.5, "joint_rad": -1.48,
//                "duty": 0.0}, {… µ7 …}]}
// The file is replaced atomically (a temporary file renamed over it; ext4 flushes a file renamed
// over another before the rename), whenever the state changes and at least every
// max_age/4 so that a still rover's state stays recent.
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>

#include "driver/joint_memory.hpp"

namespace marsokhod::runner {

nlohmann::json joint_memory_json(const driver::JointMemory& memory);
// Throws std::invalid_argument naming `where` and the field for a malformed state.
driver::JointMemory joint_memory_from_json(const nlohmann::json& json, const std::string& where);

class JointMemoryFile {
 public:
  JointMemoryFile(std::filesystem::path path, double max_age_s);

  // The state in the file if it exists and was written at most max_age_s before now; `note`
  // says what was found ("none", "17 s old", "stale: 3600 s old"). Throws std::runtime_error
  // naming the file when it exists but cannot be read or parsed.
  std::optional<driver::JointMemory> load(double now_unix_s, std::string& note) const;

  // Keeps `memory` (none: nothing to keep yet, the file stays as it is). Throws
  // std::runtime_error naming the file when it cannot be written.
  void keep(const std::optional<driver::JointMemory>& memory, double now_unix_s);

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  double max_age_s_;
  std::optional<driver::JointMemory> written_;
  double written_unix_s_ = 0.0;
};

}  // namespace marsokhod::runner
