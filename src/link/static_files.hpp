// Which file of the console's build (web/dist) an HTTP request names, decided on the text of the
// request alone: the server then only opens paths this returns, below its root. Rejected: a
// target that is not an absolute path, any "." or ".." segment (also written %2e%2e), a
// backslash, a NUL and bad percent escapes — a request may never leave the root.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace marsokhod::link {

struct StaticPath {
  bool ok = false;
  std::string relative_path;  // "index.html", "assets/app.js"; empty when !ok
  std::string reason;         // why the target was rejected; empty when ok
};

// "/" and any path ending in "/" name its index.html; the query and fragment are ignored.
StaticPath resolve_static_target(std::string_view target);

// The regular file `relative` (from resolve_static_target) names below `root`, with symbolic
// links resolved; nullopt if it does not exist or a link leads out of the root.
std::optional<std::filesystem::path> static_file_under(const std::filesystem::path& root,
                                                       const std::string& relative);

// The Content-Type for a file name by its extension (case-insensitive);
// "application/octet-stream" for an unknown one.
std::string_view mime_type(std::string_view path);

}  // namespace marsokhod::link
