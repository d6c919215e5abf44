#include "app/slope_sweep_command.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <ostream>

#include "app/number_checks.hpp"
#include "runner/slope_sweep.hpp"

namespace marsokhod::app {
namespace {

constexpr int kUsageError = 2;

// [KG92] (chapter 2's Marsokhod trials on granular slopes): what each way of climbing reached.
const char* kg92_figure(mobility::Gait gait) {
  return gait == mobility::Gait::kNone ? "20°" : "25–30° (wheel walking)";
}

}  // namespace

CLI::App* add_slope_sweep_command(CLI::App& cli, SlopeSweepArgs& args) {
  CLI::App* cmd = cli.add_subcommand(
      "slope-sweep",
      "the steepest soft-soil slope the simulated rover climbs by driving and by each gait");
  cmd->add_option("--ground", args.ground, "a soft soil: sand (default) or lunar-soil");
  cmd->add_option("--distance", args.distance_m,
                  "metres along the slope that count as climbed (default 0.1)")
      ->check(finite_range(0.001, 100.0));
  cmd->add_option("--time", args.time_s, "seconds of driving or walking a climb gets (default 40)")
      ->check(finite_range(1.0, 3600.0));
  cmd->add_option("--window", args.window_s,
                  "judge the climb at its end too: the mean position along the slope over the last "
                  "W seconds must also lie --distance ahead of the mean over the W before (default "
                  "0: only the advance over the whole climb)")
      ->check(finite_range(0.0, 1800.0));
  cmd->add_option("--step", args.step_deg, "the angles' resolution in degrees (default 0.5)")
      ->check(finite_range(0.1, 10.0));
  cmd->add_option("--drive", args.drive_radps, "v1 when driving, rad/s (default 1.0)")
      ->check(finite_range(0.01, 100.0));
  cmd->add_option("--modes", args.modes,
                  "the modes to sweep, comma-separated: driving, rolking, front-wheel-walking, "
                  "rear-wheel-walking, worm-like, rolking-extended-base (default: all)")
      ->delimiter(',');
  cmd->add_flag("--shear-reload-memory", args.shear_reload_memory,
                "the soil's tangential shear reloads along the line it unloaded on "
                "(docs/simulator.md, \"The anchors' jitter\"; off by default)");
  return cmd;
}

int run_slope_sweep_command(const SlopeSweepArgs& args, const config::LoadedConfig& config,
                            std::ostream& out, std::ostream& err) {
  const std::optional<sim::Material> ground = sim::material_named(args.ground);
  if (!ground || !ground->soil) {
    err << "marsokhod slope-sweep: --ground " << args.ground
        << " is not a soft soil; use sand or lunar-soil" << sim::retired_material_note(args.ground)
        << "\n";
    return kUsageError;
  }
  if (2.0 * args.window_s > args.time_s) {
    err << "marsokhod slope-sweep: --window " << args.window_s << " is longer than half of --time "
        << args.time_s << " (the two windows it compares must fit into the climb)\n";
    return kUsageError;
  }
  if (args.drive_radps > config.params.operator_input.max_drive_speed_radps) {
    err << "marsokhod slope-sweep: --drive " << args.drive_radps << " exceeds max_drive_speed_radps "
        << config.params.operator_input.max_drive_speed_radps << "\n";
    return kUsageError;
  }
  std::vector<mobility::Gait> modes;
  for (const std::string& name : args.modes) {
    const std::optional<mobility::Gait> gait =
        name == "driving" ? std::optional{mobility::Gait::kNone} : mobility::gait_from_id(name);
    if (!gait) {
      err << "marsokhod slope-sweep: --modes: unknown mode \"" << name
          << "\"; use driving, rolking, front-wheel-walking, rear-wheel-walking, worm-like or "
             "rolking-extended-base\n";
      return kUsageError;
    }
    if (std::find(modes.begin(), modes.end(), *gait) == modes.end()) modes.push_back(*gait);
  }
  if (modes.empty()) modes.assign(mobility::kAllGaits.begin(), mobility::kAllGaits.end());
  const double repose_deg = ground->soil->repose_angle_rad * 180.0 / std::numbers::pi;
  runner::ClimbSpec spec;
  spec.ground = *ground;
  spec.ground.soil->tangential_reload_memory = args.shear_reload_memory;
  spec.drive_radps = args.drive_radps;
  spec.time_s = args.time_s;
  spec.distance_m = args.distance_m;
  spec.seed = args.seed;
  spec.window_s = args.window_s;
  char line[400];
  char criterion[160];
  if (args.window_s > 0.0) {
    std::snprintf(criterion, sizeof criterion,
                  "%.2f m along the slope in %.0f s and still as much between the mean positions "
                  "of its last two %.0f-s windows",
                  args.distance_m, args.time_s, args.window_s);
  } else {
    std::snprintf(criterion, sizeof criterion, "%.2f m along the slope in %.0f s", args.distance_m,
                  args.time_s);
  }
  std::snprintf(line, sizeof line,
                "slope sweep on %s%s (angle of repose %.1f°), unit %llu: climbed = %s (driving "
                "at v1 = %.2f rad/s, gaits at full speed), %.1f° steps\n",
                args.ground.c_str(),
                args.shear_reload_memory ? " with the shear's reload memory" : "", repose_deg,
                static_cast<unsigned long long>(args.seed), criterion, args.drive_radps,
                args.step_deg);
  out << line << "| mode | steepest climbed | [KG92] | angles tried (° climbed/failed, advance) |\n"
      << "|---|---|---|---|\n";
  std::optional<double> driving_deg, best_gait_deg;
  bool past_repose = false;
  try {
    for (const mobility::Gait gait : modes) {
      std::string tried;
      const runner::SteepestClimb found = runner::find_steepest(
          [&](double angle_deg) {
            double advanced = 0.0;
            const bool climbed = runner::run_slope_climb(gait, angle_deg, spec, config.params,
                                                         &config.nominal, &advanced);
            char entry[64];
            std::snprintf(entry, sizeof entry, "%s%.1f %s %.3f m", tried.empty() ? "" : ", ",
                          angle_deg, climbed ? "✓" : "✗", advanced);
            tried += entry;
            return climbed;
          },
          repose_deg, args.step_deg);
      const std::string mode =
          gait == mobility::Gait::kNone ? "driving" : std::string(mobility::gait_name(gait));
      std::string steepest = "none";
      if (found.steepest_deg) {
        std::snprintf(line, sizeof line, "%.1f°%s", *found.steepest_deg,
                      found.climbs_at_max ? " (the angle of repose)" : "");
        steepest = line;
      }
      out << "| " << mode << " | " << steepest << " | " << kg92_figure(gait) << " | " << tried
          << " |" << std::endl;
      const double reached = found.steepest_deg.value_or(-1.0);
      if (gait == mobility::Gait::kNone) {
        driving_deg = reached;
      } else if (!best_gait_deg || reached > *best_gait_deg) {
        best_gait_deg = reached;
      }
      past_repose = past_repose || reached > repose_deg;
    }
  } catch (const std::exception& e) {
    err << "marsokhod slope-sweep: " << e.what() << "\n";
    return kUsageError;
  }
  if (driving_deg && best_gait_deg) {  // both swept
    out << "wheel walking out-climbs driving: "
        << (*best_gait_deg > *driving_deg ? "yes" : "no") << "\n";
  }
  out << "nothing climbed past the angle of repose: " << (past_repose ? "no" : "yes") << "\n";
  return 0;
}

}  // namespace marsokhod::app
