#include <iostream>

#include "host/cli/cli.h"
#include "host/engines/engine_module.h"
#include "host/util/process_memory.h"

int main(int argc, char** argv) {
  using namespace raycube::host;
  keepFreedMemory();
  putHeapOnHugePages();
  if (!asksForMpi(argc, argv)) return runCommandLine(argc, argv);
  try {
    return engineModule().runUnderMpi(argc, argv, [&] { return runCommandLine(argc, argv); });
  } catch (const std::exception& e) {
    std::cerr << "raycube: " << e.what() << "\n";
    return 2;
  }
}
