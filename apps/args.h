#pragma once
// A small command-line parser: positional arguments and --name value flags,
// each validated with a one-line error naming the flag.
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace mvr::app {

// "WxH" with sides 1..16384; errors name the flag.
std::pair<int, int> parseSize(const std::string& flag, const std::string& text);

class Args {
 public:
  // flags: names that take a value; switches: names that take none.
  Args(int argc, char** argv, int first, std::set<std::string> flags,
       std::set<std::string> switches);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback) const;
  int getInt(const std::string& name, int fallback, int lo, int hi) const;
  double getDouble(const std::string& name, double fallback) const;
  // "WxH"
  std::pair<int, int> getSize(const std::string& name, std::pair<int, int> fallback) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

}  // namespace mvr::app
