#include "link/static_files.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "link/access_token.hpp"

namespace marsokhod::link {
namespace {

constexpr std::array<std::pair<std::string_view, std::string_view>, 20> kMimeTypes = {{
    {"html", "text/html; charset=utf-8"},
    {"htm", "text/html; charset=utf-8"},
    {"js", "text/javascript; charset=utf-8"},
    {"mjs", "text/javascript; charset=utf-8"},
    {"css", "text/css; charset=utf-8"},
    {"json", "application/json"},
    {"map", "application/json"},
    {"webmanifest", "application/manifest+json"},
    {"txt", "text/plain; charset=utf-8"},
    {"svg", "image/svg+xml"},
    {"png", "image/png"},
    {"jpg", "image/jpeg"},
    {"jpeg", "image/jpeg"},
    {"gif", "image/gif"},
    {"ico", "image/x-icon"},
    {"wasm", "application/wasm"},
    {"woff2", "font/woff2"},
    {"woff", "font/woff"},
    {"glb", "model/gltf-binary"},
    {"gltf", "model/gltf+json"},
}};

std::optional<int> hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return std::nullopt;
}

std::optional<std::string> percent_decoded(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size()) return std::nullopt;
    const auto high = hex_digit(text[i + 1]);
    const auto low = hex_digit(text[i + 2]);
    if (!high || !low) return std::nullopt;
    out += static_cast<char>(*high * 16 + *low);
    i += 2;
  }
  return out;
}

StaticPath rejected(std::string reason) { return {false, "", std::move(reason)}; }

char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

}  // namespace

StaticPath resolve_static_target(std::string_view target) {
  const std::string_view raw = target_path(target);
  if (raw.empty() || raw.front() != '/') return rejected("the path must start with '/'");
  const auto decoded = percent_decoded(raw);
  if (!decoded) return rejected("bad percent escape in the path");
  std::string path = decoded->substr(1);
  if (path.find('\0') != std::string::npos) return rejected("NUL in the path");
  if (path.find('\\') != std::string::npos) return rejected("backslash in the path");
  if (path.empty() || path.back() == '/') path += "index.html";
  std::size_t start = 0;
  while (start <= path.size()) {
    const auto slash = path.find('/', start);
    const std::string_view segment =
        std::string_view(path).substr(start, slash == std::string::npos ? std::string::npos
                                                                        : slash - start);
    if (segment == "..") return rejected("'..' is not allowed in a path");
    if (segment == "." || segment.empty()) return rejected("empty or '.' path segment");
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return {true, path, ""};
}

std::optional<std::filesystem::path> static_file_under(const std::filesystem::path& root,
                                                       const std::string& relative) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::path real_root = fs::canonical(root, error);
  if (error) return std::nullopt;
  const fs::path file = fs::canonical(real_root / relative, error);
  if (error) return std::nullopt;
  // Inside the root means: the root's path is a prefix of the file's, element by element.
  const auto differ = std::mismatch(real_root.begin(), real_root.end(), file.begin(), file.end());
  if (differ.first != real_root.end()) return std::nullopt;
  if (!fs::is_regular_file(file, error)) return std::nullopt;
  return file;
}

std::string_view mime_type(std::string_view path) {
  const auto slash = path.rfind('/');
  const std::string_view name = slash == std::string_view::npos ? path : path.substr(slash + 1);
  const auto dot = name.rfind('.');
  if (dot == std::string_view::npos) return "application/octet-stream";
  std::string extension;
  for (const char c : name.substr(dot + 1)) extension += lower(c);
  for (const auto& [known, type] : kMimeTypes) {
    if (extension == known) return type;
  }
  return "application/octet-stream";
}

}  // namespace marsokhod::link
