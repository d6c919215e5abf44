// A grey-scale image in the Netpbm PGM format (P2 plain text, P5 binary, 8 or 16 bits), the
// format a scenario's heightfield comes in: every image editor writes it and its header is three
// numbers, so the simulator needs no image library.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

namespace marsokhod::sim {

struct GrayImage {
  std::size_t width = 0;
  std::size_t height = 0;
  // Row-major, the top row first (as the file stores it), each value scaled to [0, 1] by maxval.
  std::vector<double> values;

  double at(std::size_t row, std::size_t column) const { return values[row * width + column]; }
};

// Parses the bytes of a PGM file. Throws std::invalid_argument naming what is wrong (magic number,
// header field, truncated pixel data, a sample above maxval).
GrayImage parse_pgm(std::string_view bytes);

// Reads and parses a PGM file; the error names the file.
GrayImage read_pgm(const std::filesystem::path& path);

}  // namespace marsokhod::sim
