#include "config/calibration.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace marsokhod::config {
namespace {

const std::map<std::string, std::set<std::string>>& calibratable_keys() {
  static const std::map<std::string, std::set<std::string>> keys = {
      {"sensors",
       {"accelerometer_minus_g_counts", "accelerometer_plus_g_counts", "supply_v_per_count",
        "supply_offset_v"}},
      {"motors", {"backlash_rad", "scale"}},
      {"load", {"gain_same_sign_radps_per_nm", "gain_opposite_sign_radps_per_nm"}},
      {"spin", {"slope_per_m", "offset"}},
      {"power", {"duty_drop_v", "load_drop_v_s2_per_rad2"}},
  };
  return keys;
}

const std::map<std::string, std::set<std::string>>& calibratable_tables() {
  static const std::map<std::string, std::set<std::string>> keys = {
      {"motor_curve", {"icr", "duty", "no_load_speed_radps"}},
      {"response", {"period_s", "con", "delta"}},
  };
  return keys;
}

std::string join_names(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Whether two [[motor_curve]] / [[response]] entries describe the same table.
bool same_table(const std::string& kind, const toml::table& a, const toml::table& b) {
  if (kind == "motor_curve") return a["icr"].value<int64_t>() == b["icr"].value<int64_t>();
  const auto pa = a["period_s"].value<double>();
  const auto pb = b["period_s"].value<double>();
  return a["con"].value<int64_t>() == b["con"].value<int64_t>() && pa && pb &&
         std::abs(*pa - *pb) <= 0.001;
}

}  // namespace

std::vector<std::string> calibration_problems(const toml::table& calibration) {
  std::vector<std::string> problems;
  for (const auto& [key, node] : calibration) {
    const std::string section(key.str());
    if (section == "calibration") {
      if (!node.is_table()) problems.push_back("calibration: must be a table of reports");
      continue;
    }
    if (const auto t = calibratable_tables().find(section); t != calibratable_tables().end()) {
      const toml::array* array = node.as_array();
      if (array == nullptr || !array->is_array_of_tables()) {
        problems.push_back(section + ": must be an array of tables ([[" + section + "]])");
        continue;
      }
      for (std::size_t i = 0; i < array->size(); ++i) {
        const toml::table& entry = *array->get(i)->as_table();
        for (const std::string& need : t->second) {
          if (!entry.contains(need)) {
            problems.push_back(section + "[" + std::to_string(i) + "]." + need +
                               ": missing (a [[" + section + "]] needs " +
                               join_names(t->second) + ")");
          }
        }
        for (const auto& [k, v] : entry) {
          if (!t->second.contains(std::string(k.str()))) {
            problems.push_back(section + "[" + std::to_string(i) + "]." + std::string(k.str()) +
                               ": unknown key");
          }
        }
      }
      continue;
    }
    const auto s = calibratable_keys().find(section);
    if (s == calibratable_keys().end()) {
      problems.push_back(section + ": not a calibrated section (a calibration file holds only " +
                         "sensors, motors, motor_curve, response, load, spin, power and " +
                         "calibration; change other settings in the configuration)");
      continue;
    }
    const toml::table* table = node.as_table();
    if (table == nullptr) {
      problems.push_back(section + ": must be a table");
      continue;
    }
    for (const auto& [k, v] : *table) {
      if (!s->second.contains(std::string(k.str()))) {
        problems.push_back(section + "." + std::string(k.str()) +
                           ": not a calibrated value (calibrated in [" + section + "]: " +
                           join_names(s->second) + ")");
      }
    }
  }
  return problems;
}

toml::table merge_calibration(const toml::table& base, const toml::table& calibration,
                              const std::string& calibration_source) {
  std::vector<std::string> problems = calibration_problems(calibration);
  if (!problems.empty()) throw ConfigError(calibration_source, std::move(problems));
  toml::table merged = base;
  for (const auto& [key, node] : calibration) {
    const std::string section(key.str());
    if (section == "calibration") continue;
    if (calibratable_tables().contains(section)) {
      toml::array* target = merged[section].as_array();
      if (target == nullptr) {
        merged.insert_or_assign(section, toml::array{});
        target = merged[section].as_array();
      }
      for (const auto& entry_node : *node.as_array()) {
        const toml::table& entry = *entry_node.as_table();
        bool replaced = false;
        for (std::size_t i = 0; i < target->size(); ++i) {
          const toml::table* existing = target->get(i)->as_table();
          if (existing != nullptr && same_table(section, *existing, entry)) {
            target->replace(target->cbegin() + static_cast<std::ptrdiff_t>(i), toml::table(entry));
            replaced = true;
          }
        }
        if (!replaced) target->push_back(entry);
      }
      continue;
    }
    toml::table* target = merged[section].as_table();
    if (target == nullptr) {
      merged.insert_or_assign(section, toml::table{});
      target = merged[section].as_table();
    }
    for (const auto& [k, v] : *node.as_table()) target->insert_or_assign(k, v);
  }
  return merged;
}

toml::table read_toml_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError(file.string(), {"cannot open the file: check the path"});
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return toml::parse(text.str(), file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "line " << e.source().begin.line << ", column " << e.source().begin.column
        << ": TOML syntax error: " << e.description();
    throw ConfigError(file.string(), {msg.str()});
  }
}

Params load_params(const std::filesystem::path& config_file,
                   const std::filesystem::path& calibration_file) {
  const toml::table base = read_toml_file(config_file);
  // The configuration alone must be valid too: its errors are named against its own file.
  (void)params_from_table(base, config_file.string());
  const toml::table calibration = read_toml_file(calibration_file);
  const toml::table merged = merge_calibration(base, calibration, calibration_file.string());
  Params params = params_from_table(merged, config_file.string() + " with calibration " +
                                                calibration_file.string());
  params.calibration.file = calibration_file.string();
  if (const toml::table* reports = calibration["calibration"].as_table()) {
    for (const auto& [procedure, report] : *reports) {
      params.calibration.procedures.emplace_back(procedure.str());
    }
  }
  return params;
}

Params apply_calibration_values(const std::filesystem::path& config_file,
                                const toml::table& values) {
  const toml::table merged =
      merge_calibration(read_toml_file(config_file), values, "calibration values");
  return params_from_table(merged, config_file.string() + " with calibration values");
}

}  // namespace marsokhod::config
