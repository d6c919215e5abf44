// The parameter schema: one table (param_schema.cpp) names every key of config/marsokhod.toml with
// its type, range, unit, thesis source and meaning, and binds it to its field of Configuration.
// It drives the loader (load_params.cpp: what to read, what to check, what errors say), the
// calibration file's allowed keys (calibration.cpp) and the reference page docs/parameters.md
// (param_docs.cpp). A parameter is added in three places that tests hold together: its field in
// core/params.hpp (with the thesis' value as default), its row here, its line in the TOML file.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "config/configuration.hpp"

namespace marsokhod::config {

// What a parameter's TOML value is.
enum class ParamKind {
  kNumber,   // a number in [min, max] (an integer is a number too)
  kInteger,  // an integer in [min, max]
  kBoolean,  // true or false
  kText,     // a string of at most max_length characters
  kTexts,    // an array of at most max_count strings of 1 to max_length characters
  kChoice,   // one of `choices`
  kNumbers,  // an array of min_count to max_count numbers, each in [min, max]
};

// A value between TOML and a field: kNumber double, kInteger std::int64_t, kBoolean bool, kText
// string, kTexts vector<string>, kChoice the index into `choices` (std::int64_t), kNumbers
// vector<double>.
using ParamValue = std::variant<double, std::int64_t, bool, std::string, std::vector<double>,
                                std::vector<std::string>>;

// A field of a section's struct, type-erased: made by field<…> or column<…> below, which also
// give its kind from the field's C++ type.
struct FieldBinding {
  ParamKind kind;
  std::size_t fixed_count;  // a std::array field's size (kNumbers); else 0
  const void* owner;        // the section struct's type (detail::kTypeTag)
  void (*store)(void* section, const ParamValue& value);
  ParamValue (*load)(const void* section);
};

// One parameter: a key of its section.
struct ParamSpec {
  std::string_view key;
  FieldBinding field;
  double min = 0.0;  // kNumber, kInteger, and each element of kNumbers
  double max = 0.0;
  std::size_t min_count = 0;                       // kNumbers of a std::vector
  std::size_t max_count = 0;                       // kNumbers of a std::vector, kTexts
  std::size_t max_length = 0;                      // kText, kTexts
  std::span<const std::string_view> choices = {};  // kChoice, in the order of the enum
  std::string_view unit = "";                      // "" for a pure number
  std::string_view symbol = "";                    // the thesis' notation, "" where it has none
  std::string_view source = "";  // the equation, procedure or figure; "" for the section's
  std::string_view about = "";   // what it means (docs/parameters.md)
  bool calibrated = false;       // a calibration file may set it (calibration.hpp)

  // Elements a kNumbers value must have: its std::array's size, else min_count..max_count.
  std::size_t count_min() const { return field.fixed_count != 0 ? field.fixed_count : min_count; }
  std::size_t count_max() const { return field.fixed_count != 0 ? field.fixed_count : max_count; }
};

// One TOML table [name], or an array of tables [[name]] (at least one entry), of Configuration.
struct SectionSpec {
  std::string_view name;
  bool repeated;            // [[name]]: a std::vector of the section's struct
  std::string_view source;  // the thesis' chapter, figure or procedure
  std::string_view about;
  std::span<const ParamSpec> params;
  std::size_t (*entries)(const Configuration& c);    // 1 for a table
  void (*resize)(Configuration& c, std::size_t n);   // a repeated section's entries; else no-op
  void* (*at)(Configuration& c, std::size_t entry);  // the struct the params are stored in
  const void* (*at_const)(const Configuration& c, std::size_t entry);
};

// The schema, in the order of config/marsokhod.toml.
std::span<const SectionSpec> param_schema();

// The section named `name`, or nullptr.
const SectionSpec* find_section(std::string_view name);

// ---- Building the table (param_schema.cpp) ----
namespace detail {

template <class T>
inline constexpr char kTypeTag = 0;  // &kTypeTag<T> stands for the type T

template <auto First, auto... Rest, class Object>
constexpr auto& follow(Object& object) {
  return ((object.*First).*....*Rest);
}

template <class C, class T>
C class_of(T C::*);

template <auto First, auto... Rest>
inline constexpr auto kHead = First;

template <class T>
struct IsStdArray : std::false_type {};
template <class T, std::size_t N>
struct IsStdArray<std::array<T, N>> : std::true_type {};

template <class T>
constexpr ParamKind kind_of() {
  if constexpr (std::is_same_v<T, double>)
    return ParamKind::kNumber;
  else if constexpr (std::is_same_v<T, int>)
    return ParamKind::kInteger;
  else if constexpr (std::is_same_v<T, bool>)
    return ParamKind::kBoolean;
  else if constexpr (std::is_same_v<T, std::string>)
    return ParamKind::kText;
  else if constexpr (std::is_same_v<T, std::vector<std::string>>)
    return ParamKind::kTexts;
  else if constexpr (std::is_enum_v<T>)
    return ParamKind::kChoice;
  else {
    static_assert(std::is_same_v<T, std::vector<double>> || IsStdArray<T>::value,
                  "a parameter is a number, integer, boolean, string, strings, enum or numbers");
    return ParamKind::kNumbers;
  }
}

template <class T>
constexpr std::size_t fixed_count_of() {
  if constexpr (IsStdArray<T>::value)
    return std::tuple_size_v<T>;
  else
    return 0;
}

template <class T>
void assign(T& field, const ParamValue& value) {
  if constexpr (std::is_same_v<T, int> || std::is_enum_v<T>) {
    field = static_cast<T>(std::get<std::int64_t>(value));
  } else if constexpr (IsStdArray<T>::value) {
    const auto& numbers = std::get<std::vector<double>>(value);
    for (std::size_t i = 0; i < field.size() && i < numbers.size(); ++i) field[i] = numbers[i];
  } else {
    field = std::get<T>(value);
  }
}

template <class T>
ParamValue value_of(const T& field) {
  if constexpr (std::is_same_v<T, int> || std::is_enum_v<T>) {
    return static_cast<std::int64_t>(field);
  } else if constexpr (IsStdArray<T>::value) {
    return std::vector<double>(field.begin(), field.end());
  } else {
    return field;
  }
}

template <auto... Path>
struct Field {
  using Section = decltype(class_of(kHead<Path...>));  // the class of the path's first member
  using Value = std::remove_cvref_t<decltype(follow<Path...>(std::declval<Section&>()))>;
  static void store(void* s, const ParamValue& v) {
    assign(follow<Path...>(*static_cast<Section*>(s)), v);
  }
  static ParamValue load(const void* s) {
    return value_of(follow<Path...>(*static_cast<const Section*>(s)));
  }
};

// One member of each element of a std::array of structs, read as an array of numbers.
template <auto Array, auto Member>
struct Column {
  using Section = decltype(class_of(Array));
  static constexpr std::size_t kCount =
      std::tuple_size_v<std::remove_cvref_t<decltype(std::declval<Section&>().*Array)>>;
  static void store(void* s, const ParamValue& v) {
    const auto& numbers = std::get<std::vector<double>>(v);
    auto& elements = static_cast<Section*>(s)->*Array;
    for (std::size_t i = 0; i < elements.size() && i < numbers.size(); ++i) {
      elements[i].*Member = numbers[i];
    }
  }
  static ParamValue load(const void* s) {
    std::vector<double> out;
    for (const auto& element : static_cast<const Section*>(s)->*Array)
      out.push_back(element.*Member);
    return out;
  }
};

}  // namespace detail

// The field at the end of a path of members from its section's struct: field<&GeometryParams::a>,
// field<&SensorParams::tilt_front, &LinearConversion::gain>.
template <auto... Path>
inline constexpr FieldBinding field{
    detail::kind_of<typename detail::Field<Path...>::Value>(),
    detail::fixed_count_of<typename detail::Field<Path...>::Value>(),
    &detail::kTypeTag<typename detail::Field<Path...>::Section>, &detail::Field<Path...>::store,
    &detail::Field<Path...>::load};

// `Member` of every element of the std::array `Array`: an array of numbers.
template <auto Array, auto Member>
inline constexpr FieldBinding column{
    ParamKind::kNumbers, detail::Column<Array, Member>::kCount,
    &detail::kTypeTag<typename detail::Column<Array, Member>::Section>,
    &detail::Column<Array, Member>::store, &detail::Column<Array, Member>::load};

// A section at the end of a path of members from Configuration: a struct (table<…>) or a
// std::vector of structs (repeated<…>). Every parameter must be a field of that struct.
template <auto... Path>
consteval SectionSpec table(std::string_view name, std::string_view source, std::string_view about,
                            std::span<const ParamSpec> params) {
  using Section =
      std::remove_cvref_t<decltype(detail::follow<Path...>(std::declval<Configuration&>()))>;
  for (const ParamSpec& p : params) {
    if (p.field.owner != &detail::kTypeTag<Section>)
      throw "a parameter of another section's struct";
  }
  return {name,
          false,
          source,
          about,
          params,
          [](const Configuration&) -> std::size_t { return 1; },
          [](Configuration&, std::size_t) {},
          [](Configuration& c, std::size_t) -> void* { return &detail::follow<Path...>(c); },
          [](const Configuration& c, std::size_t) -> const void* {
            return &detail::follow<Path...>(c);
          }};
}

template <auto... Path>
consteval SectionSpec repeated(std::string_view name, std::string_view source,
                               std::string_view about, std::span<const ParamSpec> params) {
  using Vector =
      std::remove_cvref_t<decltype(detail::follow<Path...>(std::declval<Configuration&>()))>;
  for (const ParamSpec& p : params) {
    if (p.field.owner != &detail::kTypeTag<typename Vector::value_type>) {
      throw "a parameter of another section's struct";
    }
  }
  return {name,
          true,
          source,
          about,
          params,
          [](const Configuration& c) { return detail::follow<Path...>(c).size(); },
          [](Configuration& c, std::size_t n) { detail::follow<Path...>(c).resize(n); },
          [](Configuration& c, std::size_t i) -> void* { return &detail::follow<Path...>(c)[i]; },
          [](const Configuration& c, std::size_t i) -> const void* {
            return &detail::follow<Path...>(c)[i];
          }};
}

}  // namespace marsokhod::config
