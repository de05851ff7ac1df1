#pragma once
// The differential oracle shared by the fuzz target (tests/fuzz/fuzz_nff.cpp, libFuzzer) and the replay test
// (tests/fuzz_regressions_test.cpp, an ordinary ctest): one input, every rule a scene file must obey.
#include <string>
#include <string_view>

namespace raycube::fuzz {

// Parses `text` as NFF named `source`. A parse error must name source:line:column. A scene that parses is
// rendered tiny (at most 8x8, depth 3) in the reference, image-parallel and machine modes (threads at 2x2
// with a BVH and with the paper's cells, BSPs, strips, tiny FIFOs, every light-ray mode) in both precisions:
// every mode must return an image bit-identical to the reference's, or every mode must refuse the scene
// alike. A machine that stalls fails; a render still running after RAYCUBE_ORACLE_SECONDS (30) hangs, and
// the program aborts naming it. Returns "" when the input passes, otherwise what went wrong, for a human.
std::string checkInput(std::string_view text, std::string_view source);

}  // namespace raycube::fuzz
