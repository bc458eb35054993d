#pragma once
// What every written image set holds: its views by name and a manifest
// that names the back end, the view count and the timings.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace mvr::test {

inline void expectSet(const std::filesystem::path& dir, int views, const std::string& backend) {
  for (int i = 0; i < views; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << dir / name;
  }
  ASSERT_TRUE(std::filesystem::exists(dir / "manifest.json"));
  const auto m = nlohmann::json::parse(std::ifstream(dir / "manifest.json"));
  EXPECT_EQ(m["backend"], backend);
  EXPECT_EQ(m["views"], views);
  EXPECT_TRUE(m["timings_s"].contains("total"));
}

}  // namespace mvr::test
