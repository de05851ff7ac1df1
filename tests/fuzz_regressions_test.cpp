// Every input that ever failed the fuzzer's differential oracle (tests/fuzz/regressions/), replayed through
// the same oracle on every build: no clang needed, so CI guards each class found.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/differential_oracle.h"

namespace {

std::vector<std::filesystem::path> regressions() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(RAYCUBE_SOURCE_DIR) / "tests/fuzz/regressions"))
    if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

class FuzzRegression : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(FuzzRegression, PassesTheDifferentialOracle) {
  std::ifstream in(GetParam(), std::ios::binary);
  ASSERT_TRUE(in) << GetParam();
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(raycube::fuzz::checkInput(text.str(), GetParam().filename().string()), "");
}

INSTANTIATE_TEST_SUITE_P(Corpus, FuzzRegression, ::testing::ValuesIn(regressions()),
                         [](const ::testing::TestParamInfo<std::filesystem::path>& info) {
                           std::string name = info.param.stem().string();
                           std::replace_if(
                               name.begin(), name.end(), [](char c) { return !std::isalnum((unsigned char)c); },
                               '_');
                           return name;
                         });

TEST(FuzzRegressionCorpus, IsNotEmpty) { EXPECT_GE(regressions().size(), 2u); }

}  // namespace
