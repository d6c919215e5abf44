#include "link/link_server.hpp"

#include "link/server_core.hpp"

namespace marsokhod::link {

LinkServer::LinkServer(const Params& params, ServerOptions options)
    : core_(std::make_unique<ServerCore>(params, std::move(options))) {}

LinkServer::~LinkServer() = default;

void LinkServer::start() { core_->start(); }

void LinkServer::stop() { core_->stop(); }

std::uint16_t LinkServer::port() const { return core_->port(); }

const std::string& LinkServer::token() const { return core_->token(); }

namespace {

// The address a client opens: every interface is not one, the loopback one reaches it.
std::string shown_address(const ServerCore& core) {
  ListenAddress shown = core.options().listen;
  shown.port = core.port() != 0 ? core.port() : shown.port;
  if (shown.address == "0.0.0.0") shown.address = "127.0.0.1";
  if (shown.address == "::") shown.address = "::1";
  return to_string(shown);
}

}  // namespace

std::string LinkServer::console_url() const {
  return "http://" + shown_address(*core_) + "/?token=" + core_->token();
}

std::string LinkServer::foxglove_url() const {
  return "ws://" + shown_address(*core_) + "/foxglove?token=" + core_->token();
}

std::vector<InboundCommand> LinkServer::take_inbound() { return core_->take_inbound(); }

void LinkServer::publish_status(nlohmann::json status) { core_->publish_status(std::move(status)); }

void LinkServer::publish_foxglove(std::uint64_t time_ns, std::vector<FoxgloveMessage> messages) {
  core_->publish_foxglove(time_ns, std::move(messages));
}

FoxgloveInterest LinkServer::foxglove_interest() const { return core_->foxglove_interest(); }

ServerStats LinkServer::stats() const { return core_->stats(); }

}  // namespace marsokhod::link
