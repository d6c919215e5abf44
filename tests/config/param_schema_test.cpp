// The parameter schema holds the three places a parameter is written together: docs/parameters.md
// is generated from it, config/marsokhod.toml has exactly its keys, and the file's values are the
// defaults of core/params.hpp.
#include "config/param_schema.hpp"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "config/calibration.hpp"
#include "config/load_params.hpp"
#include "config/param_docs.hpp"

namespace marsokhod::config {
namespace {

const std::string kSourceDir = MARSOKHOD_SOURCE_DIR;
const std::string kShippedFile = kSourceDir + "/config/marsokhod.toml";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The tables of a section in the shipped file: one, or each entry of an array of tables.
std::vector<const toml::table*> tables_of(const toml::table& root, const SectionSpec& section) {
  std::vector<const toml::table*> out;
  if (!section.repeated) {
    if (const toml::table* t = root[section.name].as_table()) out.push_back(t);
  } else if (const toml::array* a = root[section.name].as_array()) {
    for (const toml::node& entry : *a) {
      if (const toml::table* t = entry.as_table()) out.push_back(t);
    }
  }
  return out;
}

TEST(ParamSchema, ReferencePageIsCurrent) {
  const std::string page = read_text(kSourceDir + "/" + "docs/parameters.md");
  EXPECT_TRUE(page == parameters_markdown())
      << "docs/parameters.md is stale: the schema (src/config/param_schema.cpp) or the defaults "
         "changed. Regenerate it: make params-doc (build/src/config/marsokhod-param-docs > "
         "docs/parameters.md)";
}

TEST(ParamSchema, ShippedFileHasEveryKeyOfTheSchemaAndNoOther) {
  const toml::table root = toml::parse_file(kShippedFile);
  std::set<std::string_view> sections;
  for (const SectionSpec& section : param_schema()) {
    sections.insert(section.name);
    const auto tables = tables_of(root, section);
    EXPECT_FALSE(tables.empty()) << "config/marsokhod.toml lacks the section " << section.name;
    for (const toml::table* table : tables) {
      std::set<std::string_view> keys;
      for (const ParamSpec& param : section.params) {
        keys.insert(param.key);
        EXPECT_TRUE(table->contains(param.key))
            << "config/marsokhod.toml lacks " << section.name << "." << param.key;
      }
      for (const auto& [key, node] : *table) {
        EXPECT_TRUE(keys.contains(key.str()))
            << "config/marsokhod.toml:" << node.source().begin.line << ": " << section.name << "."
            << key.str() << " is not in the schema (misspelt, or add it to param_schema.cpp)";
      }
    }
  }
  for (const auto& [key, node] : root) {
    EXPECT_TRUE(sections.contains(key.str()))
        << "config/marsokhod.toml: section " << key.str() << " is not in the schema";
  }
}

TEST(ParamSchema, ShippedValuesAreTheDefaultsOfParams) {
  const Configuration shipped = load_configuration(kShippedFile);
  const Configuration defaults;
  for (const SectionSpec& section : param_schema()) {
    ASSERT_EQ(section.entries(shipped), section.entries(defaults)) << section.name;
    for (std::size_t i = 0; i < section.entries(shipped); ++i) {
      for (const ParamSpec& p : section.params) {
        const ParamValue file = p.field.load(section.at_const(shipped, i));
        const ParamValue code = p.field.load(section.at_const(defaults, i));
        EXPECT_TRUE(file == code) << section.name << "[" << i << "]." << p.key << ": the file has "
                                  << format_value(p, file) << ", params.hpp "
                                  << format_value(p, code);
      }
    }
  }
}

TEST(ParamSchema, EveryRowIsComplete) {
  std::set<std::string_view> sections;
  for (const SectionSpec& section : param_schema()) {
    EXPECT_TRUE(sections.insert(section.name).second) << section.name << " twice";
    EXPECT_FALSE(section.about.empty()) << section.name;
    std::set<std::string_view> keys;
    for (const ParamSpec& p : section.params) {
      const std::string name = std::string(section.name) + "." + std::string(p.key);
      EXPECT_TRUE(keys.insert(p.key).second) << name << " twice";
      EXPECT_FALSE(p.about.empty()) << name << " says nothing about itself";
      switch (p.field.kind) {
        case ParamKind::kNumber:
        case ParamKind::kInteger:
          EXPECT_LT(p.min, p.max) << name;
          break;
        case ParamKind::kNumbers:
          EXPECT_LT(p.min, p.max) << name;
          EXPECT_GE(p.count_max(), p.count_min()) << name;
          EXPECT_GT(p.count_max(), 0U) << name;
          break;
        case ParamKind::kText:
          EXPECT_GT(p.max_length, 0U) << name;
          break;
        case ParamKind::kTexts:
          EXPECT_GT(p.max_count, 0U) << name;
          EXPECT_GT(p.max_length, 0U) << name;
          break;
        case ParamKind::kChoice:
          EXPECT_GE(p.choices.size(), 2U) << name;
          break;
        case ParamKind::kBoolean:
          break;
      }
    }
  }
}

// The shipped file with `old_text` (once) replaced, as rover.toml: its problems, and the line the
// replacement stands on.
std::pair<std::vector<std::string>, long> problems_with(const std::string& old_text,
                                                        const std::string& new_text) {
  std::string text = read_text(kShippedFile);
  const auto at = text.find(old_text);
  EXPECT_NE(at, std::string::npos) << old_text;
  if (at == std::string::npos) return {};
  const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
  text.replace(at, old_text.size(), new_text);
  try {
    (void)parse_configuration(text, "rover.toml");
  } catch (const ConfigError& e) {
    return {e.problems(), line};
  }
  ADD_FAILURE() << "no ConfigError";
  return {};
}

// Each problem names the key, the value, the range, and FILE:LINE.
TEST(ParamSchema, ErrorsNameTheFileAndLine) {
  const auto [problems, line] = problems_with("icr = 511                          # PWM period",
                                              "icr = 5                            # PWM period");
  ASSERT_EQ(problems.size(), 1U);
  EXPECT_EQ(problems.front(), "cycle.icr: 5 is out of range; allowed [255, 2047] (rover.toml:" +
                                  std::to_string(line) + ")");
}

// A key spelt wrong is missing under its name and unknown under the other, which names the key
// it meant.
TEST(ParamSchema, AMisspeltKeyNamesTheKeyItMeant) {
  const auto [problems, line] = problems_with("track_width_m = 0.70", "track_wdth_m = 0.70");
  ASSERT_EQ(problems.size(), 2U);
  EXPECT_EQ(problems[0], "geometry.track_width_m: missing; expected a number in [0.1, 3]");
  EXPECT_EQ(problems[1], "geometry.track_wdth_m: unknown key (rover.toml:" + std::to_string(line) +
                             "); did you mean track_width_m?");
}

// A calibration file's bad value is named with the calibration file's line, not the merged
// configuration's (which has none).
TEST(ParamSchema, CalibrationErrorsNameTheCalibrationFileAndLine) {
  const std::string file = ::testing::TempDir() + "param_schema_calibration.toml";
  std::ofstream(file) << "[calibration.voltage]\nsource = \"test\"\n\n[sensors]\n"
                      << "supply_v_per_count = 5.0\n";
  try {
    (void)load_configuration(kShippedFile, file);
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    ASSERT_EQ(e.problems().size(), 1U) << e.what();
    EXPECT_EQ(e.problems().front(),
              "sensors.supply_v_per_count: 5.0 is out of range; allowed [1e-06, "
              "1] (" +
                  file + ":5)");
  }
}

}  // namespace
}  // namespace marsokhod::config
