// The calibration file: written only for good fits, never over an existing file without
// --force, merged with what other procedures wrote, and loaded by the configuration loader on
// top of config/marsokhod.toml (which reports the file and its procedures).
#include "calibration/calibration_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/calibration.hpp"

namespace marsokhod::calibration {
namespace {

namespace fs = std::filesystem;
const fs::path kConfig = MARSOKHOD_SOURCE_DIR "/config/marsokhod.toml";

class CalibrationFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("marsokhod-calibration-" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

ProcedureResult voltage_result(double gain, double offset) {
  ProcedureResult r;
  r.procedure = "voltage";
  r.reference = "Procedure 3.5";
  toml::table sensors;
  sensors.insert_or_assign("supply_v_per_count", gain);
  sensors.insert_or_assign("supply_offset_v", offset);
  r.values.insert_or_assign("sensors", std::move(sensors));
  r.quality["rms_residual_v"] = 0.01;
  return r;
}

ProcedureResult curve_result(int icr, double top) {
  ProcedureResult r;
  r.procedure = "motor-curve";
  r.reference = "Procedure 4.4";
  toml::table curve;
  curve.insert_or_assign("icr", icr);
  curve.insert_or_assign("duty", toml::array{0.0, 0.5, 1.0});
  curve.insert_or_assign("no_load_speed_radps", toml::array{0.0, 1.4, top});
  toml::array curves;
  curves.push_back(std::move(curve));
  r.values.insert_or_assign("motor_curve", std::move(curves));
  return r;
}

TEST_F(CalibrationFile, WritesALoadableFileThatTheLoaderReports) {
  const fs::path file = dir_ / "calibration.toml";
  write_calibration(file, voltage_result(0.0683, -41.5), kConfig, "simulator (seed 1, tether)",
                    false);
  const config::Configuration loaded = config::load_configuration(kConfig, file);
  const Params& params = loaded.params;
  EXPECT_DOUBLE_EQ(params.sensors.supply.gain, 0.0683);
  EXPECT_DOUBLE_EQ(params.sensors.supply.offset, -41.5);
  EXPECT_EQ(loaded.calibration.file, file.string());
  EXPECT_EQ(loaded.calibration.procedures, std::vector<std::string>{"voltage"});
  // Everything else is the configuration's.
  const config::Configuration nominal = config::load_configuration(kConfig);
  EXPECT_EQ(params.motors.scale, nominal.params.motors.scale);
  EXPECT_TRUE(nominal.calibration.file.empty());
  const toml::table written = config::read_toml_file(file);
  EXPECT_EQ(written["calibration"]["voltage"]["source"].value_or(std::string()),
            "simulator (seed 1, tether)");
  EXPECT_DOUBLE_EQ(written["calibration"]["voltage"]["rms_residual_v"].value_or(0.0), 0.01);
}

TEST_F(CalibrationFile, NeverOverwritesWithoutForceAndKeepsOtherProcedures) {
  const fs::path file = dir_ / "calibration.toml";
  write_calibration(file, voltage_result(0.0683, -41.5), kConfig, "sim", false);
  EXPECT_THROW(write_calibration(file, curve_result(511, 2.8), kConfig, "sim", false),
               CalibrationRefused);
  write_calibration(file, curve_result(511, 2.8), kConfig, "sim", true);
  write_calibration(file, curve_result(1023, 2.9), kConfig, "sim", true);
  write_calibration(file, curve_result(511, 2.7), kConfig, "sim", true);  // replaces icr 511
  const config::Configuration loaded = config::load_configuration(kConfig, file);
  const Params& params = loaded.params;
  EXPECT_DOUBLE_EQ(params.sensors.supply.gain, 0.0683);  // kept
  ASSERT_EQ(params.motor_curves.size(), 2U);
  for (const MotorCurveParams& c : params.motor_curves) {
    EXPECT_DOUBLE_EQ(c.no_load_speed_radps.back(), c.icr == 511 ? 2.7 : 2.9);
  }
  EXPECT_EQ(loaded.calibration.procedures.size(), 2U);
}

TEST_F(CalibrationFile, ALoadGainTableReplacesTheOneOfItsIcr) {
  // (4.6): a [[load_gain]] in the calibration file replaces the configured table of its icr.
  ProcedureResult r;
  r.procedure = "load";
  r.reference = "Procedure 4.13";
  toml::table gains;
  gains.insert_or_assign("icr", 511);
  gains.insert_or_assign("duty", toml::array{0.0, 0.6});
  gains.insert_or_assign("same_sign_radps_per_nm", toml::array{0.05, 0.031});
  gains.insert_or_assign("opposite_sign_radps_per_nm", toml::array{0.02, 0.014});
  toml::array tables;
  tables.push_back(std::move(gains));
  r.values.insert_or_assign("load_gain", std::move(tables));
  const fs::path file = dir_ / "calibration.toml";
  write_calibration(file, r, kConfig, "sim", false);
  const Params params = config::load_configuration(kConfig, file).params;
  ASSERT_EQ(params.load_gains.size(), 4U);  // 255, 511, 1023, 2047
  for (const LoadGainParams& g : params.load_gains) {
    if (g.icr != 511) continue;
    EXPECT_EQ(g.duty, (std::vector<double>{0.0, 0.6}));
    EXPECT_EQ(g.same_sign_radps_per_nm, (std::vector<double>{0.05, 0.031}));
  }
}

TEST_F(CalibrationFile, RefusesPoorFitsAndValuesTheConfigurationRejects) {
  const fs::path file = dir_ / "calibration.toml";
  ProcedureResult poor = voltage_result(0.0683, -41.5);
  poor.problems.push_back("a reading lies 0.3 V off the line");
  try {
    write_calibration(file, poor, kConfig, "sim", false);
    FAIL() << "a poor fit was written";
  } catch (const CalibrationRefused& e) {
    EXPECT_NE(std::string(e.what()).find("0.3 V off the line"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
  // W must increase: a falling curve is not a configuration.
  EXPECT_THROW(write_calibration(file, curve_result(511, 1.0), kConfig, "sim", false),
               CalibrationRefused);
  EXPECT_FALSE(fs::exists(file));
}

TEST_F(CalibrationFile, TheLoaderRejectsKeysACalibrationMustNotChange) {
  const fs::path file = dir_ / "calibration.toml";
  std::ofstream(file) << "[safety]\noperator_timeout_s = 5.0\n\n[motors]\nwheel_count = 6\n";
  try {
    (void)config::load_params(kConfig, file);
    FAIL() << "a calibration changed the safety limits";
  } catch (const config::ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("safety: not a calibrated section"), std::string::npos) << what;
    EXPECT_NE(what.find("motors.wheel_count: not a calibrated value"), std::string::npos) << what;
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
  }
  std::ofstream(file, std::ios::trunc) << "[motors]\nscale = [1.0, 2.0]\n";
  EXPECT_THROW((void)config::load_params(kConfig, file), config::ConfigError);
  std::ofstream(file, std::ios::trunc) << "[motors\n";
  EXPECT_THROW((void)config::load_params(kConfig, file), config::ConfigError);
  EXPECT_THROW((void)config::load_params(kConfig, dir_ / "missing.toml"), config::ConfigError);
}

}  // namespace
}  // namespace marsokhod::calibration
