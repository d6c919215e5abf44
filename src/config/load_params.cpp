#include "config/load_params.hpp"

#include <fstream>
#include <sstream>
#include <utility>

#include "config/calibration.hpp"
#include "config/config_reader.hpp"
#include "config/param_schema.hpp"

namespace marsokhod::config {
namespace {

std::string join(const std::string& source, const std::vector<std::string>& problems) {
  std::string text = source + ": " + std::to_string(problems.size()) + " configuration problem" +
                     (problems.size() == 1 ? "" : "s");
  for (const auto& p : problems) text += "\n  " + p;
  return text;
}

// Every key of one section's table into the struct at `target`, then its unknown keys.
void read_section(ConfigReader reader, const SectionSpec& section, void* target) {
  for (const ParamSpec& param : section.params) {
    if (auto value = reader.read(param)) param.field.store(target, *value);
  }
  reader.reject_unknown_keys();
}

}  // namespace

ConfigError::ConfigError(const std::string& source, std::vector<std::string> problems)
    : std::runtime_error(join(source, problems)), problems_(std::move(problems)) {}

Configuration configuration_from_table(const toml::table& root, const std::string& source) {
  std::vector<std::string> problems;
  ConfigReader reader(&root, "", problems);
  reader.name_files();
  Configuration config;
  for (const SectionSpec& section : param_schema()) {
    if (!section.repeated) {
      read_section(reader.table(section.name), section, section.at(config, 0));
      continue;
    }
    std::vector<ConfigReader> entries = reader.tables(section.name, 1);
    section.resize(config, entries.size());
    for (std::size_t i = 0; i < entries.size(); ++i) {
      read_section(entries[i], section, section.at(config, i));
    }
  }
  reader.reject_unknown_keys();
  if (problems.empty()) problems = consistency_problems(config.params);
  if (!problems.empty()) throw ConfigError(source, std::move(problems));
  return config;
}

Params params_from_table(const toml::table& root, const std::string& source) {
  return configuration_from_table(root, source).params;
}

toml::table parse_toml(std::string_view toml_text, const std::string& source) {
  try {
    return toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "line " << e.source().begin.line << ", column " << e.source().begin.column
        << ": TOML syntax error: " << e.description();
    throw ConfigError(source, {msg.str()});
  }
}

toml::table read_toml_file(const std::filesystem::path& file, std::string_view missing_hint) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ConfigError(file.string(),
                      {"cannot open the file: check the path" + std::string(missing_hint)});
  }
  std::ostringstream text;
  text << in.rdbuf();
  return parse_toml(text.str(), file.string());
}

Configuration parse_configuration(std::string_view toml_text, const std::string& source) {
  return configuration_from_table(parse_toml(toml_text, source), source);
}

Params parse_params(std::string_view toml_text, const std::string& source) {
  return parse_configuration(toml_text, source).params;
}

Configuration load_configuration(const std::filesystem::path& file) {
  return configuration_from_table(
      read_toml_file(file, " (the default is config/marsokhod.toml in the source tree)"),
      file.string());
}

Params load_params(const std::filesystem::path& file) { return load_configuration(file).params; }

}  // namespace marsokhod::config
