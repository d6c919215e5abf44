#include "bus/socketcand_server.hpp"

#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "bus/socketcand_protocol.hpp"
#include "bus/socketcand_session.hpp"

namespace marsokhod::bus {
namespace {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

// broadcast() hands frames to the server's thread; if that thread falls this far behind, frames
// are dropped (and counted) instead of piling up without bound.
constexpr std::size_t kMaxPendingBroadcasts = 4096;
constexpr std::chrono::milliseconds kAcceptRetry{100};  // after EMFILE and the like

double wall_clock_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

struct SocketcandServer::Impl final : SessionHost {
  Config settings;
  FrameCallback on_frame;
  // Declared first so that it is destroyed last: the handlers it still holds own sessions whose
  // sockets and timers need its services while they are destroyed.
  asio::io_context io;
  tcp::acceptor acceptor{io};
  asio::steady_timer accept_retry{io};
  std::set<std::shared_ptr<SocketcandSession>> sessions;  // server thread only
  std::thread thread;
  std::atomic<bool> running{false};
  std::atomic<std::size_t> pending_broadcasts{0};
  std::uint16_t port = 0;
  mutable std::mutex mutex;
  mutable std::condition_variable streaming_changed;
  ServerCounters totals;  // guarded by mutex

  Impl(Config c, FrameCallback callback) : settings(std::move(c)), on_frame(std::move(callback)) {}

  const SocketcandServer::Config& config() const override { return settings; }

  void count(std::uint64_t ServerCounters::*counter) override {
    const std::lock_guard lock(mutex);
    ++(totals.*counter);
  }

  void streaming_started() override {
    const std::lock_guard lock(mutex);
    ++totals.streaming_clients;
    streaming_changed.notify_all();
  }

  void closed(SocketcandSession& session, bool was_streaming) override {
    if (was_streaming) {
      const std::lock_guard lock(mutex);
      --totals.streaming_clients;
      streaming_changed.notify_all();
    }
    sessions.erase(session.shared_from_this());
  }

  void frame_from_client(SocketcandSession& from, const protocol::CanFrame& frame) override {
    count(&ServerCounters::frames_from_clients);
    if (on_frame) on_frame(frame);  // exceptions reach the session, which reports them
    if (!settings.relay_between_clients) return;
    send_to_streaming(socketcand::format_message(socketcand::Frame{frame, wall_clock_s(), false}),
                      &from);
  }

  void send_to_streaming(const std::string& text, const SocketcandSession* except) {
    const auto snapshot = sessions;  // delivering may close a session, which erases it
    for (const auto& session : snapshot) {
      if (session.get() != except && session->streaming()) session->deliver(text, true);
    }
  }

  void accept() {
    acceptor.async_accept([this](const boost::system::error_code& error, tcp::socket socket) {
      if (error == asio::error::operation_aborted || !acceptor.is_open()) return;
      if (error) {
        accept_retry.expires_after(kAcceptRetry);
        accept_retry.async_wait([this](const boost::system::error_code& e) {
          if (!e) accept();
        });
        return;
      }
      admit(std::move(socket));
      accept();
    });
  }

  void admit(tcp::socket socket) {
    boost::system::error_code ignored;
    if (sessions.size() >= settings.max_clients) {
      count(&ServerCounters::clients_refused);
      const std::string text = socketcand::format_message(socketcand::Error{
          "too many clients (" + std::to_string(settings.max_clients) + "): try again later"});
      socket.non_blocking(true, ignored);  // a fresh socket's buffer takes it; never wait here
      socket.write_some(asio::buffer(text), ignored);
      socket.close(ignored);
      return;
    }
    socket.set_option(tcp::no_delay(true), ignored);  // small messages; latency matters
    count(&ServerCounters::clients_accepted);
    auto session = std::make_shared<SocketcandSession>(*this, std::move(socket));
    sessions.insert(session);
    session->start();
  }

  void listen() {
    boost::system::error_code error;
    const auto address = asio::ip::make_address(settings.address, error);
    if (error) {
      throw TransportError("socketcand server: '" + settings.address +
                           "' is not an IP address to listen on (e.g. 127.0.0.1 or ::1)");
    }
    const tcp::endpoint endpoint(address, settings.port);
    const std::string where =
        endpoint.address().to_string() + " port " + std::to_string(settings.port);
    acceptor.open(endpoint.protocol(), error);
    if (!error) acceptor.set_option(tcp::acceptor::reuse_address(true), error);
    if (!error) acceptor.bind(endpoint, error);
    if (!error) acceptor.listen(asio::socket_base::max_listen_connections, error);
    if (error) {
      const bool taken = error == asio::error::address_in_use;
      throw TransportError(
          "socketcand server cannot listen on " + where + ": " + error.message() +
          (taken ? ": another marsokhod sim or socketcand listens there; choose another port"
                 : ""));
    }
    port = acceptor.local_endpoint().port();
  }

  void shut_down() {
    boost::system::error_code ignored;
    acceptor.close(ignored);
    accept_retry.cancel();
    const auto snapshot = sessions;
    for (const auto& session : snapshot) session->close();
    io.stop();  // aborted handlers need not run: ~io_context releases them
  }
};

SocketcandServer::SocketcandServer(Config config, FrameCallback on_frame)
    : impl_(std::make_unique<Impl>(std::move(config), std::move(on_frame))) {}

SocketcandServer::~SocketcandServer() { stop(); }

void SocketcandServer::start() {
  if (impl_->port != 0) throw std::logic_error("SocketcandServer::start() called twice");
  impl_->listen();
  impl_->running = true;
  impl_->accept();
  impl_->thread = std::thread([impl = impl_.get()] {
    for (;;) {
      try {
        impl->io.run();
        return;
      } catch (const std::exception& error) {
        // One failed handler must not take the simulated bus down with it (sessions catch
        // their own; this is for anything else): report it and serve on.
        std::fprintf(stderr, "socketcand server: a handler failed (%s); serving on\n",
                     error.what());
      }
    }
  });
}

void SocketcandServer::stop() {
  if (!impl_->thread.joinable()) return;
  impl_->running = false;
  asio::post(impl_->io, [impl = impl_.get()] { impl->shut_down(); });
  impl_->thread.join();
}

std::uint16_t SocketcandServer::port() const { return impl_->port; }

void SocketcandServer::broadcast(const protocol::CanFrame& frame, double time_s) {
  std::string text = socketcand::format_message(socketcand::Frame{frame, time_s, false});
  if (!impl_->running) return;
  if (impl_->pending_broadcasts.fetch_add(1) >= kMaxPendingBroadcasts) {
    impl_->pending_broadcasts.fetch_sub(1);
    impl_->count(&ServerCounters::frames_dropped);
    return;
  }
  impl_->count(&ServerCounters::frames_broadcast);
  asio::post(impl_->io, [impl = impl_.get(), text = std::move(text)] {
    impl->pending_broadcasts.fetch_sub(1);
    impl->send_to_streaming(text, nullptr);
  });
}

bool SocketcandServer::wait_for_streaming_clients(std::size_t count,
                                                  std::chrono::milliseconds timeout) const {
  std::unique_lock lock(impl_->mutex);
  return impl_->streaming_changed.wait_for(
      lock, timeout, [&] { return impl_->totals.streaming_clients >= count; });
}

ServerCounters SocketcandServer::counters() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->totals;
}

}  // namespace marsokhod::bus
