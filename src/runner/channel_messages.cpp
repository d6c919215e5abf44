#include "runner/channel_messages.hpp"

#include <cstdio>
#include <stdexcept>

#include "bus/candump_log.hpp"
#include "core/protocol/codec.hpp"
#include "link/frame_json.hpp"
#include "link/server_messages.hpp"
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
Json frame_transform_schema() {
  return object_of({{"timestamp", time_schema()},
                    {"parent_frame_id", {{"type", "string"}}},
                    {"child_frame_id", {{"type", "string"}}},
                    {"translation", vector3_schema()},
                    {"rotation", quaternion_schema()}});
}

// Foxglove's own message schemas (the fields its panels read), in JSON Schema.
Json foxglove_schema(const std::string& name) {
  Json schema;
  if (name == "foxglove.FrameTransform") {
    schema = frame_transform_schema();
  } else if (name == "foxglove.FrameTransforms") {
    schema = object_of({{"transforms", {{"type", "array"}, {"items", frame_transform_schema()}}}});
  } else if (name == "foxglove.PoseInFrame") {
    schema = object_of({{"timestamp", time_schema()},
                        {"frame_id", {{"type", "string"}}},
                        {"pose", object_of({{"position", vector3_schema()},
                                            {"orientation", quaternion_schema()}})}});
  } else {
    throw std::logic_error("channels: no schema " + name);
  }
  schema["title"] = name;
  return schema;
}

Json timestamp(std::int64_t time_us) {
  return {{"sec", time_us / 1000000}, {"nsec", (time_us % 1000000) * 1000}};
}

Json quaternion_json(const std::array<double, 4>& q) {
  return {{"x", q[0]}, {"y", q[1]}, {"z", q[2]}, {"w", q[3]}};
}

Json frame_transform_json(std::int64_t time_us, const std::string& parent, const std::string& child,
                          const std::array<double, 3>& translation,
                          const std::array<double, 4>& rotation) {
  return {{"timestamp", timestamp(time_us)},
          {"parent_frame_id", parent},
          {"child_frame_id", child},
          {"translation", {{"x", translation[0]}, {"y", translation[1]}, {"z", translation[2]}}},
          {"rotation", quaternion_json(rotation)}};
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

void append(std::vector<ChannelMessage>& out, const std::string& topic, const Json& message,
            const char* schema_name = nullptr) {
  out.push_back({topic, schema_name != nullptr ? schema_name : schema_name_of(topic),
                 link::wire_text(message)});
}

}  // namespace

TruePose true_pose_of(const sim::GroundTruth& truth, const std::vector<sim::RoverJoint>& joints) {
  return {truth.position_m, truth.roll_pitch_yaw_rad, sim::link_transforms(joints, truth)};
}

std::string schema_name_of(const std::string& topic) {
  std::string name = "marsokhod" + topic;
  for (char& c : name) c = c == '/' ? '.' : c;
  return name;
}

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

Json channel_schema(const std::string& schema_name, const Json& first) {
  if (schema_name.rfind("foxglove.", 0) == 0) return foxglove_schema(schema_name);
  Json schema = json_schema_of(first);
  schema["title"] = schema_name;
  return schema;
}

std::vector<ChannelMessage> status_channel_messages(std::int64_t time_us,
                                                    const driver::DriverStatus* status,
                                                    const Json& truth,
                                                    const std::optional<TruePose>& true_pose) {
  std::vector<ChannelMessage> out;
  if (status != nullptr) {
    const driver::DriverStatus& s = *status;
    append(out, "/status", link::status_json(s, truth));
    append(out, "/imu", imu_json(s));
    append(out, "/joint_states", joint_states_json(time_us, s));
    append(out, "/pose",
        {{"timestamp", timestamp(time_us)},
         {"frame_id", "world"},
         {"pose",
          {{"position", {{"x", s.pose.x_m}, {"y", s.pose.y_m}, {"z", 0.0}}},
           {"orientation", quaternion_json(sim::quaternion_of_rpy({0.0, 0.0, s.pose.heading_rad}))}}}},
        "foxglove.PoseInFrame");
    append(out, "/pose/estimate", link::pose_json(s.pose));
  }
  if (true_pose) {
    const TruePose& p = *true_pose;
    append(out, "/tf",
        frame_transform_json(time_us, "world", "base_link", p.position_m,
                             sim::quaternion_of_rpy(p.roll_pitch_yaw_rad)),
        "foxglove.FrameTransform");
    if (!p.links.empty()) {
      Json transforms = Json::array();
      for (const sim::LinkTransform& link : p.links) {
        transforms.push_back(
            frame_transform_json(time_us, link.parent, link.child, link.translation, link.rotation));
      }
      append(out, "/tf/links", {{"transforms", transforms}}, "foxglove.FrameTransforms");
    }
  }
  return out;
}

CanChannels::CanChannels(const Params& params) : bus_(params) {}

void CanChannels::add(std::int64_t time_us, const protocol::CanFrame& frame, bool received,
                      std::vector<ChannelMessage>* out) {
  const protocol::DecodeResult result = protocol::decode(frame, bus_.decode_context());
  if (result.ok()) bus_.observe(result.message());
  if (out == nullptr) return;
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
  append(*out, "/can/raw",
              {{"time", logged.time_s},
               {"timestamp", logged.timestamp},
               {"direction", received ? "rx" : "tx"},
               {"id", frame.id},
               {"dlc", frame.dlc},
               {"data", hex},
               {"bytes", bytes}});
  nlohmann::ordered_json decoded;
  if (result.ok()) {
    decoded = link::frame_json(logged, protocol::describe(result.message(), bus_));
  } else {
    decoded["time"] = logged.time_s;
    decoded["timestamp"] = logged.timestamp;
    decoded["interface"] = logged.interface;
    decoded["id"] = frame.id;
    decoded["error"] = result.error().reason;
  }
  out->push_back({"/can/decoded", "marsokhod.can.decoded",
                  decoded.dump(-1, ' ', false, Json::error_handler_t::replace)});
}

}  // namespace marsokhod::runner
