// Typed, range-checked reading of one TOML table. Problems are collected, not thrown, so that an
// operator sees every wrong key of a file at once; each names the key, the value and what is
// allowed, with the line it stands on.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstddef>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace marsokhod::config {

class ConfigReader {
 public:
  // `path` is the dotted name of the table ("geometry", "response[1]"); `problems` collects.
  ConfigReader(const toml::table* table, std::string path, std::vector<std::string>& problems);

  double number(std::string_view key, double min, double max);
  int integer(std::string_view key, int min, int max);
  bool boolean(std::string_view key);
  std::string text(std::string_view key, std::size_t max_length);
  // An array of at most max_count strings of at most max_length characters each.
  std::vector<std::string> texts(std::string_view key, std::size_t max_count,
                                 std::size_t max_length);
  std::string choice(std::string_view key, std::initializer_list<std::string_view> allowed);
  std::vector<double> numbers(std::string_view key, double min, double max, std::size_t min_count,
                              std::size_t max_count);
  template <std::size_t N>
  std::array<double, N> fixed_numbers(std::string_view key, double min, double max) {
    std::array<double, N> out{};
    const std::vector<double> values = numbers(key, min, max, N, N);
    for (std::size_t i = 0; i < N && i < values.size(); ++i) out[i] = values[i];
    return out;
  }
  // Sub-tables: a missing one is reported and yields a reader over nothing.
  ConfigReader table(std::string_view key);
  // Arrays of tables ([[key]]); at least `min_count` entries.
  std::vector<ConfigReader> tables(std::string_view key, std::size_t min_count);

  // Reports every key of the table that no accessor asked for (a typo, or a stale key).
  void reject_unknown_keys();

  void problem(std::string message);
  const std::string& path() const { return path_; }

 private:
  const toml::node* find(std::string_view key, std::string_view expected);
  std::string key_name(std::string_view key) const;
  std::string where(const toml::node& node) const;

  const toml::table* table_;
  std::string path_;
  std::vector<std::string>* problems_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace marsokhod::config
