#include "config/param_docs.hpp"

#include <sstream>

#include "config/config_reader.hpp"

namespace marsokhod::config {
namespace {

std::string range(const ParamSpec& p) {
  return "[" + show_number(p.min) + ", " + show_number(p.max) + "]";
}

// The type column, in the order of ParamKind.
constexpr std::string_view kKindNames[] = {"number", "integer", "boolean", "string",
                                           "strings", "string",  "numbers"};

std::string_view kind_name(const ParamSpec& p) {
  return kKindNames[static_cast<std::size_t>(p.field.kind)];
}

std::string allowed(const ParamSpec& p) {
  switch (p.field.kind) {
    case ParamKind::kNumber:
    case ParamKind::kInteger:
      return range(p);
    case ParamKind::kBoolean:
      return "true, false";
    case ParamKind::kText:
      return "at most " + std::to_string(p.max_length) + " characters";
    case ParamKind::kTexts:
      return "at most " + std::to_string(p.max_count) + ", each 1 to " +
             std::to_string(p.max_length) + " characters";
    case ParamKind::kChoice: {
      std::string out;
      for (std::string_view c : p.choices) out += (out.empty() ? "" : ", ") + std::string(c);
      return out;
    }
    case ParamKind::kNumbers: {
      const std::string count =
          p.count_min() == p.count_max()
              ? std::to_string(p.count_min())
              : std::to_string(p.count_min()) + " to " + std::to_string(p.count_max());
      return count + ", each in " + range(p);
    }
  }
  return "";
}

std::string thesis(const ParamSpec& p) {
  if (p.symbol.empty()) return std::string(p.source);
  if (p.source.empty()) return std::string(p.symbol);
  return std::string(p.symbol) + ", " + std::string(p.source);
}

// A table cell: a | would end it.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// The shipped value: every entry's for an array of tables.
std::string shipped(const SectionSpec& section, const ParamSpec& p, const Configuration& c) {
  std::string out;
  for (std::size_t i = 0; i < section.entries(c); ++i) {
    out += (i == 0 ? "" : "; ") + format_value(p, p.field.load(section.at_const(c, i)));
  }
  return "`" + out + "`";
}

void write_section(std::ostringstream& out, const SectionSpec& s, const Configuration& defaults) {
  out << "\n## `" << (s.repeated ? "[[" : "[") << s.name << (s.repeated ? "]]" : "]") << "`";
  if (!s.source.empty()) out << " — " << s.source;
  out << "\n\n" << s.about << ".";
  if (s.repeated) out << " An array of tables: one or more, each with every key.";
  out << "\n\n| key | value | type | allowed | unit | thesis | meaning |\n"
      << "|---|---|---|---|---|---|---|\n";
  for (const ParamSpec& p : s.params) {
    out << "| `" << p.key << "` | " << cell(shipped(s, p, defaults)) << " | " << kind_name(p)
        << " | " << cell(allowed(p)) << " | " << cell(p.unit) << " | " << cell(thesis(p)) << " | "
        << cell(p.about) << (p.calibrated ? " *(calibrated)*" : "") << " |\n";
  }
}

constexpr const char* kIntroduction = R"(# Configuration parameters

<!-- Generated from src/config/param_schema.cpp by `make params-doc`; do not edit. -->

Every key of `config/marsokhod.toml`, generated from the one table the loader reads by
(`src/config/param_schema.cpp`); a test fails when this page is stale. Every key is required. A
missing or unknown key, a wrong type or a value outside *allowed* is an error naming the key, the
value, what is allowed and FILE:LINE. Relations between values (h below T(con), ordered joint
bounds, monotone W, a δ table for the configured cycle) are checked after the ranges
(`src/config/consistency.cpp`).

*value* is the shipped value: the thesis' where it gives one, and the default in
`src/core/params.hpp`. *thesis* is the symbol and the equation, procedure or figure of "Mobility and
Autonomous Reconfiguration of Marsokhod" (2008); where a row names none, its section's holds.
Vectors over the 8 motors follow (3.1): 0 FL, 1 FR, 2 CL, 3 CR, 4 BL, 5 BR, 6 AF, 7 AR.
*(calibrated)* values may also come from a calibration file ([calibration.md](calibration.md)).
)";

}  // namespace

std::string format_value(const ParamSpec& spec, const ParamValue& value) {
  std::ostringstream out;
  if (const auto* d = std::get_if<double>(&value)) {
    out << show_number(*d);
  } else if (const auto* i = std::get_if<std::int64_t>(&value)) {
    if (spec.field.kind == ParamKind::kChoice)
      out << '"' << spec.choices[static_cast<std::size_t>(*i)] << '"';
    else
      out << *i;
  } else if (const auto* b = std::get_if<bool>(&value)) {
    out << (*b ? "true" : "false");
  } else if (const auto* s = std::get_if<std::string>(&value)) {
    out << '"' << *s << '"';
  } else if (const auto* numbers = std::get_if<std::vector<double>>(&value)) {
    out << '[';
    for (std::size_t k = 0; k < numbers->size(); ++k)
      out << (k ? ", " : "") << show_number((*numbers)[k]);
    out << ']';
  } else if (const auto* texts = std::get_if<std::vector<std::string>>(&value)) {
    out << '[';
    for (std::size_t k = 0; k < texts->size(); ++k)
      out << (k ? ", \"" : "\"") << (*texts)[k] << '"';
    out << ']';
  }
  return out.str();
}

std::string parameters_markdown() {
  std::ostringstream out;
  out << kIntroduction;
  const Configuration defaults;
  for (const SectionSpec& section : param_schema()) write_section(out, section, defaults);
  return out.str();
}

}  // namespace marsokhod::config
