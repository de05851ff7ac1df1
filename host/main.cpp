#include "host/cli.h"
#include "host/mpi_session.h"

int main(int argc, char** argv) {
  using namespace raycube::host;
  if (asksForMpi(argc, argv)) return runUnderMpi(argc, argv, [&] { return runCommandLine(argc, argv); });
  return runCommandLine(argc, argv);
}
