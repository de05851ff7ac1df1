#include "host/cli.h"

int main(int argc, char** argv) {
  return raycube::host::runCommandLine(argc, argv);
}
