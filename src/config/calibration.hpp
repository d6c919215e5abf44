// The calibration file: what `marsokhod calibrate` measured, loaded on top of
// config/marsokhod.toml. It uses the configuration's own sections and keys, limited to the values
// a procedure fits (the schema's `calibrated` parameters, param_schema.cpp):
//   [sensors]  accelerometer_minus_g_counts, accelerometer_plus_g_counts     (Procedure 3.3)
//              supply_v_per_count, supply_offset_v                           (Procedure 3.5)
//   [motors]   backlash_rad                                                  (Procedures 4.1/4.3)
//              scale                                                         (Procedure 4.5)
//   [[motor_curve]]  icr, duty, no_load_speed_radps     replaces the table of its icr (4.4)
//   [[response]]     period_s, con, delta   replaces the table of its (h ± 1 ms, con) (4.8)
//   [load]     gain_same_sign_radps_per_nm, gain_opposite_sign_radps_per_nm  (Procedure 4.13)
//   [[load_gain]]    icr, duty, same_sign_radps_per_nm, opposite_sign_radps_per_nm
//                    replaces the B± table of its icr (4.6), Procedure 4.13
//   [sensors]  tilt_front_rad_per_count, tilt_front_offset_rad, tilt_rear_…   (Procedure 3.4)
//   [spin]     slope_per_m, offset                                           (Procedure 5.1)
//   [power]    duty_drop_v, load_drop_v_s2_per_rad2                          ((4.5))
// and [calibration.<procedure>] tables reporting where and how well each was measured. Any other
// key is an error naming it (a calibration must not silently change, say, the safety limits);
// the merged configuration passes the same checks as the file alone.
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "config/configuration.hpp"
#include "config/load_params.hpp"
#include "core/params.hpp"

namespace marsokhod::config {

// The configuration's TOML read by the schema (every key required, ranges, consistency).
Configuration configuration_from_table(const toml::table& root, const std::string& source);
Params params_from_table(const toml::table& root, const std::string& source);

// Problems with a calibration table (unknown sections or keys, wrong shapes); empty when fine.
std::vector<std::string> calibration_problems(const toml::table& calibration);

// `base` with the calibration's values merged in (the [calibration] report table left out).
// Throws ConfigError (source = calibration_source) for the problems above.
toml::table merge_calibration(const toml::table& base, const toml::table& calibration,
                              const std::string& calibration_source);

// TOML text or a file as a table; ConfigError when it is missing (`missing_hint` appended to the
// message) or not TOML.
toml::table parse_toml(std::string_view toml_text, const std::string& source);
toml::table read_toml_file(const std::filesystem::path& file, std::string_view missing_hint = "");

// The configuration file with the calibration file on top. `calibration` names the file and the
// procedures it holds. Throws ConfigError naming the file at fault.
Configuration load_configuration(const std::filesystem::path& config_file,
                                 const std::filesystem::path& calibration_file);
Params load_params(const std::filesystem::path& config_file,
                   const std::filesystem::path& calibration_file);

// The Params a procedure's fitted values would give on top of `config_file` (for tests and for
// checking a result before writing it). Throws ConfigError.
Params apply_calibration_values(const std::filesystem::path& config_file,
                                const toml::table& values);

}  // namespace marsokhod::config
