#pragma once
// A structure-aware mutator over NFF lines (issue 41), for libFuzzer's custom mutator (fuzz_nff.cpp) and the
// compiler-independent campaign (fuzz_campaign.cpp): it perturbs numbers toward 0, +-huge and denormals,
// lifts a polygon's vertex off the plane of the others, duplicates faces (coplanar overlaps, ties) and
// drops or swaps lines: the inputs byte flips rarely reach, which broke the modes' agreement.
#include <cstdint>
#include <random>
#include <string>
#include <string_view>

namespace raycube::fuzz {

// One mutation of `text` chosen by `random`; may return text unchanged (nothing to act on).
std::string mutateNff(std::string_view text, std::mt19937_64& random);

}  // namespace raycube::fuzz
