#pragma once
// A back end's options declared once: the flag, its key in the bench's
// compact back-end specs, the member it sets (whose initializer is the
// default), its range and its help. The command line (apps/backend_flags),
// the spec parser (mvr/backends/backend.cpp), validate() and, through
// `--help`, docs/CLI.md all read the same table.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <variant>

#include "mvr/error.h"

namespace mvr {

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// A number. In a spec, `key` then the value ("x8"); an empty key takes a
// bare number.
template <class Options>
struct NumberOption {
  const char* flag;
  const char* key;
  std::variant<int Options::*, float Options::*> member;
  double min, max;        // inclusive unless open; max infinite: no upper bound
  bool open = false;      // both ends excluded
  const char* unit = "";  // the value's name in --help ("" for N, S ...)
  const char* help = "";

  double get(const Options& o) const {
    return std::visit([&](auto m) { return double(o.*m); }, member);
  }
  // "1 to 64", "in (0, 1)", "at least 0".
  std::string range() const {
    auto number = [](double v) {
      char text[32];
      std::snprintf(text, sizeof text, "%g", v);
      return std::string(text);
    };
    if (std::isinf(max)) return (open ? "above " : "at least ") + number(min);
    if (open) return "in (" + number(min) + ", " + number(max) + ")";
    return number(min) + " to " + number(max);
  }
  bool inRange(double v) const {
    return std::isfinite(v) && (open ? v > min && v < max : v >= min && v <= max);
  }
  // Throws naming the flag where o's value is out of range.
  void check(const Options& o) const {
    if (!inRange(get(o))) fail(flag, "must be " + range());
  }
  // Sets o's member to v; false where the member is an integer and v has
  // a fraction. An integer out of int's range is left out of range for
  // check() rather than cast.
  bool set(Options& o, double v) const {
    return std::visit(
        [&](auto m) {
          using T = std::remove_reference_t<decltype(o.*m)>;
          if (std::is_integral_v<T> && v != std::trunc(v)) return false;
          o.*m = std::is_integral_v<T> && !(std::abs(v) < 1e9) ? T(v > 0 ? 1e9 : -1e9) : T(v);
          return true;
        },
        member);
  }
  // Sets o's member from a spec's text; false where it is not a number.
  bool parse(const std::string& text, Options& o) const {
    if (text.empty()) return false;
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    return *end == '\0' && set(o, v);
  }
};

// A switch: given, it sets the member to `value`; in a spec, the word `key`.
template <class Options>
struct FlagOption {
  const char* flag;
  const char* key;
  bool Options::*member;
  bool value;
  const char* help;
};

template <class Options>
void checkRanges(std::span<const NumberOption<Options>> table, const Options& o) {
  for (const NumberOption<Options>& option : table) option.check(o);
}

// One spec token against the tables: a flag's word, or a number's key and
// value. False where no entry takes it.
template <class Options>
bool parseSpecToken(const std::string& token, std::span<const NumberOption<Options>> numbers,
                    std::span<const FlagOption<Options>> flags, Options& o) {
  for (const FlagOption<Options>& f : flags)
    if (token == f.key) {
      o.*f.member = f.value;
      return true;
    }
  for (const NumberOption<Options>& n : numbers) {
    const std::string key = n.key;
    if (token.size() > key.size() && token.compare(0, key.size(), key) == 0 && n.parse(token.substr(key.size()), o))
      return true;
  }
  return false;
}

}  // namespace mvr
