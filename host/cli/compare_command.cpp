// raycube compare: two images, and the difference between them.
#include <fmt/format.h>

#include <iostream>
#include <string>

#include "core/image.h"
#include "host/chart/chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"

namespace raycube::host {
namespace {

struct CompareCommand {
  std::string first, second;
  std::string diffPath;
  double gain = 1;
};

// `raycube compare A B`: how far apart two renders are; exit 0 only when bit-identical.
int runCompare(const CompareCommand& cmd) {
  const core::Image a = core::readImage(cmd.first), b = core::readImage(cmd.second);
  const core::ImageDifference d = core::compareImages(a, b);
  const bool identical = core::bitIdentical(a, b);
  std::cout << fmt::format("rmse {:.3g}, psnr {:.2f} dB, max {:.3g}, pixels over 1/255: {}, {}\n", d.rmse,
                           d.psnr, d.maxAbs, d.pixelsOver, identical ? "bit-identical" : "different");
  if (!cmd.diffPath.empty()) core::writeImage(core::differenceImage(a, b, cmd.gain), cmd.diffPath);
  return identical ? 0 : 1;
}

void addCompareSubcommand(CLI::App& app, CompareCommand& cmd) {
  CLI::App* compare =
      app.add_subcommand("compare", "Compare two images (EXR or PNG); exit 0 if bit-identical");
  compare->add_option("first", cmd.first, "First image")->required()->check(CLI::ExistingFile);
  compare->add_option("second", cmd.second, "Second image")->required()->check(CLI::ExistingFile);
  compare->add_option("--diff", cmd.diffPath, "Write |first - second| (times --gain) to this EXR or PNG");
  compare->add_option("--gain", cmd.gain, "Scale of the difference image")
      ->check(kNotNaN & CLI::Range(0.0, 1e12));
}

}  // namespace

RunCommand addCompareCommand(CLI::App& app) {
  return commandOf<CompareCommand>(app, addCompareSubcommand, runCompare);
}

}  // namespace raycube::host
