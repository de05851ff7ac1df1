#include "host/prepare/hypercube_mapping.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>

namespace raycube::host {
namespace {

// Node numbers are uint32_t; 31 bits keeps 1 << d representable and is far beyond any iPSC (d <= 7).
constexpr int kMaxAddressBits = 31;
// Bounded work: each swap round judges vertices x nodes moves at O(1) each; rounds stop earlier when
// nothing improves, which on the machine's graphs happens after a handful.
constexpr int kMaxImprovementRounds = 32;
// Greedy placement depends heavily on its first vertex (on an 8 x 8 grid the eight best-connected starts
// all end near dilation 1.3, while one of the 64 reaches the Gray code's 1.0), so it starts from as many
// vertices as this budget of vertices x nodes x starts allows: every vertex up to 64 processors, a few at
// 256.
constexpr long kGreedyStartBudget = 64L * 64 * 64;
// Annealing after the best start: a deterministic seed, a geometric cooling from a temperature where a
// one-hop loss is taken a third of the time down to one where it practically never is.
constexpr long kAnnealingMovesPerVertex = 1000;
constexpr double kHotTemperature = 1.0;
constexpr double kColdTemperature = 0.05;
constexpr std::uint32_t kAnnealingSeed = 1988;
constexpr std::uint32_t kUnplaced = std::numeric_limits<std::uint32_t>::max();

void requirePositiveGrid(int rows, int columns, const char* who) {
  if (rows < 1 || columns < 1) {
    throw std::invalid_argument(std::string(who) + ": grid must have at least one row and one column, got " +
                                std::to_string(rows) + " x " + std::to_string(columns));
  }
}

void requireEdgesInside(const AdjacencyGraph& graph, const char* who) {
  if (graph.vertices < 0) {
    throw std::invalid_argument(std::string(who) + ": vertex count must not be negative, got " +
                                std::to_string(graph.vertices));
  }
  for (const auto& [a, b] : graph.edges) {
    if (a < 0 || a >= graph.vertices || b < 0 || b >= graph.vertices) {
      throw std::invalid_argument(std::string(who) + ": edge (" + std::to_string(a) + ", " +
                                  std::to_string(b) + ") names a vertex outside [0, " +
                                  std::to_string(graph.vertices) + ")");
    }
  }
}

// Sorted, duplicate-free neighbour lists without self-loops: the cost of a placement is then a plain sum.
std::vector<std::vector<int>> neighbourLists(const AdjacencyGraph& graph) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(graph.vertices));
  for (const auto& [a, b] : graph.edges) {
    if (a == b) continue;
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

// One embedding in progress: where each vertex sits, who occupies each node, and for every vertex and
// node the hops that vertex would have to its placed neighbours from that node. The table makes a
// candidate move cost O(1) to judge, so greedy and descent scan every node for every vertex cheaply.
class Placement {
 public:
  // steps: where to count the placement's work (HostWork::mappingSteps), shared by its copies.
  Placement(const std::vector<std::vector<int>>& neighbours, int dimension, std::uint64_t* steps)
      : neighbours_(&neighbours),
        steps_(steps),
        nodes_(std::uint32_t{1} << dimension),
        nodeOf_(neighbours.size(), kUnplaced),
        vertexAt_(nodes_, -1),
        hopsFrom_(neighbours.size() * nodes_, 0) {
    for (const auto& list : neighbours) edges_ += static_cast<long>(list.size());
    edges_ /= 2;
  }

  // Breadth-first greedy: the unplaced vertex with most placed neighbours (then highest degree, then lowest
  // index) takes the free node closest in total hops to those neighbours (ties: lowest node number).
  void placeGreedily(int first) {
    const int vertices = static_cast<int>(neighbours_->size());
    std::vector<int> placedNeighbours(neighbours_->size(), 0);
    for (int step = 0; step < vertices; ++step) {
      const int chosen = step == 0 ? first : nextVertex(placedNeighbours);
      std::uint32_t bestNode = kUnplaced;
      int bestHops = std::numeric_limits<int>::max();
      *steps_ += nodes_;
      for (std::uint32_t node = 0; node < nodes_; ++node) {
        if (vertexAt_[node] < 0 && hopsFrom(chosen, node) < bestHops) {
          bestHops = hopsFrom(chosen, node);
          bestNode = node;
        }
      }
      place(chosen, bestNode);
      for (int w : (*neighbours_)[chosen]) ++placedNeighbours[w];
    }
  }

  // Steepest descent per vertex: move it to the node (free, or swapping with that node's occupant) that
  // lowers the total hops most; repeat until a round changes nothing or the round budget is spent.
  void improveBySwaps() {
    const int vertices = static_cast<int>(neighbours_->size());
    for (int round = 0; round < kMaxImprovementRounds; ++round) {
      bool improved = false;
      for (int v = 0; v < vertices; ++v) {
        const std::uint32_t here = nodeOf_[v];
        int bestDelta = 0;
        std::uint32_t bestNode = kUnplaced;
        *steps_ += nodes_;
        for (std::uint32_t there = 0; there < nodes_; ++there) {
          if (there == here) continue;
          const int delta = swapDelta(v, there);
          if (delta < bestDelta) {
            bestDelta = delta;
            bestNode = there;
          }
        }
        if (bestNode != kUnplaced) {
          swap(v, bestNode);
          improved = true;
        }
      }
      if (!improved) break;
    }
  }

  // Simulated annealing over swaps with random nodes, from the current placement; keeps the cheapest
  // placement seen. Escapes local minima of the descent that no single swap can leave. Most of its moves
  // are accepted while hot, so it prices them from the neighbour lists rather than paying to keep the table
  // current, and rebuilds the table at the end. The generator is used through plain modulo so every
  // standard library gives the same result.
  void anneal(std::uint32_t seed, long moves) {
    std::mt19937 random(seed);
    const auto vertices = static_cast<std::uint32_t>(neighbours_->size());
    long hops = totalHops();
    long bestHops = hops;
    std::vector<std::uint32_t> best = nodeOf_;
    for (long move = 0; move < moves && bestHops > edges_; ++move) {
      const double temperature =
          kHotTemperature * std::pow(kColdTemperature / kHotTemperature, static_cast<double>(move) / moves);
      const int v = static_cast<int>(random() % vertices);
      const std::uint32_t here = nodeOf_[v];
      const std::uint32_t there = random() % nodes_;
      if (there == here) continue;
      const int u = vertexAt_[there];
      // The edge u-v, if any, keeps its length under a swap, so both sums leave it out.
      long delta = hopsExcept(v, there, u) - hopsExcept(v, here, u);
      if (u >= 0) delta += hopsExcept(u, here, v) - hopsExcept(u, there, v);
      const double uniform = static_cast<double>(random() >> 8) * 0x1p-24;
      if (delta > 0 && uniform >= std::exp(-static_cast<double>(delta) / temperature)) continue;
      nodeOf_[v] = there;
      vertexAt_[there] = v;
      vertexAt_[here] = u;
      if (u >= 0) nodeOf_[u] = here;
      hops += delta;
      if (hops < bestHops) {
        bestHops = hops;
        best = nodeOf_;
      }
    }
    std::fill(nodeOf_.begin(), nodeOf_.end(), kUnplaced);
    std::fill(vertexAt_.begin(), vertexAt_.end(), -1);
    std::fill(hopsFrom_.begin(), hopsFrom_.end(), 0);
    for (std::size_t v = 0; v < best.size(); ++v) place(static_cast<int>(v), best[v]);
  }

  long totalHops() const {
    *steps_ += std::uint64_t(edges_);
    long total = 0;
    for (std::size_t v = 0; v < neighbours_->size(); ++v) {
      for (int w : (*neighbours_)[v]) {
        if (static_cast<std::size_t>(w) > v) total += hypercubeHops(nodeOf_[v], nodeOf_[w]);
      }
    }
    return total;
  }

  // Every edge costs at least one hop: a placement with this total cannot be beaten.
  long edgeCount() const { return edges_; }

  const std::vector<std::uint32_t>& nodes() const { return nodeOf_; }

 private:
  int nextVertex(const std::vector<int>& placedNeighbours) const {
    int best = -1;
    for (int v = 0; v < static_cast<int>(neighbours_->size()); ++v) {
      if (nodeOf_[v] != kUnplaced) continue;
      if (best < 0 || placedNeighbours[v] > placedNeighbours[best] ||
          (placedNeighbours[v] == placedNeighbours[best] &&
           (*neighbours_)[v].size() > (*neighbours_)[best].size())) {
        best = v;
      }
    }
    return best;
  }

  int& hopsFrom(int v, std::uint32_t node) { return hopsFrom_[static_cast<std::size_t>(v) * nodes_ + node]; }

  bool adjacent(int a, int b) const {
    const auto& list = (*neighbours_)[a];
    return std::binary_search(list.begin(), list.end(), b);
  }

  // Change in total hops if v moved to `there` and its occupant, if any, to v's node. The table counts the
  // edge u-v from both ends at the length it has now; under a swap it keeps that length, so add it back.
  int swapDelta(int v, std::uint32_t there) {
    const std::uint32_t here = nodeOf_[v];
    const int u = vertexAt_[there];
    int delta = hopsFrom(v, there) - hopsFrom(v, here);
    if (u >= 0) {
      delta += hopsFrom(u, here) - hopsFrom(u, there);
      if (adjacent(u, v)) delta += 2 * hypercubeHops(here, there);
    }
    return delta;
  }

  void swap(int v, std::uint32_t there) {
    const std::uint32_t here = nodeOf_[v];
    const int u = vertexAt_[there];
    lift(v);
    if (u >= 0) lift(u);
    place(v, there);
    if (u >= 0) place(u, here);
  }

  // Hops from node to every placed neighbour of v except `skip`, straight from the neighbour list.
  long hopsExcept(int v, std::uint32_t node, int skip) const {
    *steps_ += (*neighbours_)[v].size();
    long hops = 0;
    for (int w : (*neighbours_)[v]) {
      if (w != skip && nodeOf_[w] != kUnplaced) hops += hypercubeHops(node, nodeOf_[w]);
    }
    return hops;
  }

  void place(int v, std::uint32_t node) {
    nodeOf_[v] = node;
    vertexAt_[node] = v;
    addHopsToNeighbours(v, node, +1);
  }

  void lift(int v) {
    addHopsToNeighbours(v, nodeOf_[v], -1);
    vertexAt_[nodeOf_[v]] = -1;
    nodeOf_[v] = kUnplaced;
  }

  void addHopsToNeighbours(int v, std::uint32_t node, int sign) {
    *steps_ += (*neighbours_)[v].size() * nodes_;
    for (int w : (*neighbours_)[v]) {
      int* row = &hopsFrom(w, 0);
      for (std::uint32_t x = 0; x < nodes_; ++x) row[x] += sign * hypercubeHops(x, node);
    }
  }

  const std::vector<std::vector<int>>* neighbours_;  // a pointer so placements can be copied
  std::uint64_t* steps_;
  std::uint32_t nodes_;
  std::vector<std::uint32_t> nodeOf_;
  std::vector<int> vertexAt_;
  std::vector<int> hopsFrom_;  // vertices x nodes
  long edges_ = 0;
};

}  // namespace

int hypercubeHops(std::uint32_t a, std::uint32_t b) {
  return std::popcount(a ^ b);
}

int hypercubeDimension(int processors) {
  if (processors < 1) {
    throw std::invalid_argument("hypercubeDimension: need at least one processor, got " +
                                std::to_string(processors));
  }
  return std::bit_width(static_cast<unsigned>(processors - 1));
}

std::vector<std::uint32_t> grayCodeGridMapping(int rows, int columns) {
  requirePositiveGrid(rows, columns, "grayCodeGridMapping");
  const int columnBits = hypercubeDimension(columns);
  const int rowBits = hypercubeDimension(rows);
  if (rowBits + columnBits > kMaxAddressBits) {
    throw std::invalid_argument("grayCodeGridMapping: a " + std::to_string(rows) + " x " +
                                std::to_string(columns) + " grid needs more than " +
                                std::to_string(kMaxAddressBits) + " address bits");
  }
  const auto gray = [](std::uint32_t x) { return x ^ (x >> 1); };
  std::vector<std::uint32_t> mapping;
  mapping.reserve(static_cast<std::size_t>(rows) * columns);
  for (std::uint32_t r = 0; r < static_cast<std::uint32_t>(rows); ++r) {
    for (std::uint32_t c = 0; c < static_cast<std::uint32_t>(columns); ++c) {
      mapping.push_back((gray(r) << columnBits) | gray(c));
    }
  }
  return mapping;
}

std::vector<std::uint32_t> mapToHypercube(const AdjacencyGraph& graph, std::uint64_t* steps) {
  requireEdgesInside(graph, "mapToHypercube");
  if (graph.vertices > kMaxMappedVertices) {
    throw std::invalid_argument("mapToHypercube: " + std::to_string(graph.vertices) + " vertices; at most " +
                                std::to_string(kMaxMappedVertices) + " are supported");
  }
  if (graph.vertices == 0) return {};
  const int dimension = hypercubeDimension(graph.vertices);
  const auto neighbours = neighbourLists(graph);

  // Starts: the best-connected vertices, as a hub placed first constrains the rest least.
  std::vector<int> order(static_cast<std::size_t>(graph.vertices));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return neighbours[a].size() > neighbours[b].size(); });
  const long nodes = 1L << dimension;
  const int starts = static_cast<int>(
      std::clamp(kGreedyStartBudget / (graph.vertices * nodes), 1L, static_cast<long>(graph.vertices)));

  std::uint64_t counted = 0;
  Placement best(neighbours, dimension, &counted);
  long bestHops = std::numeric_limits<long>::max();
  for (int s = 0; s < starts && bestHops > best.edgeCount(); ++s) {
    Placement placement(neighbours, dimension, &counted);
    placement.placeGreedily(order[s]);
    placement.improveBySwaps();
    const long hops = placement.totalHops();
    if (hops < bestHops) {
      bestHops = hops;
      best = placement;
    }
  }
  if (bestHops == best.edgeCount()) {
    if (steps) *steps = counted;
    return best.nodes();
  }
  Placement annealed = best;
  annealed.anneal(kAnnealingSeed, kAnnealingMovesPerVertex * graph.vertices);
  annealed.improveBySwaps();
  if (annealed.totalHops() < bestHops) best = annealed;
  if (steps) *steps = counted;
  return best.nodes();
}

Dilation dilationOf(const AdjacencyGraph& graph, const std::vector<std::uint32_t>& mapping) {
  requireEdgesInside(graph, "dilationOf");
  if (mapping.size() != static_cast<std::size_t>(graph.vertices)) {
    throw std::invalid_argument("dilationOf: mapping has " + std::to_string(mapping.size()) + " nodes for " +
                                std::to_string(graph.vertices) + " vertices");
  }
  Dilation dilation;
  if (!mapping.empty())
    dilation.dimension = std::bit_width(*std::max_element(mapping.begin(), mapping.end()));
  if (graph.edges.empty()) return dilation;
  long total = 0;
  for (const auto& [a, b] : graph.edges) {
    const int hops = hypercubeHops(mapping[a], mapping[b]);
    total += hops;
    dilation.max = std::max(dilation.max, hops);
  }
  dilation.mean = static_cast<double>(total) / static_cast<double>(graph.edges.size());
  return dilation;
}

AdjacencyGraph gridAdjacency(int rows, int columns) {
  requirePositiveGrid(rows, columns, "gridAdjacency");
  AdjacencyGraph graph;
  graph.vertices = rows * columns;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const int v = r * columns + c;
      if (c + 1 < columns) graph.edges.emplace_back(v, v + 1);
      if (r + 1 < rows) graph.edges.emplace_back(v, v + columns);
    }
  }
  return graph;
}

}  // namespace raycube::host
