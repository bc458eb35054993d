#include "apps/args.h"

#include <cstdlib>

#include "mvr/error.h"

namespace mvr::app {

Args::Args(int argc, char** argv, int first, std::set<std::string> flags,
           std::set<std::string> switches) {
  for (int i = first; i < argc; ++i) {
    std::string a = argv[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    } else if (flags.count(name)) {
      if (i + 1 >= argc) fail(a, "needs a value");
      value = argv[++i];
    }
    if (!flags.count(name) && !switches.count(name)) fail(a, "unknown option (see --help)");
    values_[name] = value;
  }
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

int Args::getInt(const std::string& name, int fallback, int lo, int hi) const {
  if (!has(name)) return fallback;
  const std::string v = get(name, "");
  char* end = nullptr;
  long n = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end != '\0') fail("--" + name, "'" + v + "' is not an integer");
  if (n < lo || n > hi)
    fail("--" + name, v + " outside " + std::to_string(lo) + ".." + std::to_string(hi));
  return int(n);
}

double Args::getDouble(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string v = get(name, "");
  char* end = nullptr;
  double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0') fail("--" + name, "'" + v + "' is not a number");
  return d;
}

std::pair<int, int> parseSize(const std::string& flag, const std::string& v) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
      w < 1 || h < 1 || w > 16384 || h > 16384)
    fail(flag, "'" + v + "' is not WxH with sides 1..16384");
  return {w, h};
}

std::pair<int, int> Args::getSize(const std::string& name, std::pair<int, int> fallback) const {
  if (!has(name)) return fallback;
  return parseSize("--" + name, get(name, ""));
}

}  // namespace mvr::app
