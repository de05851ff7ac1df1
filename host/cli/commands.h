#pragma once
// raycube's subcommands, one file each (host/cli/<name>_command.cpp, over the options they share in
// options.h): each adds itself to the program's command line and returns what runs it once the line is
// parsed.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>

namespace raycube::host {

using RunCommand = std::function<int()>;

// A subcommand whose options `add` declares into a Command of its own, run by `run` once the line is parsed.
template <class Command, class Add, class Run>
RunCommand commandOf(CLI::App& app, Add add, Run run) {
  auto cmd = std::make_shared<Command>();
  add(app, *cmd);
  return [cmd, run] { return run(*cmd); };
}

RunCommand addRenderCommand(CLI::App& app);
RunCommand addCompareCommand(CLI::App& app);
RunCommand addTradeoffCommand(CLI::App& app);
RunCommand addScalingCommand(CLI::App& app);
RunCommand addPlotCommand(CLI::App& app);
RunCommand addSpdCommand(CLI::App& app);
RunCommand addCalibrateCommand(CLI::App& app);

}  // namespace raycube::host
