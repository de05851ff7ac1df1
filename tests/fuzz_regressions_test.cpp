// Every input that ever failed the fuzzer's differential oracle (tests/fuzz/regressions/), replayed through
// the same oracle on every build: no clang needed, so CI guards each class found. And the NFF files of
// tests/data/nff/, through the same oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/nff_reader.h"
#include "test_support.h"
#include "tests/fuzz/differential_oracle.h"

namespace {

using raycube::testing_support::slurp;

// The regular files of a folder of the repository, sorted; with `extension`, only those that have it.
std::vector<std::filesystem::path> filesIn(const char* folder, const char* extension = nullptr) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(raycube::testing_support::sourcePath(folder)))
    if (entry.is_regular_file() && (extension == nullptr || entry.path().extension() == extension))
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::filesystem::path> regressions() {
  return filesIn("tests/fuzz/regressions");
}

// A file's stem as a test name: letters and digits only.
std::string testNameOf(const ::testing::TestParamInfo<std::filesystem::path>& info) {
  std::string name = info.param.stem().string();
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum((unsigned char)c); }, '_');
  return name;
}

class FuzzRegression : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(FuzzRegression, PassesTheDifferentialOracle) {
  EXPECT_EQ(raycube::fuzz::checkInput(slurp(GetParam()), GetParam().filename().string()), "");
}

INSTANTIATE_TEST_SUITE_P(Corpus, FuzzRegression, ::testing::ValuesIn(regressions()), testNameOf);

TEST(FuzzRegressionCorpus, IsNotEmpty) {
  EXPECT_GE(regressions().size(), 2u);
}

// NFF as people wrote it (tests/data/nff/: free layout, no lights, degenerate polygons skipped, VM_pRAY's
// hints): read, not refused, and the same image in every mode and precision.
class NffInTheWild : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(NffInTheWild, IsReadAndRendersTheSameInEveryModeAndPrecision) {
  const std::string text = slurp(GetParam());
  ASSERT_FALSE(text.empty()) << GetParam();
  EXPECT_NO_THROW(raycube::core::parseNff(text, GetParam().string()));
  EXPECT_EQ(raycube::fuzz::checkInput(text, GetParam().filename().string()), "");
}

INSTANTIATE_TEST_SUITE_P(Files, NffInTheWild, ::testing::ValuesIn(filesIn("tests/data/nff", ".nff")),
                         testNameOf);

}  // namespace
