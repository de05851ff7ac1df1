#include "host/cli/cli.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "host/cli/commands.h"

namespace raycube::host {

int runCommandLine(int argc, char** argv) {
  CLI::App app{"raycube: Priol & Bouatouch's hypercube ray tracer (INRIA RR-0843, 1988), emulated"};
  app.require_subcommand(1);
  // In the order --help lists them.
  const std::vector<std::pair<const char*, RunCommand>> commands{
      {"render", addRenderCommand(app)},      {"compare", addCompareCommand(app)},
      {"tradeoff", addTradeoffCommand(app)},  {"scaling", addScalingCommand(app)},
      {"plot", addPlotCommand(app)},          {"spd", addSpdCommand(app)},
      {"calibrate", addCalibrateCommand(app)}};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "raycube: " << e.what() << " (see raycube --help)\n";
    return 2;
  }
  try {
    for (const auto& [name, run] : commands)
      if (app.got_subcommand(name)) return run();
  } catch (const CLI::ValidationError& e) {
    std::cerr << "raycube: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "raycube: " << e.what() << '\n';
    return 1;
  }
  return 0;
}

}  // namespace raycube::host
