// raycube spd: the built-in SPD generators' scenes as NFF.
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include "core/nff_writer.h"
#include "core/spd/generators.h"
#include "host/chart/chart.h"
#include "host/cli/commands.h"
#include "host/cli/options.h"

namespace raycube::host {
namespace {

struct SpdCommand {
  std::string scene;  // NAME[:SIZE]; empty: list the generators
  std::string output;
};

// `raycube spd NAME[:SIZE] [-o FILE]`: the generated scene as NFF, the same text the SPD program prints.
int runSpd(const SpdCommand& cmd) {
  if (cmd.scene.empty()) {
    std::cout << "Built-in SPD generators (raycube spd NAME[:SIZE], render --spd NAME[:SIZE]):\n"
              << spdSceneList();
    return 0;
  }
  const SpdChoice choice = parseSpdChoice(cmd.scene);
  const core::Scene scene = core::makeSpdScene(choice.name, choice.size);
  if (cmd.output.empty() || cmd.output == "-") {
    core::writeNff(std::cout, scene);
    return 0;
  }
  std::ofstream file(ensureParent(cmd.output), std::ios::binary);
  core::writeNff(file, scene);
  file.close();
  if (!file) throw std::runtime_error(fmt::format("cannot write '{}'", cmd.output));
  std::cerr << fmt::format("wrote {} ({}: {} objects)\n", cmd.output, scene.name, scene.objects.size());
  return 0;
}

void addSpdSubcommand(CLI::App& app, SpdCommand& cmd) {
  CLI::App* spd = app.add_subcommand(
      "spd", "Write a built-in SPD scene as NFF (the SPD program's own output); without a scene, list them");
  spd->add_option("scene", cmd.scene, "NAME[:SIZE], SIZE defaulting to the SPD's default size")
      ->check(kSpdChoice);
  spd->add_option("-o,--output", cmd.output, "NFF file to write (default: standard output)");
}

}  // namespace

RunCommand addSpdCommand(CLI::App& app) {
  return commandOf<SpdCommand>(app, addSpdSubcommand, runSpd);
}

}  // namespace raycube::host
