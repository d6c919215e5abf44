// A minimal XML writer for the generated MuJoCo model (MJCF): elements with attributes, numbers
// written in their shortest exact form so that the same Params give byte-identical XML.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/checks/checks.hpp"

namespace marsokhod::sim {

inline std::string xml_number(double value) { return checks::format_number(value); }

template <std::size_t N>
std::string xml_numbers(const std::array<double, N>& values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + xml_number(v);
  return out;
}

class XmlWriter {
 public:
  using Attributes = std::vector<std::pair<std::string_view, std::string>>;

  void open(std::string_view tag, const Attributes& attributes = {}) {
    start(tag, attributes);
    text_ += ">\n";
    open_.emplace_back(tag);
  }

  void leaf(std::string_view tag, const Attributes& attributes = {}) {
    start(tag, attributes);
    text_ += "/>\n";
  }

  void close() {
    indent(open_.size() - 1);
    text_ += "</" + open_.back() + ">\n";
    open_.pop_back();
  }

  const std::string& text() const { return text_; }

 private:
  void start(std::string_view tag, const Attributes& attributes) {
    indent(open_.size());
    text_ += "<";
    text_ += tag;
    for (const auto& [name, value] : attributes) {
      text_ += " ";
      text_ += name;
      text_ += "=\"" + value + "\"";
    }
  }

  void indent(std::size_t depth) { text_.append(depth * 2, ' '); }

  std::string text_;
  std::vector<std::string> open_;
};

}  // namespace marsokhod::sim
