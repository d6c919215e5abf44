#include "config/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

namespace marsokhod::config {
namespace {

std::string show(const toml::node& node) {
  std::ostringstream out;
  if (const auto* s = node.as_string()) {
    out << '"' << s->get() << '"';
  } else if (node.is_table()) {
    out << "a table";
  } else if (node.is_array()) {
    out << "an array";
  } else {
    node.visit([&out](const auto& v) { out << v; });
  }
  return out.str();
}

// Single-character edits from a to b (Levenshtein), for suggesting the key a typo meant.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string show_range(double min, double max) {
  return "[" + show_number(min) + ", " + show_number(max) + "]";
}

}  // namespace

std::string show_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

ConfigReader::ConfigReader(const toml::table* table, std::string path,
                           std::vector<std::string>& problems)
    : table_(table), path_(std::move(path)), problems_(&problems) {}

std::string ConfigReader::key_name(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

// " (FILE:LINE)" or " (line LINE)" where toml++ knows it; a merged table's copied nodes have no
// position.
std::string ConfigReader::where(const toml::node& node) const {
  const toml::source_region& source = node.source();
  if (source.begin.line == 0) return {};
  const std::string line = std::to_string(source.begin.line);
  if (!name_files_ || source.path == nullptr || source.path->empty()) {
    return " (line " + line + ")";
  }
  return " (" + *source.path + ":" + line + ")";
}

void ConfigReader::problem(std::string message) { problems_->push_back(std::move(message)); }

const toml::node* ConfigReader::find(std::string_view key, std::string_view expected) {
  used_.emplace(key);
  if (table_ == nullptr) return nullptr;  // the enclosing table is missing: already reported
  const toml::node* node = table_->get(key);
  if (node == nullptr) {
    problem(key_name(key) + ": missing; expected " + std::string(expected));
  }
  return node;
}

std::optional<ParamValue> ConfigReader::read(const ParamSpec& spec) {
  const std::size_t problems_before = problems_->size();
  ParamValue read_value = value(spec);
  if (table_ == nullptr || problems_->size() != problems_before) return std::nullopt;
  return read_value;
}

ParamValue ConfigReader::value(const ParamSpec& p) {
  switch (p.field.kind) {
    case ParamKind::kNumber:
      return number(p.key, p.min, p.max);
    case ParamKind::kInteger:
      return std::int64_t{integer(p.key, static_cast<int>(p.min), static_cast<int>(p.max))};
    case ParamKind::kBoolean:
      return boolean(p.key);
    case ParamKind::kText:
      return text(p.key, p.max_length);
    case ParamKind::kTexts:
      return texts(p.key, p.max_count, p.max_length);
    case ParamKind::kChoice:
      return static_cast<std::int64_t>(choice(p.key, p.choices));
    case ParamKind::kNumbers:
      return numbers(p.key, p.min, p.max, p.count_min(), p.count_max());
  }
  return {};
}

double ConfigReader::number(std::string_view key, double min, double max) {
  const std::string expected = "a number in " + show_range(min, max);
  const toml::node* node = find(key, expected);
  if (node == nullptr) return min;
  if (!node->is_number()) {
    problem(key_name(key) + ": " + show(*node) + " is not a number; expected " + expected +
            where(*node));
    return min;
  }
  const double value = node->value<double>().value_or(min);
  if (!std::isfinite(value) || value < min || value > max) {
    problem(key_name(key) + ": " + show(*node) + " is out of range; allowed " +
            show_range(min, max) + where(*node));
    return min;
  }
  return value;
}

int ConfigReader::integer(std::string_view key, int min, int max) {
  const std::string expected = "an integer in " + show_range(min, max);
  const toml::node* node = find(key, expected);
  if (node == nullptr) return min;
  if (!node->is_integer()) {
    problem(key_name(key) + ": " + show(*node) + " is not an integer; expected " + expected +
            where(*node));
    return min;
  }
  const std::int64_t value = node->value<std::int64_t>().value_or(min);
  if (value < min || value > max) {
    problem(key_name(key) + ": " + show(*node) + " is out of range; allowed " +
            show_range(min, max) + where(*node));
    return min;
  }
  return static_cast<int>(value);
}

bool ConfigReader::boolean(std::string_view key) {
  const toml::node* node = find(key, "true or false");
  if (node == nullptr) return false;
  if (!node->is_boolean()) {
    problem(key_name(key) + ": " + show(*node) + " is not a boolean; expected true or false" +
            where(*node));
    return false;
  }
  return node->value<bool>().value_or(false);
}

std::string ConfigReader::text(std::string_view key, std::size_t max_length) {
  const toml::node* node = find(key, "a string");
  if (node == nullptr) return {};
  const auto* value = node->as_string();
  if (value == nullptr) {
    problem(key_name(key) + ": " + show(*node) + " is not a string" + where(*node));
    return {};
  }
  if (value->get().size() > max_length) {
    problem(key_name(key) + ": longer than " + std::to_string(max_length) + " characters" +
            where(*node));
    return {};
  }
  return value->get();
}

std::vector<std::string> ConfigReader::texts(std::string_view key, std::size_t max_count,
                                             std::size_t max_length) {
  const std::string expected = "an array of at most " + std::to_string(max_count) + " strings";
  const toml::node* node = find(key, expected);
  std::vector<std::string> out;
  if (node == nullptr) return out;
  const toml::array* array = node->as_array();
  if (array == nullptr || array->size() > max_count) {
    problem(key_name(key) + ": " + show(*node) + " given; expected " + expected + where(*node));
    return out;
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& item = (*array)[i];
    const auto* value = item.as_string();
    const std::string name = key_name(key) + "[" + std::to_string(i) + "]";
    if (value == nullptr) {
      problem(name + ": " + show(item) + " is not a string" + where(item));
    } else if (value->get().empty() || value->get().size() > max_length) {
      problem(name + ": empty or longer than " + std::to_string(max_length) + " characters" +
              where(item));
    } else {
      out.push_back(value->get());
    }
  }
  return out;
}

std::size_t ConfigReader::choice(std::string_view key, std::span<const std::string_view> allowed) {
  std::string options;
  for (std::string_view a : allowed) {
    options += (options.empty() ? "\"" : ", \"") + std::string(a) + "\"";
  }
  const toml::node* node = find(key, "one of " + options);
  if (node == nullptr) return 0;
  if (const auto* text = node->as_string()) {
    for (std::size_t i = 0; i < allowed.size(); ++i) {
      if (text->get() == allowed[i]) return i;
    }
  }
  problem(key_name(key) + ": " + show(*node) + " is not allowed; expected one of " + options +
          where(*node));
  return 0;
}

std::vector<double> ConfigReader::numbers(std::string_view key, double min, double max,
                                          std::size_t min_count, std::size_t max_count) {
  std::ostringstream expected;
  expected << "an array of " << min_count;
  if (max_count != min_count) expected << " to " << max_count;
  expected << " numbers in " << show_range(min, max);
  const toml::node* node = find(key, expected.str());
  if (node == nullptr) return {};
  const toml::array* array = node->as_array();
  if (array == nullptr || array->size() < min_count || array->size() > max_count) {
    const std::string got =
        array == nullptr ? show(*node) : "an array of " + std::to_string(array->size());
    problem(key_name(key) + ": " + got + " given; expected " + expected.str() + where(*node));
    return {};
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::node& item = (*array)[i];
    const std::string name = key_name(key) + "[" + std::to_string(i) + "]";
    const double value = item.value<double>().value_or(std::nan(""));
    if (!item.is_number()) {
      problem(name + ": " + show(item) + " is not a number" + where(item));
    } else if (!std::isfinite(value) || value < min || value > max) {
      problem(name + ": " + show(item) + " is out of range; allowed " + show_range(min, max) +
              where(item));
    }
    out.push_back(value);
  }
  return out;
}

ConfigReader ConfigReader::table(std::string_view key) {
  const toml::node* node = find(key, "a table [" + key_name(key) + "]");
  const toml::table* sub = node == nullptr ? nullptr : node->as_table();
  if (node != nullptr && sub == nullptr) {
    problem(key_name(key) + ": " + show(*node) + " given; expected a table" + where(*node));
  }
  ConfigReader reader(sub, key_name(key), *problems_);
  reader.name_files_ = name_files_;
  return reader;
}

std::vector<ConfigReader> ConfigReader::tables(std::string_view key, std::size_t min_count) {
  const toml::node* node = find(key, "an array of tables [[" + key_name(key) + "]]");
  std::vector<ConfigReader> out;
  if (node == nullptr) return out;
  const toml::array* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables()) {
    problem(key_name(key) + ": expected an array of tables [[" + key_name(key) + "]]" +
            where(*node));
    return out;
  }
  if (array->size() < min_count) {
    problem(key_name(key) + ": " + std::to_string(array->size()) + " entries; at least " +
            std::to_string(min_count) + " required" + where(*node));
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    out.emplace_back((*array)[i].as_table(), key_name(key) + "[" + std::to_string(i) + "]",
                     *problems_);
    out.back().name_files_ = name_files_;
  }
  return out;
}

void ConfigReader::reject_unknown_keys() {
  if (table_ == nullptr) return;
  for (const auto& [key, node] : *table_) {
    if (used_.find(key.str()) != used_.end()) continue;
    std::string_view nearest;
    std::size_t nearest_distance = 3;  // suggest only keys within two edits
    for (const std::string& known : used_) {
      const std::size_t d = edit_distance(key.str(), known);
      if (d < nearest_distance && table_->get(known) == nullptr) {
        nearest = known;
        nearest_distance = d;
      }
    }
    const std::string hint = nearest.empty() ? "check its spelling against docs/parameters.md"
                                             : "did you mean " + std::string(nearest) + "?";
    problem(key_name(key.str()) + ": unknown key" + where(node) + "; " + hint);
  }
}

}  // namespace marsokhod::config
