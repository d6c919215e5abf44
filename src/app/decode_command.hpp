// `marsokhod decode FILE`: a CAN trace in candump log format, each frame decoded on one line.
#pragma once

#include <iosfwd>
#include <string>

#include "core/params.hpp"

namespace marsokhod::app {

struct DecodeOptions {
  bool json = false;  // one JSON object a line instead of text
};

// Reads `in` line by line, writes decoded frames to `out` and one error a line to `err`
// ("<source>:<line>: <reason>"), and goes on after an invalid line. Returns 0 if every line was
// valid, 1 otherwise.
int decode_trace(std::istream& in, const std::string& source, const Params& params,
                 const DecodeOptions& options, std::ostream& out, std::ostream& err);

}  // namespace marsokhod::app
