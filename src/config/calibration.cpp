#include "config/calibration.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/config_reader.hpp"
#include "config/param_schema.hpp"

namespace marsokhod::config {
namespace {

using KeysBySection = std::map<std::string, std::set<std::string>, std::less<>>;

// The schema's calibrated keys of [tables] (calibratable_keys) and of [[arrays of tables]], whose
// every key is calibrated (calibratable_tables).
KeysBySection calibrated_keys(bool repeated) {
  KeysBySection keys;
  for (const SectionSpec& section : param_schema()) {
    if (section.repeated != repeated) continue;
    for (const ParamSpec& param : section.params) {
      if (param.calibrated) keys[std::string(section.name)].emplace(param.key);
    }
  }
  return keys;
}

const KeysBySection& calibratable_keys() {
  static const KeysBySection keys = calibrated_keys(false);
  return keys;
}

const KeysBySection& calibratable_tables() {
  static const KeysBySection keys = calibrated_keys(true);
  return keys;
}

// "motors, motor_curve, …, sensors and calibration": what a calibration file may hold.
std::string calibrated_sections() {
  std::string out;
  for (const SectionSpec& section : param_schema()) {
    if (calibratable_keys().contains(section.name) ||
        calibratable_tables().contains(section.name)) {
      out += std::string(section.name) + ", ";
    }
  }
  return out.substr(0, out.size() - 2) + " and calibration";
}

std::string join_names(const std::set<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Whether two [[motor_curve]] / [[load_gain]] / [[response]] entries describe the same table.
bool same_table(const std::string& kind, const toml::table& a, const toml::table& b) {
  if (kind == "motor_curve" || kind == "load_gain") {
    return a["icr"].value<int64_t>() == b["icr"].value<int64_t>();
  }
  const auto pa = a["period_s"].value<double>();
  const auto pb = b["period_s"].value<double>();
  return a["con"].value<int64_t>() == b["con"].value<int64_t>() && pa && pb &&
         std::abs(*pa - *pb) <= 0.001;
}

// The keys a calibration table states, checked by the schema: its problems name the calibration
// file's lines, which the merged configuration no longer knows.
void check_stated_values(const SectionSpec& section, const toml::table* table, std::string path,
                         std::vector<std::string>& problems) {
  if (table == nullptr) return;
  ConfigReader reader(table, std::move(path), problems);
  reader.name_files();
  for (const ParamSpec& param : section.params) {
    if (table->contains(param.key)) (void)reader.read(param);
  }
}

std::vector<std::string> value_problems(const toml::table& calibration) {
  std::vector<std::string> problems;
  for (const auto& [key, node] : calibration) {
    const SectionSpec* section = find_section(key.str());
    if (section == nullptr) continue;
    const std::string name(key.str());
    if (const toml::array* entries = node.as_array()) {
      for (std::size_t i = 0; i < entries->size(); ++i) {
        check_stated_values(*section, entries->get(i)->as_table(),
                            name + "[" + std::to_string(i) + "]", problems);
      }
    } else {
      check_stated_values(*section, node.as_table(), name, problems);
    }
  }
  return problems;
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
                         calibrated_sections() + "; change other settings in the configuration)");
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
  if (problems.empty()) problems = value_problems(calibration);
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

Configuration load_configuration(const std::filesystem::path& config_file,
                                 const std::filesystem::path& calibration_file) {
  const toml::table base = read_toml_file(config_file);
  // The configuration alone must be valid too: its errors are named against its own file.
  (void)configuration_from_table(base, config_file.string());
  const toml::table calibration = read_toml_file(calibration_file);
  const toml::table merged = merge_calibration(base, calibration, calibration_file.string());
  Configuration config = configuration_from_table(
      merged, config_file.string() + " with calibration " + calibration_file.string());
  config.calibration.file = calibration_file.string();
  if (const toml::table* reports = calibration["calibration"].as_table()) {
    for (const auto& [procedure, report] : *reports) {
      config.calibration.procedures.emplace_back(procedure.str());
    }
  }
  return config;
}

Params load_params(const std::filesystem::path& config_file,
                   const std::filesystem::path& calibration_file) {
  return load_configuration(config_file, calibration_file).params;
}

Params apply_calibration_values(const std::filesystem::path& config_file,
                                const toml::table& values) {
  const toml::table merged =
      merge_calibration(read_toml_file(config_file), values, "calibration values");
  return params_from_table(merged, config_file.string() + " with calibration values");
}

}  // namespace marsokhod::config
