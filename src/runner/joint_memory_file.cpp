#include "runner/joint_memory_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "link/json_fields.hpp"

namespace marsokhod::runner {
namespace {

constexpr double kRefreshShare = 0.25;  // rewrite an unchanged state after max_age/4

std::uint16_t read_register(const nlohmann::json& value, const std::string& field) {
  const double v = link::read_number(value, field);
  if (!(v >= 0.0 && v <= 65535.0) || v != static_cast<double>(static_cast<std::uint16_t>(v))) {
    throw std::invalid_argument(field + " must be an integer in 0..65535, not " +
                                link::shown_value(value));
  }
  return static_cast<std::uint16_t>(v);
}

const nlohmann::json& at(const nlohmann::json& object, const std::string& key,
                         const std::string& where) {
  if (!object.is_object() || !object.contains(key)) {
    throw std::invalid_argument(where + ": the kept joint state has no \"" + key + "\"");
  }
  return object.at(key);
}

}  // namespace

nlohmann::json joint_memory_json(const driver::JointMemory& memory) {
  nlohmann::json joints = nlohmann::json::array();
  for (const driver::KeptJoint& j : memory.joints) {
    joints.push_back({{"enc", j.reading.enc},
                      {"stp", j.reading.stp},
                      {"dir", j.reading.dir},
                      {"shaft_rad", j.shaft_rad},
                      {"joint_rad", j.joint_rad},
                      {"duty", j.duty},
                      {"uncertainty_rad", j.uncertainty_rad}});
  }
  return {{"known", memory.known}, {"joints", joints}};
}

driver::JointMemory joint_memory_from_json(const nlohmann::json& json, const std::string& where) {
  driver::JointMemory memory;
  memory.known = link::read_bool(at(json, "known", where), where + ": known");
  const nlohmann::json& joints = at(json, "joints", where);
  if (!joints.is_array() || joints.size() != 2) {
    throw std::invalid_argument(where + ": joints must be an array of two (µ6, µ7)");
  }
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string field = where + ": joints[" + std::to_string(k) + "].";
    driver::KeptJoint& j = memory.joints[k];
    j.reading.enc = read_register(at(joints[k], "enc", where), field + "enc");
    j.reading.stp = read_register(at(joints[k], "stp", where), field + "stp");
    j.reading.dir = link::read_bool(at(joints[k], "dir", where), field + "dir");
    j.shaft_rad = link::read_number(at(joints[k], "shaft_rad", where), field + "shaft_rad");
    j.joint_rad = link::read_number(at(joints[k], "joint_rad", where), field + "joint_rad");
    j.duty = link::read_number(at(joints[k], "duty", where), field + "duty");
    if (!(std::abs(j.duty) <= 1.0)) {
      throw std::invalid_argument(field + "duty must lie in [-1, 1], not " +
                                  link::shown_value(joints[k]["duty"]));
    }
    // Absent in states kept before the driver counted it: none carried.
    if (joints[k].contains("uncertainty_rad")) {
      j.uncertainty_rad =
          link::read_number(joints[k]["uncertainty_rad"], field + "uncertainty_rad");
      if (!(j.uncertainty_rad >= 0.0 && std::isfinite(j.uncertainty_rad))) {
        throw std::invalid_argument(field + "uncertainty_rad must be a finite number ≥ 0, not " +
                                    link::shown_value(joints[k]["uncertainty_rad"]));
      }
    }
  }
  return memory;
}

JointMemoryFile::JointMemoryFile(std::filesystem::path path, double max_age_s)
    : path_(std::move(path)), max_age_s_(max_age_s) {}

std::optional<driver::JointMemory> JointMemoryFile::load(double now_unix_s,
                                                         std::string& note) const {
  std::ifstream in(path_);
  if (!in) {
    note = "none in " + path_.string();
    return std::nullopt;
  }
  std::stringstream text;
  text << in.rdbuf();
  try {
    const nlohmann::json json = link::parse_json_strictly(text.str());
    const double written = link::read_number(at(json, "written_unix_s", path_.string()),
                                             path_.string() + ": written_unix_s");
    driver::JointMemory memory = joint_memory_from_json(json, path_.string());
    const double age_s = now_unix_s - written;
    char text_age[96];
    std::snprintf(text_age, sizeof text_age, "%.0f s old", age_s);
    if (!(age_s >= 0.0 && age_s <= max_age_s_)) {
      note = std::string("stale (") + text_age + ", written by an earlier power-up) in " +
             path_.string();
      return std::nullopt;
    }
    note = std::string(text_age) + " from " + path_.string();
    return memory;
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path_.string() + ": " + e.what());
  }
}

void JointMemoryFile::keep(const std::optional<driver::JointMemory>& memory, double now_unix_s) {
  if (!memory) return;
  if (written_ && *written_ == *memory &&
      now_unix_s - written_unix_s_ < kRefreshShare * max_age_s_) {
    return;
  }
  nlohmann::json json = joint_memory_json(*memory);
  json["written_unix_s"] = now_unix_s;
  std::filesystem::path temporary = path_;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    out << json.dump() << '\n';
    if (!out) throw std::runtime_error("cannot write the joint state to " + temporary.string());
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path_, ec);
  if (ec) throw std::runtime_error("cannot replace " + path_.string() + ": " + ec.message());
  written_ = memory;
  written_unix_s_ = now_unix_s;
}

}  // namespace marsokhod::runner
