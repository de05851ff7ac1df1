// The MPI machine's watchdog (host/engines/stall_watch.h), run under mpiexec by mpi_stall_test.sh: the last
// processor never returns from the step that sends its first contribution (MachineSettings::
// stallAStepForTests), or every processor waits for a termination token lost on the way
// (loseTheTokenForTests, argument "lost-token"). The job must end non-zero within seconds, with a message
// naming the stuck processor, never spin. Rank 0 renders; the other ranks serve.
#include <chrono>
#include <cstdio>
#include <string>

#include "core/nff_reader.h"
#include "host/engines/mpi/mpi_session.h"
#include "host/render/render_machine.h"

int main(int argc, char** argv) {
  const bool lostToken = argc > 1 && std::string(argv[1]) == "lost-token";
  return raycube::host::runUnderMpi(argc, argv, [&] {
    const raycube::core::Scene scene = raycube::core::parseNff(
        "v\nfrom 0 0 -8\nat 0 0 0\nup 0 1 0\nangle 30\nhither 0.001\nresolution 8 8\n"
        "l 3 4 -5\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n",
        "stuck.nff");
    raycube::host::RenderSettings settings;
    settings.width = settings.height = 16;
    settings.progress = false;
    raycube::host::MachineSettings machine;
    machine.rows = machine.columns = 2;
    machine.balance = raycube::host::Balance::Uniform;
    machine.mpi = true;
    machine.stallPeriod = std::chrono::milliseconds(500);
    (lostToken ? machine.loseTheTokenForTests : machine.stallAStepForTests) = true;
    raycube::host::renderMachine(scene, settings, machine);
    std::puts("the render ended: the watchdog was never needed");
    return 0;
  });
}
