#include "runner/scenario.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "config/config_reader.hpp"
#include "runner/metrics.hpp"
#include "link/command_json.hpp"
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

  // The configuration reader's check (finite, in [min, max], the line named); absent: fallback.
  double number(const toml::table& t, const std::string& key, double fallback, double min,
                double max, const std::string& prefix = "") const {
    if (t.get(key) == nullptr) return fallback;
    std::vector<std::string> problems;
    const std::string path = prefix.empty() ? "" : prefix.substr(0, prefix.size() - 1);
    config::ConfigReader reader(&t, path, problems);
    const double value = reader.number(key, min, max);
    if (!problems.empty()) throw std::invalid_argument(file_ + ": " + problems.front());
    return value;
  }

  // Anything in the file that is NaN or ±inf, named by its key, before any value is used: toml
  // reads nan and inf, and nothing in a scenario means them.
  void reject_non_finite(const toml::node& node, const std::string& key) const {
    if (const auto* value = node.as_floating_point()) {
      if (!std::isfinite(value->get())) fail(key, "is not a finite number", &node);
    } else if (const auto* table = node.as_table()) {
      for (const auto& [k, child] : *table) {
        reject_non_finite(child, (key.empty() ? "" : key + ".") + std::string(k.str()));
      }
    } else if (const auto* array = node.as_array()) {
      for (std::size_t i = 0; i < array->size(); ++i) {
        reject_non_finite(*array->get(i), key + "[" + std::to_string(i) + "]");
      }
    }
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

// The [[name]] tables of the file, or none; anything else under that key is an error.
const toml::array* table_array(const Reader& r, const toml::table& root, const std::string& key) {
  const toml::node* node = root.get(key);
  if (node == nullptr) return nullptr;
  const toml::array* array = node->as_array();
  if (array == nullptr || !array->is_array_of_tables()) {
    r.fail(key, "expected tables [[" + key + "]]", node);
  }
  return array;
}

void reject_unknown_keys(const Reader& r, const toml::table& t, const std::string& prefix,
                         std::initializer_list<std::string_view> known) {
  for (const auto& [key, node] : t) {
    if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
      r.fail(prefix + std::string(key.str()), "unknown key", &node);
    }
  }
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
      s.state_of_charge = r.number(*sim, k, 0.8, 0.0, 1.0, "sim.");
    } else {
      r.fail("sim." + k, "unknown key", &node);
    }
  }
}

void read_inputs(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* inputs = table_array(r, root, "input");
  if (inputs == nullptr) return;
  for (std::size_t i = 0; i < inputs->size(); ++i) {
    const toml::table* t = (*inputs)[i].as_table();
    const std::string name = "input[" + std::to_string(i) + "].";
    InputEvent e;
    if (t->get("t") == nullptr) r.fail(name + "t", "a time ≥ 0 s is required", t);
    e.t_s = r.number(*t, "t", 0.0, 0.0, s.duration_s, name);
    json j = json::object();
    for (const auto& [key, node] : *t) {
      const std::string k(key.str());
      if (k == "t" || k == "silent") continue;
      j[k] = to_nlohmann(node);
    }
    const bool silent = t->get("silent") != nullptr && t->get("silent")->value_or(false);
    if (!silent) {
      try {
        e.input = link::operator_input_from_json(j);
      } catch (const std::invalid_argument& error) {
        r.fail(name.substr(0, name.size() - 1), error.what(), t);
      }
    }
    s.inputs.push_back(e);
  }
}

void read_faults(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* faults = table_array(r, root, "fault");
  if (faults == nullptr) return;
  for (std::size_t i = 0; i < faults->size(); ++i) {
    const toml::table* t = (*faults)[i].as_table();
    const std::string name = "fault[" + std::to_string(i) + "].";
    FaultEvent f;
    for (const auto& [key, node] : *t) {
      const std::string k(key.str());
      if (k == "t") f.t_s = r.number(*t, k, 0.0, 0.0, s.duration_s, name);
      else if (k == "wheel_blocked") f.wheel_blocked = r.indices(*t, k, kWheelCount, name);
      else if (k == "wheel_no_contact") f.wheel_no_contact = r.indices(*t, k, kWheelCount, name);
      else if (k == "joint_jammed") f.joint_jammed = r.indices(*t, k, 2, name);
      else if (k == "silent") f.silent = r.indices(*t, k, kMotorCount + 1, name);
      else if (k == "frame_loss") f.frame_loss = r.number(*t, k, 0.0, 0.0, 1.0, name);
      // The simulator's bound (SimulatedRover::set_faults), checked here to name the line.
      else if (k == "battery_sag_ohm") f.battery_sag_ohm = r.number(*t, k, 0.0, 0.0, 100.0, name);
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
                                       r.number(*lp, "fraction", 0.0, 0.0, 1.0, name + k + "."));
      } else {
        r.fail(name + k, "unknown key", &node);
      }
    }
    s.faults.push_back(f);
  }
}

void read_phases(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* phases = table_array(r, root, "phase");
  if (phases == nullptr) return;
  for (std::size_t i = 0; i < phases->size(); ++i) {
    const toml::table& t = *(*phases)[i].as_table();
    const std::string name = "phase[" + std::to_string(i) + "].";
    reject_unknown_keys(r, t, name, {"name", "from_s", "to_s"});
    Phase p;
    p.name = t["name"].value_or(std::string());
    const bool valid_name = !p.name.empty() && std::all_of(p.name.begin(), p.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
    });
    if (!valid_name) r.fail(name + "name", "a name of letters, digits, '_' and '-' is required", &t);
    for (const Phase& other : s.phases) {
      if (other.name == p.name) r.fail(name + "name", "\"" + p.name + "\" is used twice", &t);
    }
    p.from_s = r.number(t, "from_s", -1.0, 0.0, 3600.0, name);
    p.to_s = r.number(t, "to_s", -1.0, 0.0, 3600.0, name);
    if (p.from_s < 0.0) r.fail(name + "from_s", "a start time >= 0 s is required", &t);
    if (!(p.to_s > p.from_s && p.to_s <= s.duration_s)) {
      r.fail(name + "to_s", "an end time after from_s and at most duration_s is required", &t);
    }
    s.phases.push_back(p);
  }
}

std::string metric_name(const Reader& r, const toml::node& node, const std::string& key,
                        const Scenario& s) {
  const auto value = node.value<std::string>();
  if (!value || value->empty()) r.fail(key, "expected a metric name", &node);
  if (!is_metric_name(*value, s.phases)) {
    r.fail(key, "\"" + *value + "\" is not a metric (see runner/metrics.hpp; phase metrics are "
                "\"PHASE.metric\" with a [[phase]] of that name)", &node);
  }
  return *value;
}

void read_checks(const Reader& r, const toml::table& root, Scenario& s) {
  const toml::array* checks = table_array(r, root, "check");
  if (checks == nullptr) return;
  for (std::size_t i = 0; i < checks->size(); ++i) {
    const toml::table& t = *(*checks)[i].as_table();
    const std::string name = "check[" + std::to_string(i) + "].";
    reject_unknown_keys(r, t, name, {"name", "metric", "ratio_of", "min", "max"});
    Check c;
    c.name = t["name"].value_or(std::string());
    if (const toml::node* metric = t.get("metric")) c.metric = metric_name(r, *metric, name + "metric", s);
    if (const toml::node* ratio = t.get("ratio_of")) {
      const toml::array* pair = ratio->as_array();
      if (!c.metric.empty() || pair == nullptr || pair->size() != 2) {
        r.fail(name + "ratio_of", "expected two metric names (and no metric key)", ratio);
      }
      c.ratio_of = std::make_pair(metric_name(r, *pair->get(0), name + "ratio_of", s),
                                  metric_name(r, *pair->get(1), name + "ratio_of", s));
      c.metric = c.ratio_of->first + " / " + c.ratio_of->second;
    }
    if (c.metric.empty()) r.fail(name + "metric", "a metric name (or ratio_of) is required", &t);
    if (c.name.empty()) c.name = c.metric;
    if (t.get("min")) c.min = r.number(t, "min", 0.0, -1e300, 1e300, name);
    if (t.get("max")) c.max = r.number(t, "max", 0.0, -1e300, 1e300, name);
    if (!c.min && !c.max) r.fail(name + "min", "give min, max or both", &t);
    if (c.min && c.max && *c.min > *c.max) r.fail(name + "max", "max is below min", &t);
    s.checks.push_back(c);
  }
}

// Settings are checked now, against the defaults, so that a typo names its line.
void check_runtime(const Reader& r, const json& settings, const std::string& key,
                   const toml::node& node) {
  try {
    (void)link::runtime_settings_from_json(settings, driver::RuntimeSettings{});
  } catch (const std::invalid_argument& e) {
    r.fail(key, e.what(), &node);
  }
}

void read_runtime(const Reader& r, const toml::table& root, Scenario& s) {
  if (const toml::node* rt = root.get("runtime")) {
    if (!rt->is_table()) r.fail("runtime", "expected a table [runtime]", rt);
    s.runtime = to_nlohmann(*rt);
    check_runtime(r, s.runtime, "runtime", *rt);
  }
  const toml::array* changes = table_array(r, root, "runtime_change");
  if (changes == nullptr) return;
  for (std::size_t i = 0; i < changes->size(); ++i) {
    const toml::table& t = *(*changes)[i].as_table();
    const std::string name = "runtime_change[" + std::to_string(i) + "]";
    RuntimeEvent e;
    e.t_s = r.number(t, "t", 0.0, 0.0, s.duration_s, name + ".");
    e.settings = to_nlohmann(t);
    e.settings.erase("t");
    check_runtime(r, e.settings, name, t);
    s.runtime_changes.push_back(e);
  }
}

}  // namespace

Scenario load_scenario(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::invalid_argument(file.string() + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_scenario(text.str(), file);
}

Scenario parse_scenario(std::string_view text, const std::filesystem::path& file) {
  const Reader r(file.string());
  toml::table root;
  try {
    root = toml::parse(text, file.string());
  } catch (const toml::parse_error& e) {
    r.fail("(file)", std::string(e.description()) + " at line " +
                         std::to_string(e.source().begin.line));
  }
  static const std::vector<std::string> kKeys = {"name", "description", "duration_s", "seed",
                                                 "sim", "terrain", "runtime", "input", "fault",
                                                 "runtime_change", "phase", "check"};
  for (const auto& [key, node] : root) {
    if (std::find(kKeys.begin(), kKeys.end(), key.str()) == kKeys.end()) {
      r.fail(std::string(key.str()), "unknown key", &node);
    }
  }
  r.reject_non_finite(root, "");
  Scenario s;
  s.file = file;
  s.name = root["name"].value_or(file.stem().string());
  s.description = root["description"].value_or(std::string());
  s.duration_s = r.number(root, "duration_s", 10.0, 0.0, 3600.0);
  if (!(s.duration_s > 0.0)) r.fail("duration_s", "allowed (0, 3600] s");
  if (const toml::node* seed = root.get("seed")) {
    const auto value = seed->value<std::int64_t>();
    if (!seed->is_integer() || !value || *value < 0) {
      r.fail("seed", "expected an integer ≥ 0", seed);  // a negative one would wrap around
    }
    s.seed = static_cast<std::uint64_t>(*value);
  }
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
  read_phases(r, root, s);
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
