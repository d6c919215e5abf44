// Typed, range-checked reading of one TOML table by the parameter schema (param_schema.hpp).
// Problems are collected, not thrown, so that an operator sees every wrong key of a file at once;
// each names the key, the value and what is allowed, with the file and line it stands on.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "config/param_schema.hpp"

namespace marsokhod::config {

// A number as the configuration's messages and docs/parameters.md show it: 0.145, 1e-06, 255.
std::string show_number(double value);

class ConfigReader {
 public:
  // `path` is the dotted name of the table ("geometry", "response[1]"); `problems` collects.
  ConfigReader(const toml::table* table, std::string path, std::vector<std::string>& problems);

  // Problems end with " (FILE:LINE)" rather than " (line LINE)", here and in the tables read
  // through this reader: for messages that stand apart from the file's name (the configuration's).
  void name_files() { name_files_ = true; }

  // The parameter's value, checked against its spec; nullopt (and a problem) when it is missing
  // or wrong, nullopt alone when the enclosing table is missing (already reported).
  std::optional<ParamValue> read(const ParamSpec& spec);

  double number(std::string_view key, double min, double max);
  int integer(std::string_view key, int min, int max);
  bool boolean(std::string_view key);
  std::string text(std::string_view key, std::size_t max_length);
  // An array of at most max_count strings of at most max_length characters each.
  std::vector<std::string> texts(std::string_view key, std::size_t max_count,
                                 std::size_t max_length);
  // The index of the value in `allowed`.
  std::size_t choice(std::string_view key, std::span<const std::string_view> allowed);
  std::vector<double> numbers(std::string_view key, double min, double max, std::size_t min_count,
                              std::size_t max_count);
  // Sub-tables: a missing one is reported and yields a reader over nothing.
  ConfigReader table(std::string_view key);
  // Arrays of tables ([[key]]); at least `min_count` entries.
  std::vector<ConfigReader> tables(std::string_view key, std::size_t min_count);

  // Reports every key of the table that no accessor asked for (a typo, or a stale key).
  void reject_unknown_keys();

  void problem(std::string message);
  const std::string& path() const { return path_; }

 private:
  ParamValue value(const ParamSpec& spec);
  const toml::node* find(std::string_view key, std::string_view expected);
  std::string key_name(std::string_view key) const;
  std::string where(const toml::node& node) const;

  const toml::table* table_;
  std::string path_;
  std::vector<std::string>* problems_;
  std::set<std::string, std::less<>> used_;
  bool name_files_ = false;
};

}  // namespace marsokhod::config
