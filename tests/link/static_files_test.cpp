// Static file resolution: index.html for "/", no way out of the root, MIME types by extension.
#include "link/static_files.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

namespace marsokhod::link {
namespace {

namespace fs = std::filesystem;

TEST(StaticFiles, MapsTargetsToRelativePaths) {
  EXPECT_EQ(resolve_static_target("/").relative_path, "index.html");
  EXPECT_EQ(resolve_static_target("/?token=abc").relative_path, "index.html");
  EXPECT_EQ(resolve_static_target("/assets/app.js").relative_path, "assets/app.js");
  EXPECT_EQ(resolve_static_target("/docs/").relative_path, "docs/index.html");
  EXPECT_EQ(resolve_static_target("/a%20b.txt").relative_path, "a b.txt");
}

TEST(StaticFiles, RejectsEveryWayOut) {
  for (const char* target : {"/..", "/../etc/passwd", "/assets/../../x", "/%2e%2e/x",
                             "/%2E%2E", "/assets/..", "..", "index.html", "", "/a\\..\\b",
                             "/a%5c..", "/%00", "/a%2", "/a%zz", "/./index.html", "//etc"}) {
    const StaticPath path = resolve_static_target(target);
    EXPECT_FALSE(path.ok) << target;
    EXPECT_FALSE(path.reason.empty()) << target;
    EXPECT_TRUE(path.relative_path.empty()) << target;
  }
  EXPECT_NE(resolve_static_target("/../x").reason.find(".."), std::string::npos);
}

TEST(StaticFiles, FindsRegularFilesOnlyInsideTheRoot) {
  const fs::path base = fs::temp_directory_path() / ("marsokhod_static_" + std::to_string(::getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "dist" / "assets");
  std::ofstream(base / "dist" / "index.html") << "<html></html>";
  std::ofstream(base / "secret.txt") << "secret";
  fs::create_symlink(base / "secret.txt", base / "dist" / "leak.txt");
  EXPECT_TRUE(static_file_under(base / "dist", "index.html").has_value());
  EXPECT_FALSE(static_file_under(base / "dist", "missing.html").has_value());
  EXPECT_FALSE(static_file_under(base / "dist", "assets").has_value());  // a directory
  EXPECT_FALSE(static_file_under(base / "dist", "leak.txt").has_value());
  EXPECT_FALSE(static_file_under(base / "nowhere", "index.html").has_value());
  fs::remove_all(base);
}

TEST(StaticFiles, KnowsTheConsolesMimeTypes) {
  EXPECT_EQ(mime_type("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(mime_type("assets/index-3f2a.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(mime_type("assets/INDEX.CSS"), "text/css; charset=utf-8");
  EXPECT_EQ(mime_type("rover.glb"), "model/gltf-binary");
  EXPECT_EQ(mime_type("favicon.svg"), "image/svg+xml");
  EXPECT_EQ(mime_type("module.wasm"), "application/wasm");
  EXPECT_EQ(mime_type("assets.d/README"), "application/octet-stream");
  EXPECT_EQ(mime_type("data.bin"), "application/octet-stream");
}

}  // namespace
}  // namespace marsokhod::link
