#include "sim/physics/terrain.hpp"

#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace marsokhod::sim {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
// A slope steeper than this is a wall; a plane at exactly 90° has no height function.
constexpr double kMaxSlopeDeg = 89.0;
constexpr double kMaxLengthM = 1000.0;

// Reads one TOML table; every error names the dotted key and its line, and a key nobody asked
// for is an error too (a typo must not silently fall back to a default).
class TableReader {
 public:
  TableReader(const toml::table& table, std::string path) : table_(table), path_(std::move(path)) {}

  const toml::node* optional(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  const toml::node& required(std::string_view key, std::string_view what) {
    const toml::node* node = optional(key);
    if (node == nullptr) fail(key, "is missing; expected " + std::string(what), nullptr);
    return *node;
  }

  double number(std::string_view key, double min, double max) {
    return checked_number(required(key, "a number"), key, min, max);
  }

  double number_or(std::string_view key, double min, double max, double fallback) {
    const toml::node* node = optional(key);
    return node == nullptr ? fallback : checked_number(*node, key, min, max);
  }

  template <std::size_t N>
  std::array<double, N> numbers(std::string_view key, double min, double max) {
    return checked_numbers<N>(required(key, "an array of numbers"), key, min, max);
  }

  template <std::size_t N>
  std::array<double, N> numbers_or(std::string_view key, double min, double max) {
    const toml::node* node = optional(key);
    return node == nullptr ? std::array<double, N>{} : checked_numbers<N>(*node, key, min, max);
  }

  std::optional<bool> boolean_or_none(std::string_view key) {
    const toml::node* node = optional(key);
    if (node == nullptr) return std::nullopt;
    const toml::value<bool>* value = node->as_boolean();  // value<bool>() would take a 1 too
    if (value == nullptr) fail(key, "must be true or false", node);
    return value->get();
  }

  std::string choice(std::string_view key, std::initializer_list<std::string_view> allowed) {
    const toml::node& node = required(key, "a string");
    const std::optional<std::string> value = node.value<std::string>();
    for (std::string_view option : allowed) {
      if (value && *value == option) return *value;
    }
    std::string list;
    for (std::string_view option : allowed)
      list += (list.empty() ? "\"" : ", \"") + std::string(option) + "\"";
    fail(key, "must be one of " + list, &node);
  }

  void reject_unknown_keys() const {
    for (const auto& [key, node] : table_) {
      if (used_.count(std::string(key.str())) == 0) {
        fail(key.str(), "is not a known key here (a typo?)", &node);
      }
    }
  }

  [[noreturn]] void fail(std::string_view key, const std::string& message,
                         const toml::node* node) const {
    std::ostringstream out;
    out << "scenario " << path_ << '.' << key;
    const toml::source_region& source = node != nullptr ? node->source() : table_.source();
    if (source.begin.line != 0) out << " (line " << source.begin.line << ')';
    out << ' ' << message;
    throw std::invalid_argument(out.str());
  }

  const std::string& path() const { return path_; }

 private:
  double checked_number(const toml::node& node, std::string_view key, double min,
                        double max) const {
    const std::optional<double> value = node.value<double>();  // integers convert too
    if (!value || !std::isfinite(*value)) fail(key, "must be a number", &node);
    if (*value < min || *value > max) {
      std::ostringstream range;
      range << "= " << *value << " is outside [" << min << ", " << max << ']';
      fail(key, range.str(), &node);
    }
    return *value;
  }

  template <std::size_t N>
  std::array<double, N> checked_numbers(const toml::node& node, std::string_view key, double min,
                                        double max) const {
    const toml::array* array = node.as_array();
    if (array == nullptr || array->size() != N) {
      fail(key, "must be an array of " + std::to_string(N) + " numbers", &node);
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
      out[i] =
          checked_number((*array)[i], std::string(key) + "[" + std::to_string(i) + "]", min, max);
    }
    return out;
  }

  const toml::table& table_;
  std::string path_;
  std::set<std::string, std::less<>> used_;
};

Material material_from(const toml::node* node, TableReader& owner, const Material& fallback) {
  if (node == nullptr) return fallback;
  if (const std::optional<std::string> name = node->value<std::string>()) {
    if (const std::optional<Material> named = material_named(*name)) return *named;
    owner.fail("material",
               "= \"" + *name +
                   "\" is unknown; use \"hard\", \"sand\", \"grass\", \"lunar-soil\" or a "
                   "table { friction = …, rolling_friction_m = … }" +
                   retired_material_note(*name),
               node);
  }
  const toml::table* table = node->as_table();
  if (table == nullptr) owner.fail("material", "must be a name or an inline table", node);
  TableReader reader(*table, owner.path() + ".material");
  Material material;
  material.sliding_friction = reader.number("friction", 0.0, 10.0);
  material.torsional_friction_m = reader.number_or("torsional_friction_m", 0.0, 1.0, 0.0);
  material.rolling_friction_m = reader.number_or("rolling_friction_m", 0.0, 1.0, 0.0);
  reader.reject_unknown_keys();
  return material;
}

Obstacle obstacle_from(const toml::table& table, const std::string& path, const Material& ground) {
  TableReader reader(table, path);
  Obstacle obstacle;
  const std::string shape = reader.choice("shape", {"box", "cylinder"});
  obstacle.shape = shape == "box" ? ObstacleShape::kBox : ObstacleShape::kCylinder;
  obstacle.center_m = reader.numbers<3>("center_m", -kMaxLengthM, kMaxLengthM);
  if (obstacle.shape == ObstacleShape::kBox) {
    obstacle.box_size_m = reader.numbers<3>("size_m", 1e-3, kMaxLengthM);
  } else {
    obstacle.cylinder_radius_m = reader.number("radius_m", 1e-3, kMaxLengthM);
    obstacle.cylinder_length_m = reader.number("length_m", 1e-3, kMaxLengthM);
  }
  const std::array<double, 3> orientation_deg = reader.numbers_or<3>("orientation_deg", -360, 360);
  for (std::size_t i = 0; i < 3; ++i)
    obstacle.roll_pitch_yaw_rad[i] = orientation_deg[i] * kRadPerDeg;
  obstacle.material = material_from(reader.optional("material"), reader, ground);
  reader.reject_unknown_keys();
  return obstacle;
}

void read_obstacles(TableReader& reader, TerrainSpec& terrain) {
  const toml::node* node = reader.optional("obstacles");
  if (node == nullptr) {
    if (terrain.kind == TerrainKind::kObstacles) {
      reader.fail("obstacles",
                  "is missing; kind = \"obstacles\" needs at least one "
                  "[[terrain.obstacles]]",
                  nullptr);
    }
    return;
  }
  const toml::array* array = node->as_array();
  if (array == nullptr || (terrain.kind == TerrainKind::kObstacles && array->empty())) {
    reader.fail("obstacles", "must be an array of tables ([[terrain.obstacles]]), at least one",
                node);
  }
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::string path = reader.path() + ".obstacles[" + std::to_string(i) + "]";
    const toml::table* table = (*array)[i].as_table();
    if (table == nullptr)
      reader.fail("obstacles", "entry " + std::to_string(i) + " is not a table", node);
    terrain.obstacles.push_back(obstacle_from(*table, path, terrain.ground));
  }
}

void read_heightfield(TableReader& reader, const std::filesystem::path& base_dir,
                      Heightfield& heightfield) {
  const toml::node& image = reader.required("image", "the path of a PGM image");
  const std::optional<std::string> name = image.value<std::string>();
  if (!name || name->empty()) reader.fail("image", "must be the path of a PGM image", &image);
  const std::filesystem::path path =
      std::filesystem::path(*name).is_absolute() ? std::filesystem::path(*name) : base_dir / *name;
  try {
    heightfield.image = read_pgm(path);
  } catch (const std::invalid_argument& e) {
    reader.fail("image", std::string(": ") + e.what(), &image);
  }
  const std::array<double, 2> size_m = reader.numbers<2>("size_m", 0.1, kMaxLengthM);
  heightfield.size_x_m = size_m[0];
  heightfield.size_y_m = size_m[1];
  heightfield.max_height_m = reader.number("max_height_m", 1e-3, 100.0);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("terrain: " + what);
}

void validate_material(const Material& material, const std::string& where) {
  require(std::isfinite(material.sliding_friction) && material.sliding_friction >= 0.0 &&
              std::isfinite(material.torsional_friction_m) &&
              material.torsional_friction_m >= 0.0 && std::isfinite(material.rolling_friction_m) &&
              material.rolling_friction_m >= 0.0,
          where + " friction coefficients must be finite and not negative");
}

void validate_obstacle(const Obstacle& obstacle, const std::string& where) {
  bool finite = true;
  for (double v : obstacle.center_m) finite = finite && std::isfinite(v);
  for (double v : obstacle.roll_pitch_yaw_rad) finite = finite && std::isfinite(v);
  require(finite, where + " has a non-finite center or orientation");
  if (obstacle.shape == ObstacleShape::kBox) {
    for (double v : obstacle.box_size_m)
      require(v > 0.0 && std::isfinite(v), where + " box size must be positive");
  } else {
    require(obstacle.cylinder_radius_m > 0.0 && std::isfinite(obstacle.cylinder_radius_m) &&
                obstacle.cylinder_length_m > 0.0 && std::isfinite(obstacle.cylinder_length_m),
            where + " cylinder radius and length must be positive");
  }
  validate_material(obstacle.material, where);
}

void validate_heightfield(const Heightfield& field) {
  const GrayImage& image = field.image;
  require(
      image.width >= 2 && image.height >= 2 && image.values.size() == image.width * image.height,
      "the heightfield image needs at least 2x2 pixels and width·height values");
  for (double v : image.values)
    require(v >= 0.0 && v <= 1.0, "heightfield values must lie in [0, 1]");
  require(field.size_x_m > 0.0 && field.size_y_m > 0.0 && std::isfinite(field.size_x_m) &&
              std::isfinite(field.size_y_m),
          "the heightfield size must be positive");
  require(field.max_height_m > 0.0 && std::isfinite(field.max_height_m),
          "the heightfield's max height must be positive");
}

}  // namespace

Material hard_ground() { return Material{0.9, 0.0, 0.0}; }

Material grass() { return Material{1.2, 0.0, 0.01}; }

Material sand() {
  Material material{0.5, 0.0, 0.0};
  material.soil = soil::dry_sand();
  return material;
}

std::string retired_material_note(std::string_view name) {
  if (name == "soft-sand") return " (\"soft-sand\" is now called \"sand\")";
  if (name == "rigid-sand") {
    return " (\"rigid-sand\", the rigid contact sand had before the soil model, is gone since "
           "2026-11-29: \"sand\" is the soil model)";
  }
  return "";
}

std::optional<Material> material_named(std::string_view name) {
  if (name == "hard") return hard_ground();
  if (name == "grass") return grass();
  if (name == "sand") return sand();
  if (name == "lunar-soil") return soft_lunar_soil();
  return std::nullopt;
}

Material soft_lunar_soil() {
  Material material{0.5, 0.0, 0.0};
  material.soil = soil::lunar_soil();
  return material;
}

std::string to_string(TerrainKind kind) {
  switch (kind) {
    case TerrainKind::kFlat:
      return "flat";
    case TerrainKind::kSlope:
      return "slope";
    case TerrainKind::kObstacles:
      return "obstacles";
    case TerrainKind::kHeightfield:
      return "heightfield";
  }
  return "unknown";
}

void validate(const TerrainSpec& terrain) {
  validate_material(terrain.ground, "the ground's");
  if (terrain.kind == TerrainKind::kSlope) {
    require(std::isfinite(terrain.slope_rad) &&
                std::abs(terrain.slope_rad) < kMaxSlopeDeg * kRadPerDeg + 1e-12,
            "the slope must lie within ±89°");
  }
  if (terrain.kind == TerrainKind::kObstacles) {
    require(!terrain.obstacles.empty(), "an obstacle course needs at least one obstacle");
  }
  for (std::size_t i = 0; i < terrain.obstacles.size(); ++i) {
    validate_obstacle(terrain.obstacles[i], "obstacle " + std::to_string(i));
  }
  if (terrain.kind == TerrainKind::kHeightfield) validate_heightfield(terrain.heightfield);
  if (terrain.ground.soil) soil::validate(*terrain.ground.soil);
}

TerrainSpec terrain_from_toml(const toml::table& terrain_table,
                              const std::filesystem::path& base_dir) {
  TableReader reader(terrain_table, "terrain");
  TerrainSpec terrain;
  const std::string kind = reader.choice("kind", {"flat", "slope", "obstacles", "heightfield"});
  if (kind == "slope") terrain.kind = TerrainKind::kSlope;
  if (kind == "obstacles") terrain.kind = TerrainKind::kObstacles;
  if (kind == "heightfield") terrain.kind = TerrainKind::kHeightfield;
  terrain.ground = material_from(reader.optional("material"), reader, hard_ground());
  if (const std::optional<bool> memory = reader.boolean_or_none("shear_reload_memory")) {
    if (!terrain.ground.soil) {
      reader.fail("shear_reload_memory",
                  "applies to a soft soil only (material \"sand\" or \"lunar-soil\")", nullptr);
    }
    terrain.ground.soil->tangential_reload_memory = *memory;
  }
  if (terrain.kind == TerrainKind::kSlope) {
    terrain.slope_rad = reader.number("slope_deg", -kMaxSlopeDeg, kMaxSlopeDeg) * kRadPerDeg;
  }
  if (terrain.kind == TerrainKind::kHeightfield)
    read_heightfield(reader, base_dir, terrain.heightfield);
  read_obstacles(reader, terrain);
  reader.reject_unknown_keys();
  validate(terrain);
  return terrain;
}

}  // namespace marsokhod::sim
