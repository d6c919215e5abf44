#include "runner/scenario.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "runner/operator_log.hpp"
#include "sim/physics/terrain.hpp"

namespace marsokhod::runner {
namespace {

using nlohmann::json;

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what,
                         const toml::node* node = nullptr) const {
    std::string where;
    if (node != nullptr && node->source().begin.line > 0) {
      where = " (line " + std::to_string(node->source().begin.line) + ")";
    }
    throw std::invalid_argument(file_ + ": " + key + ": " + what + where);
  }

  double number(const toml::table& t, const std::string& key, double fallback,
                const std::string& prefix = "") const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return fallback;
    if (!n->is_number()) fail(prefix + key, "expected a number", n);
    return n->value<double>().value_or(fallback);
  }

  std::vector<std::size_t> indices(const toml::table& t, const std::string& key, std::size_t limit,
                                   const std::string& prefix) const {
    std::vector<std::size_t> out;
    const toml::node* n = t.get(key);
    if (n == nullptr) return out;
    const toml::array* a = n->as_array();
    if (a == nullptr) fail(prefix + key, "expected an array of indices", n);
    for (const toml::node& item : *a) {
      const auto v = item.value<std::int64_t>();
      if (!v || *v < 0 || static_cast<std::size_t>(*v) >= limit) {
        fail(prefix + key, "indices must be integers 0.." + std::to_string(limit - 1), &item);
      }
      out.push_back(static_cast<std::size_t>(*v));
    }
    return out;
  }

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

json to_nlohmann(const toml::node& node) {
  std::ostringstream text;
  if (const auto* t = node.as_table()) {
    text << toml::json_formatter{*t};
  } else if (const auto* a = node.as_array()) {
    text << toml::json_formatter{*a};
  } else {
    node.visit([&text](const auto& v) { text << toml::json_formatter{toml::table{{"v", v}}}; });
    return json::parse(text.str())["v"];
  }
  return json::parse(text.str());
}

void read_sim(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::table* sim = root["sim"].as_table();
  if (sim == nullptr) return;
  for (const auto& [key, node] : *sim) {
    const std::string k(key.str());
    if (k == "supply") {
      const auto v = node.value<std::string>();
      if (v == "battery") s.sim.supply = sim::SupplyKind::kBattery;
      else if (v == "tether") s.sim.supply = sim::SupplyKind::kTether;
      else r.fail("sim.supply", "expected \"battery\" or \"tether\"", &node);
    } else if (k == "nominal_unit") {
      const auto v = node.value<bool>();
      if (!v) r.fail("sim.nominal_unit", "expected true or false", &node);
      s.sim.nominal_unit = *v;
    } else if (k == "state_of_charge") {
      const double v = r.number(*sim, k, 0.8, "sim.");
      if (v < 0.0 || v > 1.0) r.fail("sim.state_of_charge", "allowed [0, 1]", &node);
      s.state_of_charge = v;
    } else {
      r.fail("sim." + k, "unknown key", &node);
    }
  }
}

void read_inputs(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* inputs = root["input"].as_array();
  if (inputs == nullptr) return;
  for (std::size_t i = 0; i < inputs->size(); ++i) {
    const toml::table* t = (*inputs)[i].as_table();
    const std::string name = "input[" + std::to_string(i) + "].";
    if (t == nullptr) r.fail(name, "expected a table [[input]]");
    InputEvent e;
    e.t_s = r.number(*t, "t", -1.0, name);
    if (e.t_s < 0.0) r.fail(name + "t", "a time ≥ 0 s is required", t);
    json j = json::object();
    for (const auto& [key, node] : *t) {
      const std::string k(key.str());
      if (k == "t" || k == "silent") continue;
      j[k] = to_nlohmann(node);
    }
    const bool silent = t->get("silent") != nullptr && t->get("silent")->value_or(false);
    if (!silent) {
      try {
        e.input = operator_input_from_json(j);
      } catch (const std::invalid_argument& error) {
        r.fail(name.substr(0, name.size() - 1), error.what(), t);
      }
    }
    s.inputs.push_back(e);
  }
}

void read_faults(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* faults = root["fault"].as_array();
  if (faults == nullptr) return;
  for (std::size_t i = 0; i < faults->size(); ++i) {
    const toml::table* t = (*faults)[i].as_table();
    const std::string name = "fault[" + std::to_string(i) + "].";
    if (t == nullptr) r.fail(name, "expected a table [[fault]]");
    FaultEvent f;
    for (const auto& [key, node] : *t) {
      const std::string k(key.str());
      if (k == "t") f.t_s = r.number(*t, k, 0.0, name);
      else if (k == "wheel_blocked") f.wheel_blocked = r.indices(*t, k, kWheelCount, name);
      else if (k == "wheel_no_contact") f.wheel_no_contact = r.indices(*t, k, kWheelCount, name);
      else if (k == "silent") f.silent = r.indices(*t, k, kMotorCount + 1, name);
      else if (k == "frame_loss") f.frame_loss = r.number(*t, k, 0.0, name);
      else if (k == "battery_sag_ohm") f.battery_sag_ohm = r.number(*t, k, 0.0, name);
      else if (k == "brownout") f.brownout = node.value_or(false);
      else if (k == "driver_halt") f.driver_halt = node.value_or(false);
      else if (k == "clear") f.clear = node.value_or(false);
      else if (k == "lost_pulses") {
        const toml::table* lp = node.as_table();
        const auto motor = lp != nullptr && lp->get("motor") ? lp->get("motor")->value<std::int64_t>()
                                                             : std::optional<std::int64_t>{};
        if (!motor || *motor < 0 || *motor >= static_cast<std::int64_t>(kMotorCount)) {
          r.fail(name + k, "expected {motor = 0..7, fraction = 0..1}", &node);
        }
        f.lost_pulses = std::make_pair(static_cast<std::size_t>(*motor),
                                       r.number(*lp, "fraction", 0.0, name + k + "."));
      } else {
        r.fail(name + k, "unknown key", &node);
      }
    }
    s.faults.push_back(f);
  }
}

void read_checks(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* checks = root["check"].as_array();
  if (checks == nullptr) return;
  for (std::size_t i = 0; i < checks->size(); ++i) {
    const toml::table* t = (*checks)[i].as_table();
    const std::string name = "check[" + std::to_string(i) + "].";
    if (t == nullptr) r.fail(name, "expected a table [[check]]");
    Check c;
    c.name = t->get("name") ? t->get("name")->value_or<std::string>("") : "";
    c.metric = t->get("metric") ? t->get("metric")->value_or<std::string>("") : "";
    if (c.metric.empty()) r.fail(name + "metric", "a metric name is required", t);
    if (c.name.empty()) c.name = c.metric;
    if (t->get("min")) c.min = r.number(*t, "min", 0.0, name);
    if (t->get("max")) c.max = r.number(*t, "max", 0.0, name);
    if (!c.min && !c.max) r.fail(name, "give min, max or both", t);
    s.checks.push_back(c);
  }
}

void read_runtime(const Reader& r, const toml::table& root, Scenario& s) {
  if (const toml::table* rt = root["runtime"].as_table()) s.runtime = to_nlohmann(*rt);
  const toml::array* changes = root["runtime_change"].as_array();
  if (changes == nullptr) return;
  for (std::size_t i = 0; i < changes->size(); ++i) {
    const toml::table* t = (*changes)[i].as_table();
    if (t == nullptr) r.fail("runtime_change[" + std::to_string(i) + "]", "expected a table");
    RuntimeEvent e;
    e.t_s = r.number(*t, "t", 0.0, "runtime_change.");
    e.settings = to_nlohmann(*t);
    e.settings.erase("t");
    s.runtime_changes.push_back(e);
  }
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) {
  const Reader r(file.string());
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    r.fail("(file)", std::string(e.description()) + " at line " +
                         std::to_string(e.source().begin.line));
  }
  static const std::vector<std::string> kKeys = {"name", "description", "duration_s", "seed",
                                                 "sim", "terrain", "runtime", "input", "fault",
                                                 "runtime_change", "check"};
  for (const auto& [key, node] : root) {
    if (std::find(kKeys.begin(), kKeys.end(), key.str()) == kKeys.end()) {
      r.fail(std::string(key.str()), "unknown key", &node);
    }
  }
  Scenario s;
  s.file = file;
  s.name = root["name"].value_or(file.stem().string());
  s.description = root["description"].value_or(std::string());
  s.duration_s = r.number(root, "duration_s", 10.0);
  if (!(s.duration_s > 0.0 && s.duration_s <= 3600.0)) r.fail("duration_s", "allowed (0, 3600] s");
  s.seed = static_cast<std::uint64_t>(root["seed"].value_or<std::int64_t>(1));
  read_sim(r, root, s);
  if (const toml::table* terrain = root["terrain"].as_table()) {
    try {
      s.sim.terrain = sim::terrain_from_toml(*terrain, file.parent_path());
    } catch (const std::invalid_argument& e) {
      r.fail("terrain", e.what());
    }
  }
  read_runtime(r, root, s);
  read_inputs(r, root, s);
  read_faults(r, root, s);
  read_checks(r, root, s);
  auto by_time = [](const auto& a, const auto& b) { return a.t_s < b.t_s; };
  std::stable_sort(s.inputs.begin(), s.inputs.end(), by_time);
  std::stable_sort(s.faults.begin(), s.faults.end(), by_time);
  std::stable_sort(s.runtime_changes.begin(), s.runtime_changes.end(), by_time);
  return s;
}

std::vector<std::pair<std::string, std::filesystem::path>> list_scenarios(
    const std::filesystem::path& folder) {
  std::vector<std::pair<std::string, std::filesystem::path>> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    if (entry.path().extension() == ".toml") out.emplace_back(entry.path().stem().string(), entry.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace marsokhod::runner
