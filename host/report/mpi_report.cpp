#include "host/report/mpi_report.h"

#include <fmt/format.h>

namespace raycube::host {
namespace {

double mebibytes(std::uint64_t bytes) {
  return double(bytes) / (1024.0 * 1024.0);
}

}  // namespace

std::string mpiTable(const MachineReport& report) {
  const MpiRun& run = *report.mpi;
  std::string text = fmt::format("  MPI: {} ranks (rank 0 the host), rays batched {} per message at most\n",
                                 run.ranks.size(), run.rayBatch);
  text +=
      "  rank  procs  objects   job MB  peak RSS MB   msgs sent    MB sent  msgs recv    MB recv  ray msgs   "
      "   rays\n";
  for (const RankReport& r : run.ranks)
    text += fmt::format(
        "  {:>4} {:>6} {:>8} {:>8.2f} {:>12.1f} {:>11} {:>10.2f} {:>10} {:>10.2f} {:>9} {:>9}\n", r.rank,
        r.processors, r.objects, mebibytes(r.jobBytes), mebibytes(r.peakRssBytes), r.messagesSent,
        mebibytes(r.bytesSent), r.messagesReceived, mebibytes(r.bytesReceived), r.rayMessages, r.raysSent);
  return text;
}

nlohmann::json mpiJson(const MachineReport& report) {
  const MpiRun& run = *report.mpi;
  nlohmann::json ranks = nlohmann::json::array();
  for (const RankReport& r : run.ranks)
    ranks.push_back({{"rank", r.rank},
                     {"processors", r.processors},
                     {"objects", r.objects},
                     {"jobBytes", r.jobBytes},
                     {"peakRssBytes", r.peakRssBytes},
                     {"messagesSent", r.messagesSent},
                     {"bytesSent", r.bytesSent},
                     {"messagesReceived", r.messagesReceived},
                     {"bytesReceived", r.bytesReceived},
                     {"rayMessages", r.rayMessages},
                     {"raysSent", r.raysSent}});
  return {{"rayBatch", run.rayBatch}, {"ranks", ranks}};
}

}  // namespace raycube::host
