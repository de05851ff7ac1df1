// Every input that ever failed the fuzzer's differential oracle (tests/fuzz/regressions/), replayed through
// the same oracle on every build: no clang needed, so CI guards each class found. And the NFF files of
// tests/data/nff/, through the same oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/nff_reader.h"
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

// A file's stem as a test name: letters and digits only.
std::string testNameOf(const ::testing::TestParamInfo<std::filesystem::path>& info) {
  std::string name = info.param.stem().string();
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum((unsigned char)c); }, '_');
  return name;
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
                         testNameOf);

TEST(FuzzRegressionCorpus, IsNotEmpty) { EXPECT_GE(regressions().size(), 2u); }

// NFF as people wrote it (tests/data/nff/: free layout, no lights, degenerate polygons skipped, VM_pRAY's
// hints): read, not refused, and the same image in every mode and precision.
std::vector<std::filesystem::path> nffInTheWild() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(RAYCUBE_SOURCE_DIR) / "tests/data/nff"))
    if (entry.path().extension() == ".nff") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

class NffInTheWild : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(NffInTheWild, IsReadAndRendersTheSameInEveryModeAndPrecision) {
  std::ifstream in(GetParam(), std::ios::binary);
  ASSERT_TRUE(in) << GetParam();
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_NO_THROW(raycube::core::parseNff(text.str(), GetParam().string()));
  EXPECT_EQ(raycube::fuzz::checkInput(text.str(), GetParam().filename().string()), "");
}

INSTANTIATE_TEST_SUITE_P(Files, NffInTheWild, ::testing::ValuesIn(nffInTheWild()),
                         testNameOf);

}  // namespace
