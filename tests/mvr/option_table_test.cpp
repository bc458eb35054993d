// Back-end options declared once (mvr/option_table.h): each table's
// defaults lie in its ranges, its keys and flags are unique, and a bench
// spec sets each number through its key and is refused, naming the flag,
// outside the range.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "mvr/backends/backend.h"

namespace mvr {
namespace {

template <class Options>
void expectWellFormed(std::span<const NumberOption<Options>> numbers, std::span<const FlagOption<Options>> flags) {
  std::set<std::string> keys, names;
  for (const NumberOption<Options>& n : numbers) {
    EXPECT_TRUE(keys.insert(n.key).second) << n.flag;
    EXPECT_TRUE(names.insert(n.flag).second) << n.flag;
    EXPECT_TRUE(n.inRange(n.get(Options{}))) << n.flag << ": default outside " << n.range();
    EXPECT_NE(std::string(n.help), "") << n.flag;
  }
  for (const FlagOption<Options>& f : flags) {
    EXPECT_TRUE(keys.insert(f.key).second) << f.flag;
    EXPECT_TRUE(names.insert(f.flag).second) << f.flag;
    EXPECT_NE(Options{}.*f.member, f.value) << f.flag << " changes nothing";
  }
}

TEST(OptionTable, DefaultsInRangeKeysAndFlagsUnique) {
  expectWellFormed<InterpOptions>(kInterpNumbers, kInterpFlags);
  expectWellFormed<WarpOptions>(kWarpNumbers, {});
}

std::string errorOf(const std::string& spec) {
  try {
    parseBackendSpec(spec);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Each number at its lower end through the spec, then below it (or, for an
// open range, at it).
template <class Options>
void expectSpecsSetAndCheck(const std::string& prefix, std::span<const NumberOption<Options>> numbers,
                            const Options& (*of)(const BackendOptions&)) {
  for (const NumberOption<Options>& n : numbers) {
    const double low = n.open ? (n.min + n.max) / 2 : n.min;
    char value[32];
    std::snprintf(value, sizeof value, "%g", low);
    const std::string spec = prefix + n.key + value;
    EXPECT_EQ(errorOf(spec), "") << spec;
    if (errorOf(spec).empty()) {
      EXPECT_EQ(n.get(of(parseBackendSpec(spec))), low) << spec;
    }
    std::snprintf(value, sizeof value, "%g", n.min - (n.open ? 0 : 1));
    EXPECT_NE(errorOf(prefix + n.key + value).find(n.flag), std::string::npos) << prefix + n.key + value;
  }
}

TEST(OptionTable, SpecsSetEachNumberAndRefuseItOutsideItsRange) {
  expectSpecsSetAndCheck<InterpOptions>(
      "interp:hierarchical:", kInterpNumbers, +[](const BackendOptions& o) -> const InterpOptions& { return o.interp; });
  expectSpecsSetAndCheck<WarpOptions>(
      "warp:hierarchical:", kWarpNumbers, +[](const BackendOptions& o) -> const WarpOptions& { return o.warp; });
  // An integer takes no fraction; a switch is its word.
  EXPECT_NE(errorOf("interp:dual:x2.5").find("unknown interp option 'x2.5'"), std::string::npos);
  EXPECT_FALSE(parseBackendSpec("interp:dual:whole").interp.halves);
  EXPECT_TRUE(parseBackendSpec("interp:dual:vis").interp.visibility);
}

}  // namespace
}  // namespace mvr
