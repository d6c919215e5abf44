#include "calibration/calibration_file.hpp"

#include <chrono>
#include <ctime>
#include <fstream>

#include "config/calibration.hpp"

namespace marsokhod::calibration {
namespace {

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : "; ") + p;
  return out;
}

toml::date_time now_utc() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  return toml::date_time{
      toml::date{tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday},
      toml::time{static_cast<std::uint8_t>(tm.tm_hour), static_cast<std::uint8_t>(tm.tm_min),
                 static_cast<std::uint8_t>(tm.tm_sec)},
      toml::time_offset{}};
}

}  // namespace

void write_calibration(const std::filesystem::path& file, const ProcedureResult& result,
                       const std::filesystem::path& config_file, const std::string& source,
                       bool force) {
  const std::string what = "calibrate " + result.procedure;
  if (!result.accepted()) {
    throw CalibrationRefused(what + ": the fit is poor, nothing written: " +
                             joined(result.problems));
  }
  std::error_code ec;
  const bool exists = std::filesystem::exists(file, ec);
  if (exists && !force) {
    throw CalibrationRefused(what + ": " + file.string() +
                             " exists; pass --force to update it (the other procedures' values "
                             "in it are kept)");
  }
  toml::table existing;
  if (exists) {
    try {
      existing = config::read_toml_file(file);
      const std::vector<std::string> problems = config::calibration_problems(existing);
      if (!problems.empty()) throw config::ConfigError(file.string(), problems);
    } catch (const config::ConfigError& e) {
      throw CalibrationRefused(what + ": the existing file is not a calibration file, left as it "
                               "is: " + e.what());
    }
  }
  toml::table reports;
  if (const toml::table* old = existing["calibration"].as_table()) reports = *old;
  toml::table report;
  report.insert_or_assign("reference", result.reference);
  report.insert_or_assign("source", source);
  report.insert_or_assign("written_utc", now_utc());
  for (const auto& [name, value] : result.quality) report.insert_or_assign(name, value);
  reports.insert_or_assign(result.procedure, std::move(report));

  toml::table updated;
  try {
    updated = config::merge_calibration(existing, result.values, what);
    updated.insert_or_assign("calibration", std::move(reports));
    // What the driver will load must load: the whole file on top of the configuration.
    (void)config::params_from_table(
        config::merge_calibration(config::read_toml_file(config_file), updated, file.string()),
        config_file.string() + " with " + file.string());
  } catch (const config::ConfigError& e) {
    throw CalibrationRefused(what + ": the configuration would not accept the values, nothing "
                             "written: " + e.what());
  }

  const std::filesystem::path temporary = file.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!out) throw CalibrationRefused(what + ": cannot write " + temporary.string());
    out << "# Marsokhod calibration, written by `marsokhod calibrate` (docs/calibration.md).\n"
        << "# Load it on top of the configuration with --calibration " << file.string() << ".\n"
        << "# Values use config/marsokhod.toml's sections and keys; [calibration.*] reports\n"
        << "# where and how well each procedure measured them.\n\n"
        << updated << '\n';
    if (!out) throw CalibrationRefused(what + ": cannot write " + temporary.string());
  }
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    throw CalibrationRefused(what + ": cannot replace " + file.string() + ": " + ec.message());
  }
}

}  // namespace marsokhod::calibration
