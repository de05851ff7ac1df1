#pragma once
// The `raycube` command line: `raycube render ...` (and later subcommands).
namespace raycube::host {

// Runs the program; returns the process exit code. Errors are reported as one line on stderr.
int runCommandLine(int argc, char** argv);

}  // namespace raycube::host
