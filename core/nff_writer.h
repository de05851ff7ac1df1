#pragma once
// Writer of NFF (shared/spd/NFF.TXT), the inverse of core/nff_reader.h: readNff(written file) gives the same
// scene, number for number. Each number is printed as the shortest text that reads back as the same double
// ("0.737", not "0.73699999999999999"), so a scene whose numbers came from SPD text (the built-in SPD
// generators) is written as compactly as the SPD writes it, and any other scene loses nothing (but an ulp
// of "pp" normals, which the reader normalises again).
#include <ostream>
#include <string>

#include "core/scene.h"

namespace raycube::core {

// Order: an optional "#" comment, "b", the "v" block, the lights, then the objects, each material ("f")
// printed just before the first object that uses it. Materials are printed in index order, so objects whose
// materials never decrease (every scene read from NFF or built by an SPD generator) read back with the same
// indices; an object going back to an earlier material gets that material printed again (same look, new
// index). Materials no object uses come last.
void writeNff(std::ostream& out, const Scene& scene, const std::string& comment = {});

std::string nffText(const Scene& scene, const std::string& comment = {});

}  // namespace raycube::core
