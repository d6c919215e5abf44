#include "app/soak_command.hpp"

#include <CLI/CLI.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "runner/soak.hpp"

namespace marsokhod::app {
namespace {

constexpr int kUsageError = 2;

std::optional<std::uint64_t> parse_seed(const std::string& text) {
  if (text.empty() || text.size() > 19 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); })) {
    return std::nullopt;
  }
  return std::stoull(text);
}

// "t = 92.7420 s (segment 1 on sand, session t = 2.7456 s)": where in the soak a cycle was.
std::string soak_time(const runner::SoakViolation& v) {
  char text[120];
  std::snprintf(text, sizeof text, "t = %.4f s (segment %zu on %s, session t = %.4f s)",
                v.soak_time_s, v.segment, v.sand ? "sand" : "hard ground",
                static_cast<double>(v.violation.time_us) * 1e-6);
  return text;
}

std::string violation_line(std::uint64_t seed, const runner::SoakViolation& v) {
  return "violation: seed " + std::to_string(seed) + ", " + soak_time(v) + ", invariant " +
         runner::invariant_name(v.violation.invariant) + ": " + v.violation.detail;
}

void print_summary(const runner::SoakResult& r, std::ostream& out) {
  char line[512];
  std::snprintf(line, sizeof line,
                "soak seed %llu: %.3f h simulated (%zu segments, hard ground and sand) in %.1f s "
                "(%.1f× real time)\n",
                static_cast<unsigned long long>(r.seed), r.sim_hours, r.segments, r.wall_time_s,
                r.real_time_factor);
  out << line << "faults injected (count, time on):\n";
  for (std::size_t k = 0; k < runner::kFaultKindCount; ++k) {
    std::snprintf(line, sizeof line, "  %-18s %5llu  %8.1f s\n",
                  runner::fault_kind_name(static_cast<runner::FaultKind>(k)),
                  static_cast<unsigned long long>(r.faults_injected[k]), r.fault_active_s[k]);
    out << line;
  }
  const runner::OperatorStats& o = r.operator_stats;
  std::snprintf(line, sizeof line,
                "operator: %llu commands, %llu silences (%llu beyond the timeout), %llu hand-overs, "
                "%llu fault clears; driver restarts %llu; \"silent\" faults from lost frames alone "
                "%llu\n",
                static_cast<unsigned long long>(o.commands),
                static_cast<unsigned long long>(o.short_silences + o.long_silences),
                static_cast<unsigned long long>(o.long_silences),
                static_cast<unsigned long long>(o.hand_overs),
                static_cast<unsigned long long>(o.fault_clears),
                static_cast<unsigned long long>(r.driver_restarts),
                static_cast<unsigned long long>(r.spurious_silent_faults));
  out << line;
  std::snprintf(line, sizeof line,
                "missions: %llu sent (%llu heartbeats after them), %llu reached, %llu aborted; "
                "cmd_vel: %llu streams\n",
                static_cast<unsigned long long>(
                    o.activities[static_cast<std::size_t>(runner::Activity::kMission)]),
                static_cast<unsigned long long>(o.heartbeats),
                static_cast<unsigned long long>(r.missions_reached),
                static_cast<unsigned long long>(r.missions_aborted),
                static_cast<unsigned long long>(
                    o.activities[static_cast<std::size_t>(runner::Activity::kVelocity)]));
  out << line;
  std::snprintf(line, sizeof line,
                "invariants checked: %llu over %llu cycles; joints at most %.4f rad outside "
                "(5.3)\n",
                static_cast<unsigned long long>(r.evaluations),
                static_cast<unsigned long long>(r.cycles), r.max_joint_excess_rad);
  out << line;
  if (const auto& at = r.max_joint_excess_at) {
    out << "  the largest excess at " << soak_time(*at) << ": " << at->violation.detail << "\n";
  }
  std::snprintf(line, sizeof line,
                "joints the driver could not know (lost pulses): the truth at most %.4f rad "
                "outside (5.3)\n"
                "joints while the driver was down (their run-on after a brown-out): at most %.4f "
                "rad outside (5.3)\n"
                "violations: %llu\n",
                r.max_unknown_joint_excess_rad, r.max_down_joint_excess_rad,
                static_cast<unsigned long long>(r.total_violations()));
  out << line;
  for (std::size_t k = 0; k < runner::kInvariantCount; ++k) {
    if (r.violations[k] == 0) continue;
    std::snprintf(line, sizeof line, "  %-16s %llu\n",
                  runner::invariant_name(static_cast<runner::Invariant>(k)),
                  static_cast<unsigned long long>(r.violations[k]));
    out << line;
  }
  if (!r.first_violations.empty()) {
    out << "first " << violation_line(r.seed, r.first_violations.front()) << "\n";
  }
  if (r.recording) {
    out << "recording of the last seconds before it: " << r.recording->string()
        << " (marsokhod replay " << r.recording->string() << ")\n";
  }
  if (!r.recording_note.empty()) out << "note: " << r.recording_note << "\n";
  out << (r.total_violations() == 0 ? "passed\n" : "FAILED\n");
}

}  // namespace

CLI::App* add_soak_command(CLI::App& cli, SoakArgs& args) {
  CLI::App* cmd = cli.add_subcommand(
      "soak", "hours of random operation with random faults, every invariant checked each cycle");
  cmd->add_option("--hours", args.hours, "simulated hours (default 1; fractions allowed)");
  cmd->add_option("--seed", args.seed, "the soak's seed, a whole number ≥ 0 (default 1)");
  cmd->add_option("--out", args.out,
                  "where the first violation's recording goes (default soak-seed-N)");
  cmd->add_flag("--json", args.json, "print one JSON object");
  return cmd;
}

int run_soak_command(const SoakArgs& args, const config::LoadedConfig& config, std::ostream& out,
                     std::ostream& err) {
  const auto seed = parse_seed(args.seed);
  if (!seed) {
    err << "marsokhod soak: --seed '" << args.seed << "' is not a whole number ≥ 0\n";
    return kUsageError;
  }
  if (!(args.hours > 0.0 && args.hours <= 1000.0)) {
    err << "marsokhod soak: --hours " << args.hours << " is out of range; allowed (0, 1000]\n";
    return kUsageError;
  }
  runner::SoakOptions options;
  options.hours = args.hours;
  options.seed = *seed;
  options.out = args.out.empty() ? "soak-seed-" + std::to_string(*seed) : args.out;
  options.config_file = config.config_file;
  options.calibration_file = config.calibration_file;
  options.rover_params = &config.nominal;
  std::ostream& progress = args.json ? err : out;
  runner::SoakResult result;
  try {
    result = runner::run_soak(config.params, options, [&](const runner::SoakViolation& v) {
      progress << violation_line(*seed, v) << std::endl;
    });
  } catch (const std::exception& e) {
    err << "marsokhod soak: " << e.what() << "\n";
    return kUsageError;
  }
  if (args.json) {
    out << runner::to_json(result).dump() << "\n";
  } else {
    print_summary(result, out);
  }
  return result.total_violations() == 0 ? 0 : 1;
}

}  // namespace marsokhod::app
