#include "runner/mcap_recording.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "bus/candump_log.hpp"
#include "core/checks/checks.hpp"
#include "core/protocol/codec.hpp"
#include "link/command_json.hpp"
#include "link/frame_json.hpp"
#include "link/status_json.hpp"
#include "runner/recorder.hpp"

namespace marsokhod::runner {
namespace {

using Json = nlohmann::json;

Json number() { return {{"type", "number"}}; }
Json object_of(std::initializer_list<std::pair<const std::string, Json>> properties) {
  return {{"type", "object"}, {"properties", Json(properties)}};
}
Json time_schema() {
  return object_of({{"sec", {{"type", "integer"}, {"minimum", 0}}},
                    {"nsec", {{"type", "integer"}, {"minimum", 0}, {"maximum", 999999999}}}});
}
Json vector3_schema() { return object_of({{"x", number()}, {"y", number()}, {"z", number()}}); }
Json quaternion_schema() {
  return object_of({{"x", number()}, {"y", number()}, {"z", number()}, {"w", number()}});
}

// Foxglove's own message schemas (the fields its panels read), in JSON Schema.
Json foxglove_schema(const std::string& name) {
  Json schema;
  if (name == "foxglove.FrameTransform") {
    schema = object_of({{"timestamp", time_schema()},
                        {"parent_frame_id", {{"type", "string"}}},
                        {"child_frame_id", {{"type", "string"}}},
                        {"translation", vector3_schema()},
                        {"rotation", quaternion_schema()}});
  } else if (name == "foxglove.PoseInFrame") {
    schema = object_of({{"timestamp", time_schema()},
                        {"frame_id", {{"type", "string"}}},
                        {"pose", object_of({{"position", vector3_schema()},
                                            {"orientation", quaternion_schema()}})}});
  } else {
    throw std::logic_error("mcap: no schema " + name);
  }
  schema["title"] = name;
  return schema;
}

Json timestamp(std::int64_t time_us) {
  return {{"sec", time_us / 1000000}, {"nsec", (time_us % 1000000) * 1000}};
}

// R = Rz(yaw)·Ry(pitch)·Rx(roll) as a unit quaternion.
Json quaternion(double roll, double pitch, double yaw) {
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
  const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {{"x", sr * cp * cy - cr * sp * sy},
          {"y", cr * sp * cy + sr * cp * sy},
          {"z", cr * cp * sy - sr * sp * cy},
          {"w", cr * cp * cy + sr * sp * sy}};
}

std::string joint_name(std::size_t motor) {
  return std::string(motor < kWheelCount ? "wheel_" : "joint_") + kMotorNames[motor];
}

Json imu_json(const driver::DriverStatus& s) {
  return {{"accel_mps2", s.accel_mps2},
          {"yaw_rate_radps", s.yaw_rate_radps},
          {"front_tilt_rad", s.front_tilt_rad},
          {"rear_tilt_rad", s.rear_tilt_rad},
          {"slope_rad", s.slope_rad},
          {"roll_rad", s.attitude.roll_rad},
          {"pitch_rad", s.attitude.pitch_rad}};
}

Json joint_states_json(std::int64_t time_us, const driver::DriverStatus& s) {
  Json names = Json::array(), position = Json::array(), velocity = Json::array(),
       effort = Json::array(), commanded = Json::array(), duty = Json::array();
  for (std::size_t m = 0; m < kMotorCount; ++m) {
    const driver::MotorStatus& motor = s.motors[m];
    names.push_back(joint_name(m));
    position.push_back(motor.position_rad);
    velocity.push_back(motor.velocity_radps);
    effort.push_back(motor.torque_nm);
    commanded.push_back(motor.commanded_radps);
    duty.push_back(motor.duty);
  }
  return {{"timestamp", timestamp(time_us)}, {"name", names},     {"position", position},
          {"velocity", velocity},            {"effort", effort},  {"commanded_radps", commanded},
          {"duty", duty}};
}

}  // namespace

Json json_schema_of(const Json& value) {
  switch (value.type()) {
    case Json::value_t::object: {
      Json properties = Json::object();
      for (const auto& [key, v] : value.items()) properties[key] = json_schema_of(v);
      return {{"type", "object"}, {"properties", properties}};
    }
    case Json::value_t::array: {
      Json schema = {{"type", "array"}};
      if (!value.empty()) schema["items"] = json_schema_of(value.front());
      return schema;
    }
    case Json::value_t::string:
      return {{"type", "string"}};
    case Json::value_t::boolean:
      return {{"type", "boolean"}};
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return {{"type", "number"}};
    default:
      return Json::object();  // null: a non-finite number, or nothing yet
  }
}

std::string read_text_file(const std::filesystem::path& path) {
  if (path.empty()) return "";
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

McapRecording::McapRecording(const std::filesystem::path& file, const Params& params,
                             const std::string& source, const std::string& config_text,
                             const std::string& calibration_text)
    : file_(file), out_(file, std::ios::binary | std::ios::trunc), bus_(params) {
  if (!out_) throw std::runtime_error("cannot write " + file.string());
  writer_ = std::make_unique<McapWriter>(out_, "", "marsokhod");
  writer_->write_metadata(
      "marsokhod", {{"source", source},
                    {"log_time", "the rover's mission time (simulated time in the simulator), ns"},
                    {"cycle_period_s", checks::format_number(params.cycle.period_s)},
                    {"urdf", "marsokhod urdf"}});
  if (!config_text.empty()) writer_->write_attachment("config.toml", "application/toml", 0, config_text);
  if (!calibration_text.empty()) {
    writer_->write_attachment("calibration.toml", "application/toml", 0, calibration_text);
  }
}

McapRecording::~McapRecording() = default;

std::uint16_t McapRecording::channel(const std::string& topic, const Json& first,
                                     const std::string& schema_name) {
  if (const auto it = channels_.find(topic); it != channels_.end()) return it->second;
  Json schema;
  std::string name = schema_name;
  if (name.rfind("foxglove.", 0) == 0) {
    schema = foxglove_schema(name);
  } else {
    schema = json_schema_of(first);
    schema["title"] = name;
  }
  const std::uint16_t schema_id = writer_->add_schema(name, "jsonschema", schema.dump());
  const std::uint16_t id = writer_->add_channel(schema_id, topic, "json");
  channels_[topic] = id;
  return id;
}

void McapRecording::publish(const std::string& topic, std::int64_t time_us, const Json& message,
                            const char* schema_name) {
  const std::string name =
      schema_name != nullptr ? schema_name : "marsokhod" + [&] {
        std::string t = topic;
        for (char& c : t) c = c == '/' ? '.' : c;
        return t;
      }();
  const std::uint16_t id = channel(topic, message, name);
  const auto ns = static_cast<std::uint64_t>(time_us) * 1000U;
  writer_->write_message(id, ns, ns, message.dump(-1, ' ', false, Json::error_handler_t::replace));
}

void McapRecording::publish_ordered(const std::string& topic, std::int64_t time_us,
                                    const nlohmann::ordered_json& message) {
  const std::string text = message.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (channels_.find(topic) == channels_.end()) {
    channel(topic, Json::parse(text), "marsokhod.can.decoded");
  }
  const auto ns = static_cast<std::uint64_t>(time_us) * 1000U;
  writer_->write_message(channels_.at(topic), ns, ns, text);
}

void McapRecording::record_frame(std::int64_t time_us, const protocol::CanFrame& frame,
                                 bool received) {
  bus::LoggedFrame logged;
  logged.timestamp = format_time_us(time_us);
  logged.time_s = std::stod(logged.timestamp);
  logged.interface = "can0";
  logged.frame = frame;
  std::string hex;
  Json bytes = Json::array();
  for (std::size_t i = 0; i < frame.dlc; ++i) {
    char text[3];
    std::snprintf(text, sizeof text, "%02X", static_cast<unsigned>(frame.data[i]));
    hex += text;
    bytes.push_back(frame.data[i]);
  }
  publish("/can/raw", time_us,
          {{"time", logged.time_s},
           {"timestamp", logged.timestamp},
           {"direction", received ? "rx" : "tx"},
           {"id", frame.id},
           {"dlc", frame.dlc},
           {"data", hex},
           {"bytes", bytes}});
  const protocol::DecodeResult result = protocol::decode(frame, bus_.decode_context());
  if (!result.ok()) {
    nlohmann::ordered_json error;
    error["time"] = logged.time_s;
    error["timestamp"] = logged.timestamp;
    error["interface"] = logged.interface;
    error["id"] = frame.id;
    error["error"] = result.error().reason;
    publish_ordered("/can/decoded", time_us, error);
    return;
  }
  bus_.observe(result.message());
  publish_ordered("/can/decoded", time_us,
                  link::frame_json(logged, protocol::describe(result.message(), bus_)));
}

void McapRecording::record(const McapCycle& c) {
  for (const auto& [t_us, frame] : c.received) record_frame(t_us, frame, true);
  for (const protocol::CanFrame& frame : c.sent) record_frame(c.time_us, frame, false);
  if (c.runtime) publish("/operator/runtime", c.time_us, link::runtime_settings_json(*c.runtime));
  if (c.input != nullptr) publish("/operator/input", c.time_us, link::operator_input_json(*c.input));
  if (c.status != nullptr) {
    const driver::DriverStatus& s = *c.status;
    publish("/status", c.time_us, link::status_json(s, c.truth));
    publish("/imu", c.time_us, imu_json(s));
    publish("/joint_states", c.time_us, joint_states_json(c.time_us, s));
    publish("/pose", c.time_us,
            {{"timestamp", timestamp(c.time_us)},
             {"frame_id", "world"},
             {"pose",
              {{"position", {{"x", s.pose.x_m}, {"y", s.pose.y_m}, {"z", 0.0}}},
               {"orientation", quaternion(0.0, 0.0, s.pose.heading_rad)}}}},
            "foxglove.PoseInFrame");
    publish("/pose/estimate", c.time_us, link::pose_json(s.pose));
  }
  if (c.true_pose) {
    const TruePose& p = *c.true_pose;
    publish("/tf", c.time_us,
            {{"timestamp", timestamp(c.time_us)},
             {"parent_frame_id", "world"},
             {"child_frame_id", "base_link"},
             {"translation", {{"x", p.position_m[0]}, {"y", p.position_m[1]}, {"z", p.position_m[2]}}},
             {"rotation", quaternion(p.roll_pitch_yaw_rad[0], p.roll_pitch_yaw_rad[1],
                                     p.roll_pitch_yaw_rad[2])}},
            "foxglove.FrameTransform");
  }
}

void McapRecording::finish() {
  writer_->finish();
  out_.close();
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
}

}  // namespace marsokhod::runner
