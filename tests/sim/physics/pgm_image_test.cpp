#include "sim/physics/pgm_image.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "../../support/invalid_argument.hpp"

namespace marsokhod::sim {
namespace {

TEST(PgmImage, PlainWithCommentsScalesByMaxval) {
  const GrayImage image = parse_pgm("P2\n# a ridge\n3 2\n# maxval next\n4\n0 2 4\n4 2 0\n");
  ASSERT_EQ(image.width, 3u);
  ASSERT_EQ(image.height, 2u);
  EXPECT_DOUBLE_EQ(image.at(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(image.at(0, 1), 0.5);
  EXPECT_DOUBLE_EQ(image.at(0, 2), 1.0);
  EXPECT_DOUBLE_EQ(image.at(1, 0), 1.0);
}

TEST(PgmImage, BinaryEightBit) {
  std::string bytes = "P5 2 2 255\n";
  bytes += std::string{'\x00', '\xff', '\x80', '\x33'};
  const GrayImage image = parse_pgm(bytes);
  EXPECT_DOUBLE_EQ(image.at(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(image.at(1, 0), 128.0 / 255.0);
  EXPECT_DOUBLE_EQ(image.at(1, 1), 51.0 / 255.0);
}

TEST(PgmImage, BinarySixteenBitIsBigEndian) {
  std::string bytes = "P5\n2 2\n65535\n";
  bytes += std::string{'\x00', '\x00', '\xff', '\xff', '\x80', '\x00', '\x00', '\x01'};
  const GrayImage image = parse_pgm(bytes);
  EXPECT_DOUBLE_EQ(image.at(0, 1), 1.0);
  EXPECT_DOUBLE_EQ(image.at(1, 0), 32768.0 / 65535.0);
  EXPECT_DOUBLE_EQ(image.at(1, 1), 1.0 / 65535.0);
}

void expect_rejected(const std::string& bytes, const std::string& fragment) {
  test_support::expect_invalid_argument([&] { parse_pgm(bytes); }, {fragment});
}

TEST(PgmImage, RejectsWhatItCannotRead) {
  expect_rejected("P6 2 2 255\n", "P2 or P5");  // a colour image
  expect_rejected("P2 2 x 255\n", "height");
  expect_rejected("P2 1 1 255\n7\n", "at least 2x2");
  expect_rejected("P2 2 2 0\n0 0 0 0\n", "maxval");
  expect_rejected("P2 2 2 9\n0 1 2 10\n", "above maxval");
  expect_rejected("P5 2 2 255\n\x01\x02\x03", "truncated");
  expect_rejected("P5 2 2 65535\n\x01\x02\x03\x04\x05\x06", "truncated");
  expect_rejected("P2 100000 100000 255\n0 0", "shorter");  // no allocation for a lie
}

TEST(PgmImage, ReadsAFileAndNamesAMissingOne) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "marsokhod_pgm_image_test.pgm";
  std::ofstream(path) << "P2 2 2 1\n0 1\n1 0\n";
  const GrayImage image = read_pgm(path);
  std::filesystem::remove(path);
  EXPECT_DOUBLE_EQ(image.at(1, 0), 1.0);
  try {
    read_pgm(path);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos);
  }
}

}  // namespace
}  // namespace marsokhod::sim
