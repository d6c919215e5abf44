#include "link/http_session.hpp"

#include <chrono>
#include <string_view>

#include <boost/beast/websocket/rfc6455.hpp>

#include "link/access_token.hpp"
#include "link/static_files.hpp"
#include "link/websocket_session.hpp"

namespace marsokhod::link {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
using tcp = boost::asio::ip::tcp;

// A request's header and body are small (a GET or an upgrade); anything larger is not ours.
constexpr std::uint64_t kRequestLimitBytes = 8 * 1024;
constexpr auto kRequestTimeout = std::chrono::seconds(30);
constexpr const char* kServerName = "marsokhod-link";

std::string_view view(beast::string_view text) { return {text.data(), text.size()}; }

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, ServerCore& core)
    : stream_(std::move(socket)), core_(core) {}

HttpSession::~HttpSession() { core_.untrack(key_); }

void HttpSession::run() {
  key_ = core_.track(weak_from_this());
  read();
}

void HttpSession::close() { stream_.close(); }

void HttpSession::read() {
  parser_.emplace();
  parser_->header_limit(kRequestLimitBytes);
  parser_->body_limit(kRequestLimitBytes);
  stream_.expires_after(kRequestTimeout);
  http::async_read(stream_, buffer_, *parser_,
                   [self = shared_from_this()](beast::error_code error, std::size_t) {
                     self->on_read(error);
                   });
}

void HttpSession::on_read(beast::error_code error) {
  if (error == http::error::end_of_stream) {
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
    return;
  }
  if (error || core_.stopping()) return;
  Request request = parser_->release();
  if (beast::websocket::is_upgrade(request)) {
    upgrade(std::move(request));
    return;
  }
  core_.count_http_request();
  respond(request);
}

void HttpSession::upgrade(Request&& request) {
  const std::string_view target = view(request.target());
  if (target_path(target) != "/ws") {
    core_.count_http_request();
    send_text(request, http::status::not_found, "no WebSocket here; the console's is /ws?token=…");
  } else if (!core_.authorized(target)) {
    send_text(request, http::status::unauthorized,
              "missing or wrong token: open the console with the address the rover's server "
              "printed at start (http://…/?token=…)");
  } else if (!core_.has_room()) {
    send_text(request, http::status::service_unavailable,
              "too many consoles connected; close one and try again");
  } else {
    std::make_shared<WebSocketSession>(stream_.release_socket(), core_)->run(std::move(request));
  }
}

void HttpSession::respond(const Request& request) {
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    send_text(request, http::status::method_not_allowed, "only GET and HEAD are served here");
    return;
  }
  const StaticPath path = resolve_static_target(view(request.target()));
  if (!path.ok) {
    send_text(request, http::status::bad_request, "bad path: " + path.reason);
    return;
  }
  if (!core_.options().static_dir) {
    send_text(request, http::status::not_found,
              "this server has no console files; give it the console's build (web/dist)");
    return;
  }
  const auto file = static_file_under(*core_.options().static_dir, path.relative_path);
  if (!file) {
    send_text(request, http::status::not_found, "not found: /" + path.relative_path);
    return;
  }
  send_file(request, *file);
}

void HttpSession::send_file(const Request& request, const std::filesystem::path& file) {
  http::file_body::value_type body;
  beast::error_code error;
  body.open(file.c_str(), beast::file_mode::scan, error);
  if (error) {
    send_text(request, http::status::not_found, "cannot read " + file.filename().string());
    return;
  }
  const std::uint64_t size = body.size();
  const std::string type(mime_type(file.string()));
  if (request.method() == http::verb::head) {
    http::response<http::empty_body> response{http::status::ok, request.version()};
    response.set(http::field::server, kServerName);
    response.set(http::field::content_type, type);
    response.content_length(size);
    response.keep_alive(request.keep_alive());
    send(std::move(response));
    return;
  }
  http::response<http::file_body> response{std::piecewise_construct,
                                           std::make_tuple(std::move(body)),
                                           std::make_tuple(http::status::ok, request.version())};
  response.set(http::field::server, kServerName);
  response.set(http::field::content_type, type);
  // The console is rebuilt in place (same names); make the browser check instead of guessing.
  response.set(http::field::cache_control, "no-cache");
  response.content_length(size);
  response.keep_alive(request.keep_alive());
  send(std::move(response));
}

void HttpSession::send_text(const Request& request, http::status status, std::string body) {
  http::response<http::string_body> response{status, request.version()};
  response.set(http::field::server, kServerName);
  response.set(http::field::content_type, "text/plain; charset=utf-8");
  if (status == http::status::method_not_allowed) response.set(http::field::allow, "GET, HEAD");
  // A refusal ends the connection: a client that was refused has nothing more to ask.
  response.keep_alive(status == http::status::not_found && request.keep_alive());
  response.body() = std::move(body);
  response.body() += "\n";
  response.prepare_payload();
  send(std::move(response));
}

template <typename Body>
void HttpSession::send(http::response<Body>&& response) {
  auto message = std::make_shared<http::response<Body>>(std::move(response));
  const bool close_after = message->need_eof();
  http::async_write(stream_, *message,
                    [self = shared_from_this(), message, close_after](beast::error_code error,
                                                                      std::size_t) {
                      if (error) return;
                      if (close_after) {
                        beast::error_code ignored;
                        self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
                        return;
                      }
                      self->read();
                    });
}

}  // namespace marsokhod::link
