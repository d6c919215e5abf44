// What config/marsokhod.toml configures besides the rover (Params): the operator console's link,
// and where the calibrated values came from. The loader (load_params.hpp) reads all of it through
// one schema (param_schema.hpp); the driver and everything below it see only Params.
#pragma once

#include <string>
#include <vector>

#include "core/params.hpp"

namespace marsokhod::config {

// [console]: the operator console's link (src/link); command-line options override these.
struct ConsoleParams {
  std::string listen = "127.0.0.1:8080";     // ADDR:PORT of the HTTP/WebSocket server
  std::string token;                         // empty: a fresh random token at every start
  double status_rate_hz = 20.0;              // status messages per second to each console
  std::vector<std::string> allowed_hosts;    // Host names served besides the listen address
  std::vector<std::string> allowed_origins;  // page origins that may open the WebSocket
};

// Where the calibrated values came from (calibration.hpp): not read from the configuration file;
// the loader fills it in when a calibration file is applied.
struct CalibrationSource {
  std::string file;                     // empty: the configuration's nominal values
  std::vector<std::string> procedures;  // the procedures it holds, e.g. "voltage"
};

// The whole configuration: the rover's Params, the console, the calibration applied.
struct Configuration {
  Params params;
  ConsoleParams console;
  CalibrationSource calibration;
};

}  // namespace marsokhod::config
