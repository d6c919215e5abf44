#include "runner/mcap_recording.hpp"

#include <sstream>
#include <stdexcept>

#include "core/checks/checks.hpp"
#include "link/command_json.hpp"
#include "link/server_messages.hpp"

namespace marsokhod::runner {

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
    : file_(file), out_(file, std::ios::binary | std::ios::trunc), can_(params) {
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

void McapRecording::publish(std::int64_t time_us, const ChannelMessage& m) {
  auto it = channels_.find(m.topic);
  if (it == channels_.end()) {
    const nlohmann::json schema = channel_schema(m.schema_name, nlohmann::json::parse(m.text));
    const std::uint16_t schema_id = writer_->add_schema(m.schema_name, "jsonschema", schema.dump());
    it = channels_.emplace(m.topic, writer_->add_channel(schema_id, m.topic, "json")).first;
  }
  const auto ns = static_cast<std::uint64_t>(time_us) * 1000U;
  writer_->write_message(it->second, ns, ns, m.text);
}

void McapRecording::record(const McapCycle& c) {
  std::vector<ChannelMessage> frames;
  for (const auto& [t_us, frame] : c.received) {
    frames.clear();
    can_.add(t_us, frame, true, &frames);
    for (const ChannelMessage& m : frames) publish(t_us, m);
  }
  for (const protocol::CanFrame& frame : c.sent) {
    frames.clear();
    can_.add(c.time_us, frame, false, &frames);
    for (const ChannelMessage& m : frames) publish(c.time_us, m);
  }
  const auto own = [&](const std::string& topic, const nlohmann::json& message) {
    publish(c.time_us, {topic, schema_name_of(topic), link::wire_text(message)});
  };
  if (c.runtime) own("/operator/runtime", link::runtime_settings_json(*c.runtime));
  if (c.input != nullptr) own("/operator/input", link::operator_input_json(*c.input));
  for (const ChannelMessage& m : status_channel_messages(c.time_us, c.status, c.truth, c.true_pose)) {
    publish(c.time_us, m);
  }
}

void McapRecording::finish() {
  writer_->finish();
  out_.close();
  if (!out_) throw std::runtime_error("cannot write " + file_.string());
}

}  // namespace marsokhod::runner
