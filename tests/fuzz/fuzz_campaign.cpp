// The differential oracle driven by the structure-aware mutator alone, with any compiler (issue 41): where
// libFuzzer's coverage build is out of reach (clang, an instrumented build of everything), this runs the
// same mutations over the seeds and stops at the first failing input, which it writes out.
//   fuzz_campaign OUT_DIR SECONDS SEED SEED_FILES...
// Prints inputs, inputs per second and the failures (each written to OUT_DIR/failure-N.nff) at the end.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tests/fuzz/differential_oracle.h"
#include "tests/fuzz/nff_mutator.h"

namespace {

std::string slurp(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s OUT_DIR SECONDS SEED SEED_FILES...\n", argv[0]);
    return 2;
  }
  const std::string out = argv[1];
  std::filesystem::create_directories(out);
  const auto seconds = std::chrono::seconds(std::atoi(argv[2]));
  std::mt19937_64 random(std::strtoull(argv[3], nullptr, 10));
  std::vector<std::string> pool;
  for (int i = 4; i < argc; ++i) pool.push_back(slurp(argv[i]));
  const auto start = std::chrono::steady_clock::now();
  long long inputs = 0, failures = 0;
  while (std::chrono::steady_clock::now() - start < seconds) {
    // A seed (or an input grown from one) mutated one to four times.
    std::string text = pool[std::uniform_int_distribution<std::size_t>(0, pool.size() - 1)(random)];
    const int rounds = 1 + int(random() % 4);
    for (int r = 0; r < rounds; ++r) text = raycube::fuzz::mutateNff(text, random);
    if (text.size() > 4096) continue;
    ++inputs;
    // The input under test, kept until the next one: a crash of the renderer leaves it behind.
    std::ofstream(out + "/current.nff", std::ios::binary | std::ios::trunc) << text;
    const std::string failure = raycube::fuzz::checkInput(text, "fuzz.nff");
    if (!failure.empty()) {
      const std::string path = out + "/failure-" + std::to_string(failures++) + ".nff";
      std::ofstream(path, std::ios::binary) << text;
      std::printf("FAILURE %s: %s\n", path.c_str(), failure.c_str());
      std::fflush(stdout);
    } else if (random() % 8 == 0 && pool.size() < 4096) {
      pool.push_back(text);  // grow the pool with passing inputs, so mutations compound
    }
    if (inputs % 1000 == 0) {
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("inputs %lld, %.1f/s, failures %lld\n", inputs, double(inputs) / elapsed, failures);
      std::fflush(stdout);
    }
  }
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("done: inputs %lld in %.0f s, %.1f/s, failures %lld\n", inputs, elapsed,
              double(inputs) / elapsed, failures);
  return failures == 0 ? 0 : 1;
}
