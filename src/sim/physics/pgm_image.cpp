#include "sim/physics/pgm_image.hpp"

#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>

namespace marsokhod::sim {
namespace {

// Walks the bytes of the file; the header allows comments ('#' to the end of the line) between
// its fields.
class PgmCursor {
 public:
  explicit PgmCursor(std::string_view bytes) : bytes_(bytes) {}

  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
      } else if (std::isspace(static_cast<unsigned char>(c)) != 0) {
        ++pos_;
      } else {
        return;
      }
    }
  }

  // A decimal number of the header or of a P2 raster; `what` names it in the error.
  std::uint32_t number(const char* what) {
    skip_space_and_comments();
    std::uint64_t value = 0;
    std::size_t digits = 0;
    while (pos_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[pos_])) != 0) {
      value = value * 10 + static_cast<std::uint64_t>(bytes_[pos_] - '0');
      if (value > std::numeric_limits<std::uint32_t>::max()) {
        throw std::invalid_argument(std::string("PGM: ") + what + " is too large");
      }
      ++pos_;
      ++digits;
    }
    if (digits == 0) {
      throw std::invalid_argument(std::string("PGM: expected a decimal number for ") + what +
                                  " at byte " + std::to_string(pos_));
    }
    return static_cast<std::uint32_t>(value);
  }

  std::string_view take(std::size_t count) {
    const std::string_view out = bytes_.substr(pos_, count);
    pos_ += out.size();
    return out;
  }

  std::size_t remaining() const { return bytes_.size() - pos_; }
  void skip_one() { ++pos_; }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
};

double checked_sample(std::uint32_t sample, std::uint32_t maxval, std::size_t index) {
  if (sample > maxval) {
    throw std::invalid_argument("PGM: pixel " + std::to_string(index) + " is " +
                                std::to_string(sample) + ", above maxval " +
                                std::to_string(maxval));
  }
  return static_cast<double>(sample) / static_cast<double>(maxval);
}

void read_binary_raster(PgmCursor& cursor, std::uint32_t maxval, GrayImage& image) {
  // Exactly one whitespace byte separates maxval from the raster (Netpbm's rule).
  cursor.skip_one();
  const std::size_t bytes_per_sample = maxval < 256 ? 1 : 2;
  const std::size_t count = image.width * image.height;
  if (cursor.remaining() < count * bytes_per_sample) {
    throw std::invalid_argument(
        "PGM: the binary raster is truncated: " + std::to_string(count * bytes_per_sample) +
        " bytes needed, " + std::to_string(cursor.remaining()) + " present");
  }
  const std::string_view raster = cursor.take(count * bytes_per_sample);
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t sample = static_cast<unsigned char>(raster[i * bytes_per_sample]);
    if (bytes_per_sample == 2) {  // 16-bit samples are big-endian
      sample = (sample << 8) | static_cast<unsigned char>(raster[i * 2 + 1]);
    }
    image.values.push_back(checked_sample(sample, maxval, i));
  }
}

void read_plain_raster(PgmCursor& cursor, std::uint32_t maxval, GrayImage& image) {
  const std::size_t count = image.width * image.height;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t sample = cursor.number("a pixel of the P2 raster");
    image.values.push_back(checked_sample(sample, maxval, i));
  }
}

}  // namespace

GrayImage parse_pgm(std::string_view bytes) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '2' && bytes[1] != '5')) {
    throw std::invalid_argument(
        "PGM: the file does not start with P2 or P5; save the heightfield as a grey-scale PGM");
  }
  const bool binary = bytes[1] == '5';
  PgmCursor cursor(bytes.substr(2));
  GrayImage image;
  image.width = cursor.number("the width");
  image.height = cursor.number("the height");
  const std::uint32_t maxval = cursor.number("maxval");
  if (image.width < 2 || image.height < 2) {
    throw std::invalid_argument("PGM: the image is " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) +
                                " pixels; a heightfield needs at least 2x2");
  }
  if (maxval == 0 || maxval > 65535) {
    throw std::invalid_argument("PGM: maxval is " + std::to_string(maxval) +
                                "; it must be within 1..65535");
  }
  // Every pixel takes at least one byte in either format: a header promising more is rejected
  // before anything is allocated for it.
  if (image.width * image.height > cursor.remaining()) {
    throw std::invalid_argument("PGM: the header promises " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " pixels but the file is shorter");
  }
  image.values.reserve(image.width * image.height);
  if (binary) {
    read_binary_raster(cursor, maxval, image);
  } else {
    read_plain_raster(cursor, maxval, image);
  }
  return image;
}

GrayImage read_pgm(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw std::invalid_argument("cannot open the heightfield image " + path.string());
  }
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  try {
    return parse_pgm(bytes);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(path.string() + ": " + e.what());
  }
}

}  // namespace marsokhod::sim
