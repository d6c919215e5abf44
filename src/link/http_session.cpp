#include "link/http_session.hpp"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <string_view>

#include <boost/beast/websocket/rfc6455.hpp>

#include "link/access_token.hpp"
#include "link/foxglove_protocol.hpp"
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

// The console loads its own scripts and styles only, talks to its own server only, and may not
// be framed (clickjacking the STOP or Take control button). ws://HOST: older browsers do not
// count ws: as 'self'. HOST is the request's Host, already checked against the allowed names.
std::string content_security_policy(std::string_view host) {
  const bool clean = std::all_of(host.begin(), host.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == ':' ||
           c == '[' || c == ']';
  });
  if (!clean) host = {};  // a refused Host: not worth naming
  return "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; "
         "img-src 'self' data: blob:; connect-src 'self' ws://" +
         std::string(host) +
         "; object-src 'none'; base-uri 'none'; form-action 'none'; frame-ancestors 'none'";
}

}  // namespace

HttpSession::HttpSession(tcp::socket&& socket, ServerCore& core)
    : stream_(std::move(socket)), core_(core) {}

HttpSession::~HttpSession() { core_.untrack(key_); }

void HttpSession::run() {
  key_ = core_.track(weak_from_this());
  beast::error_code error;
  const auto peer = stream_.socket().remote_endpoint(error);
  if (error) return;  // gone already
  address_ = peer.address().to_string();
  deadline_ = std::chrono::steady_clock::now() +
              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                  std::chrono::duration<double>(core_.options().http_connection_max_s));
  read();
}

void HttpSession::close() { stream_.close(); }

void HttpSession::read() {
  parser_.emplace();
  parser_->header_limit(kRequestLimitBytes);
  parser_->body_limit(kRequestLimitBytes);
  const auto now = std::chrono::steady_clock::now();
  if (now >= deadline_) {
    close();  // kept alive long enough: the client may open a new connection
    return;
  }
  stream_.expires_at(std::min<std::chrono::steady_clock::time_point>(now + kRequestTimeout,
                                                                     deadline_));
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
  try {
    handle(parser_->release());
  } catch (const std::exception& failure) {
    core_.on_handler_failure("an HTTP request", failure);
    close();
  }
}

void HttpSession::handle(Request&& request) {
  if (!core_.host_allowed(view(request[http::field::host]))) {
    core_.count_http_request();
    send_text(request, http::status::forbidden,
              "Host '" + std::string(view(request[http::field::host])) +
                  "' is not this server's name: open the address it printed, or add the name to "
                  "[console] allowed_hosts");
    return;
  }
  if (beast::websocket::is_upgrade(request)) {
    upgrade(std::move(request));
    return;
  }
  core_.count_http_request();
  if (target_path(view(request.target())) == "/session") {
    open_session(request);
    return;
  }
  respond(request);
}

static std::optional<std::string_view> origin_of(const HttpSession::Request& request) {
  const auto it = request.find(http::field::origin);
  if (it == request.end()) return std::nullopt;
  return view(it->value());
}

bool HttpSession::refuse_token(const Request& request, const AuthDecision& decision) {
  if (decision.result == AuthDecision::Result::kAllowed) return false;
  if (decision.result == AuthDecision::Result::kBackingOff) {
    const auto wait = std::to_string(static_cast<long long>(std::ceil(decision.wait_s)));
    send_text(request, http::status::too_many_requests,
              "too many wrong tokens from " + address_ + ": try again in " + wait + " s");
    return true;
  }
  send_text(request, http::status::unauthorized,
            "missing or wrong token: open the console with the address the rover's server "
            "printed at start (http://…/?token=…)");
  return true;
}

// Whether the upgrade offers `protocol` among its Sec-WebSocket-Protocol values.
static bool offers_subprotocol(const HttpSession::Request& request, std::string_view protocol) {
  std::string_view offered = view(request[http::field::sec_websocket_protocol]);
  while (!offered.empty()) {
    const auto comma = offered.find(',');
    std::string_view item = offered.substr(0, comma);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item == protocol) return true;
    if (comma == std::string_view::npos) break;
    offered.remove_prefix(comma + 1);
  }
  return false;
}

void HttpSession::upgrade(Request&& request) {
  const std::string_view path = target_path(view(request.target()));
  const bool foxglove = path == "/foxglove";
  if (path != "/ws" && !foxglove) {
    core_.count_http_request();
    send_text(request, http::status::not_found,
              "no WebSocket here; the console's is /ws, Foxglove's /foxglove");
    return;
  }
  if (foxglove && !offers_subprotocol(request, foxglove::kSubprotocol)) {
    send_text(request, http::status::bad_request,
              "/foxglove speaks the subprotocol " + std::string(foxglove::kSubprotocol) +
                  " only: ask for it in Sec-WebSocket-Protocol (Foxglove's WebSocket connection "
                  "does)");
    return;
  }
  const auto origin = origin_of(request);
  if (!core_.origin_allowed(origin)) {
    send_text(request, http::status::forbidden,
              "a page from " + std::string(origin.value_or("")) +
                  " may not open the console's WebSocket; add it to [console] allowed_origins "
                  "if it should");
    return;
  }
  // Foxglove's connection dialog takes a URL only: its token comes in the query.
  const auto query_token =
      foxglove ? query_parameter(view(request.target()), "token") : std::nullopt;
  const AuthDecision decision =
      core_.authorize_upgrade(view(request[http::field::cookie]),
                              view(request[http::field::authorization]), address_, query_token);
  if (refuse_token(request, decision)) return;
  if (!core_.has_room()) {
    send_text(request, http::status::service_unavailable,
              "too many consoles connected; close one and try again");
    return;
  }
  std::make_shared<WebSocketSession>(stream_.release_socket(), core_,
                                     foxglove ? WebSocketSession::Kind::kFoxglove
                                              : WebSocketSession::Kind::kConsole)
      ->run(std::move(request));
}

void HttpSession::open_session(const Request& request) {
  if (request.method() != http::verb::post) {
    send_text(request, http::status::method_not_allowed,
              "POST /session with Authorization: Bearer TOKEN");
    return;
  }
  const auto origin = origin_of(request);
  if (!core_.origin_allowed(origin)) {
    send_text(request, http::status::forbidden,
              "a page from " + std::string(origin.value_or("")) + " may not open a session");
    return;
  }
  std::string session_id;
  const AuthDecision decision =
      core_.open_session(view(request[http::field::authorization]), address_, session_id);
  if (refuse_token(request, decision)) return;
  http::response<http::empty_body> response{http::status::no_content, request.version()};
  // HttpOnly: no script reads it; SameSite=Strict: no other site's page sends it. No Max-Age:
  // it ends with the browser (and the server forgets it when it restarts).
  response.set(http::field::set_cookie,
               core_.cookie_name() + "=" + session_id + "; Path=/; HttpOnly; SameSite=Strict");
  response.set(http::field::cache_control, "no-store");
  response.keep_alive(request.keep_alive());
  send(request, std::move(response));
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
    send(request, std::move(response));
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
  send(request, std::move(response));
}

void HttpSession::send_text(const Request& request, http::status status, std::string body) {
  http::response<http::string_body> response{status, request.version()};
  response.set(http::field::server, kServerName);
  response.set(http::field::content_type, "text/plain; charset=utf-8");
  if (status == http::status::method_not_allowed) {
    const bool session = target_path(view(request.target())) == "/session";
    response.set(http::field::allow, session ? "POST" : "GET, HEAD");
  }
  // A refusal ends the connection: a client that was refused has nothing more to ask.
  response.keep_alive(status == http::status::not_found && request.keep_alive());
  response.body() = std::move(body);
  response.body() += "\n";
  response.prepare_payload();
  send(request, std::move(response));
}

template <typename Body>
void HttpSession::send(const Request& request, http::response<Body>&& response) {
  response.set(http::field::server, kServerName);
  response.set("X-Content-Type-Options", "nosniff");
  response.set("Referrer-Policy", "no-referrer");
  response.set("Content-Security-Policy",
               content_security_policy(view(request[http::field::host])));
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
