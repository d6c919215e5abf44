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

std::string LinkServer::console_url() const {
  ListenAddress shown = core_->options().listen;
  shown.port = core_->port() != 0 ? core_->port() : shown.port;
  // Every interface is not an address a browser can open; the loopback one reaches it.
  if (shown.address == "0.0.0.0") shown.address = "127.0.0.1";
  if (shown.address == "::") shown.address = "::1";
  return "http://" + to_string(shown) + "/?token=" + core_->token();
}

std::vector<InboundCommand> LinkServer::take_inbound() { return core_->take_inbound(); }

void LinkServer::publish_status(nlohmann::json status) { core_->publish_status(std::move(status)); }

ServerStats LinkServer::stats() const { return core_->stats(); }

}  // namespace marsokhod::link
