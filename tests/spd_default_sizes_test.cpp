// The SPD at its default sizes (issue 13): thousands of objects per region. The machine's image stays bit
// for bit the image-parallel renderer's (which renderer_test holds bit-identical to the reference; the
// brute-force reference itself takes too long on these scenes for a test) with the paper's cells and with
// the BVH of dense regions, on a uniform grid and a BSP, with light rays traced where they start and as
// messages, in double and in float.
#include <gtest/gtest.h>

#include <string>

#include "core/nff_reader.h"
#include "host/render/sequential_renderers.h"
#include "machine_test_support.h"

namespace raycube::host {
namespace {

using namespace testing_support;

struct Case {
  std::string path;  // in the repository
  node::CellStructure cells;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.path << (c.cells == node::CellStructure::Paper ? ", paper cells" : ", auto");
}

class SpdDefaultSizes : public testing::TestWithParam<Case> {};

TEST_P(SpdDefaultSizes, MachineIsBitIdenticalOnEveryPartition) {
  const core::Scene scene = core::readNff(sourcePath(GetParam().path));
  RenderSettings settings = settingsFor(sanitized() ? 12 : 32);
  RenderSettings inFloat = settings;
  inFloat.precision = core::Precision::Float;
  const RenderResult yardstick = renderImageParallel(scene, settings);
  const RenderResult floatYardstick = renderImageParallel(scene, inFloat);
  struct Partition {
    MachineSettings machine;
    std::string label;
    bool inFloat = false;
  };
  MachineSettings bsp;
  bsp.rows = 3;
  bsp.columns = 5;
  std::vector<Partition> partitions{
      {uniformGrid(4, 4, 8), "uniform 4x4"},
      {uniformGrid(2, 3, 128, node::LightRayMode::Messages), "uniform 2x3, messages"},
      {bsp, "bsp of 15, float", true}};
  for (Partition& p : partitions) {
    p.machine.cells = GetParam().cells;
    const std::string label = GetParam().path + ", " + p.label;
    MachineReport report;
    const RenderResult result =
        renderMachineWatched(scene, p.inFloat ? inFloat : settings, p.machine, report, label);
    expectMachineMatchesReference(p.inFloat ? floatYardstick : yardstick, result, report, label);
    // Auto gives every region a BVH on threads; paper never does.
    std::size_t withBvh = 0;
    for (const ProcessorReport& processor : report.processors) withBvh += processor.node.bvh ? 1 : 0;
    EXPECT_EQ(withBvh, GetParam().cells == node::CellStructure::Auto ? report.processors.size() : 0u)
        << label;
  }
}

std::string caseName(const testing::TestParamInfo<Case>& info) {
  const std::string& path = info.param.path;
  const std::string file = path.substr(path.rfind('/') + 1);
  return file.substr(0, file.find('.')) +
         (info.param.cells == node::CellStructure::Paper ? "_paper" : "_auto");
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const char* path : {"scenes/balls4.nff", "scenes/gears4.nff", "scenes/shells5.nff",
                           "scenes/tree11.nff", "scenes/rings7.nff", "scenes/mount6.nff", "scenes/tetra6.nff",
                           "scenes/lattice12.nff", "scenes/jacks4.nff", "scenes/sombrero3.nff"})
    for (node::CellStructure cells : {node::CellStructure::Paper, node::CellStructure::Auto})
      all.push_back({path, cells});
  return all;
}

INSTANTIATE_TEST_SUITE_P(Scenes, SpdDefaultSizes, testing::ValuesIn(cases()), caseName);

}  // namespace
}  // namespace raycube::host
