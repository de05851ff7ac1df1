#pragma once
// Placing the machine's regions on the iPSC's d-dimensional hypercube. A ray leaving a region goes to a
// neighbouring region, and a message between cube nodes a and b crosses popcount(a ^ b) links, so adjacent
// regions should sit on nodes few hops apart. Priol & Bouatouch 3: the 64-node iPSC runs a 2D array, each
// processor linked to its four neighbours (the Gray code below); 3.7.1: a BSP's regions form an arbitrary
// adjacency graph, and "it is important to suitably map this graph on the hypercube topology in order to
// minimize the messages routing" (mapToHypercube).
#include <cstdint>
#include <utility>
#include <vector>

namespace raycube::host {

// Undirected graph of which regions share a border; edges may be listed in either direction, duplicates
// and self-loops are tolerated (a self-loop costs no hops).
struct AdjacencyGraph {
  int vertices = 0;
  std::vector<std::pair<int, int>> edges;
};

// Hops per adjacency edge under a mapping. dimension is the cube the mapping needs: the bits of the
// largest node number used.
struct Dilation {
  double mean = 0;
  int max = 0;
  int dimension = 0;
};

// Hops between cube nodes a and b: the number of address bits in which they differ.
int hypercubeHops(std::uint32_t a, std::uint32_t b);

// Smallest d with 2^d >= processors (0 for one processor). Throws std::invalid_argument when processors < 1.
int hypercubeDimension(int processors);

// Gray-code embedding of a rows x columns grid: region r * columns + c goes to node
// (gray(r) << ceil(log2 columns)) | gray(c), gray(x) = x ^ (x >> 1). Every grid edge has dilation 1 when
// both sides are powers of two; otherwise the mapping stays injective but may need a cube of
// ceil(log2 rows) + ceil(log2 columns) dimensions, one more than hypercubeDimension(rows * columns)
// (3 x 5 needs 5, not 4). Throws std::invalid_argument for non-positive sizes or more than 31 address bits.
std::vector<std::uint32_t> grayCodeGridMapping(int rows, int columns);

// The placement keeps a vertices x nodes table of ints: 4 MB at this size, far past any machine we emulate.
inline constexpr int kMaxMappedVertices = 1024;

// Heuristic embedding of any adjacency graph (e.g. a BSP's, whose regions are not a grid) into the smallest
// cube, d = hypercubeDimension(vertices): injective, every node < 2^d, deterministic. Greedy placement
// followed by swap/move improvement; meant for the machine's sizes (up to a few hundred regions).
// Throws std::invalid_argument when an edge names a vertex outside [0, vertices), vertices < 0, or
// vertices > 1024. steps, if given: the nodes' hops weighed for a vertex on the way (the host's work).
std::vector<std::uint32_t> mapToHypercube(const AdjacencyGraph& graph, std::uint64_t* steps = nullptr);

// Mean and max hops over the graph's edges (both 0 without edges). Throws std::invalid_argument when the
// mapping does not have one node per vertex or an edge names a vertex outside the graph.
Dilation dilationOf(const AdjacencyGraph& graph, const std::vector<std::uint32_t>& mapping);

// The 4-neighbour grid of rows x columns regions, vertex r * columns + c, as the machine's grid partition
// (3.1) connects them. Throws std::invalid_argument for non-positive sizes.
AdjacencyGraph gridAdjacency(int rows, int columns);

}  // namespace raycube::host
