#pragma once
// Tests of the loaders: a folder of its own per test for the files it
// writes, and the expectation every bad input shares, one mvr::Error of
// one line naming the file.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "mvr/error.h"

namespace mvr::test {

class FileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo& info = *::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("mvr_" + std::string(info.test_suite_name()) + "_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" + info.name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Writes text to dir_ / name (its folders made); returns the path.
  std::string write(const std::filesystem::path& name, const std::string& text) {
    std::filesystem::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  std::filesystem::path dir_;
};

// Calls load(), which must throw mvr::Error: one line holding `names`
// (the file, or what else the message must name) and `what`.
template <class Load>
void expectOneLineError(Load&& load, const std::string& names, const std::string& what) {
  try {
    load();
    ADD_FAILURE() << "no error for " << names;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(names), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
  }
}

}  // namespace mvr::test
