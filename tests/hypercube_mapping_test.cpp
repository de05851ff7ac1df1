#include "host/prepare/hypercube_mapping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

namespace raycube::host {
namespace {

// Every vertex on its own node, and every node inside a cube of `dimension` dimensions.
void expectInjectiveWithin(const std::vector<std::uint32_t>& mapping, int dimension) {
  const std::set<std::uint32_t> distinct(mapping.begin(), mapping.end());
  EXPECT_EQ(distinct.size(), mapping.size()) << "two vertices share a node";
  for (std::uint32_t node : mapping) EXPECT_LT(node, std::uint32_t{1} << dimension);
}

// A BSP-like partition: split a random rectangle of the unit square at a random place along a random axis
// until there are `count`; rectangles sharing a border of positive length are adjacent. Split coordinates
// are copied, not recomputed, so touching borders compare equal exactly.
AdjacencyGraph randomRectangleSubdivision(int count, unsigned seed) {
  struct Rect {
    double x0, y0, x1, y1;
  };
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> fraction(0.25, 0.75);
  std::vector<Rect> rects{{0, 0, 1, 1}};
  while (static_cast<int>(rects.size()) < count) {
    const std::size_t i = std::uniform_int_distribution<std::size_t>(0, rects.size() - 1)(random);
    Rect& r = rects[i];
    const bool vertical = (random() & 1u) != 0;
    Rect other = r;
    if (vertical) {
      const double x = r.x0 + fraction(random) * (r.x1 - r.x0);
      r.x1 = x;
      other.x0 = x;
    } else {
      const double y = r.y0 + fraction(random) * (r.y1 - r.y0);
      r.y1 = y;
      other.y0 = y;
    }
    rects.push_back(other);
  }
  AdjacencyGraph graph;
  graph.vertices = count;
  const auto overlap = [](double a0, double a1, double b0, double b1) {
    return std::min(a1, b1) > std::max(a0, b0);
  };
  for (int a = 0; a < count; ++a) {
    for (int b = a + 1; b < count; ++b) {
      const Rect& p = rects[a];
      const Rect& q = rects[b];
      const bool sideBySide = (p.x1 == q.x0 || q.x1 == p.x0) && overlap(p.y0, p.y1, q.y0, q.y1);
      const bool stacked = (p.y1 == q.y0 || q.y1 == p.y0) && overlap(p.x0, p.x1, q.x0, q.x1);
      if (sideBySide || stacked) graph.edges.emplace_back(a, b);
    }
  }
  return graph;
}

std::vector<std::uint32_t> identityMapping(int vertices) {
  std::vector<std::uint32_t> mapping(static_cast<std::size_t>(vertices));
  for (int v = 0; v < vertices; ++v) mapping[v] = static_cast<std::uint32_t>(v);
  return mapping;
}

TEST(HypercubeDimension, SmallestCubeHoldingAllProcessors) {
  EXPECT_EQ(hypercubeDimension(1), 0);
  EXPECT_EQ(hypercubeDimension(2), 1);
  EXPECT_EQ(hypercubeDimension(3), 2);
  EXPECT_EQ(hypercubeDimension(4), 2);
  EXPECT_EQ(hypercubeDimension(5), 3);
  EXPECT_EQ(hypercubeDimension(64), 6);
  EXPECT_EQ(hypercubeDimension(65), 7);
  EXPECT_THROW(hypercubeDimension(0), std::invalid_argument);
}

TEST(GridAdjacency, FourNeighbourEdges) {
  const AdjacencyGraph graph = gridAdjacency(3, 4);
  EXPECT_EQ(graph.vertices, 12);
  EXPECT_EQ(graph.edges.size(), 3u * 3u + 2u * 4u);  // horizontal + vertical
  const std::set<std::pair<int, int>> edges(graph.edges.begin(), graph.edges.end());
  EXPECT_TRUE(edges.count({0, 1}));
  EXPECT_TRUE(edges.count({0, 4}));
  EXPECT_FALSE(edges.count({3, 4})) << "row ends do not wrap";
  EXPECT_THROW(gridAdjacency(0, 4), std::invalid_argument);
}

class GrayCodePowerOfTwo : public testing::TestWithParam<std::pair<int, int>> {};

TEST_P(GrayCodePowerOfTwo, EveryGridEdgeIsOneHop) {
  const auto [rows, columns] = GetParam();
  const auto mapping = grayCodeGridMapping(rows, columns);
  ASSERT_EQ(mapping.size(), static_cast<std::size_t>(rows * columns));
  const int dimension = hypercubeDimension(rows * columns);
  expectInjectiveWithin(mapping, dimension);
  const AdjacencyGraph graph = gridAdjacency(rows, columns);
  for (const auto& [a, b] : graph.edges) {
    EXPECT_EQ(hypercubeHops(mapping[a], mapping[b]), 1) << "edge " << a << "-" << b;
  }
  const Dilation dilation = dilationOf(graph, mapping);
  EXPECT_EQ(dilation.mean, 1.0);
  EXPECT_EQ(dilation.max, 1);
  EXPECT_EQ(dilation.dimension, dimension);
}

INSTANTIATE_TEST_SUITE_P(Grids, GrayCodePowerOfTwo,
                         testing::Values(std::pair{4, 4}, std::pair{8, 8}, std::pair{2, 8},
                                         std::pair{1, 16}));

TEST(GrayCode, NonPowerOfTwoGridIsInjectiveInAWiderCube) {
  const auto mapping = grayCodeGridMapping(3, 5);
  ASSERT_EQ(mapping.size(), 15u);
  // ceil(log2 3) + ceil(log2 5) = 2 + 3 bits: one more than the 4 that 15 processors need.
  expectInjectiveWithin(mapping, 5);
  const Dilation dilation = dilationOf(gridAdjacency(3, 5), mapping);
  EXPECT_EQ(dilation.dimension, 5);
  std::cout << "gray 3x5: mean " << dilation.mean << " max " << dilation.max << " dimension "
            << dilation.dimension << "\n";
}

TEST(GrayCode, RejectsEmptyGrid) {
  EXPECT_THROW(grayCodeGridMapping(0, 3), std::invalid_argument);
}

TEST(DilationOf, HandMadeCases) {
  AdjacencyGraph triangle{3, {{0, 1}, {1, 2}, {2, 0}}};
  // Nodes 0, 3, 5: hops 0-3 = 2, 3-5 = popcount(6) = 2, 5-0 = 2.
  Dilation d = dilationOf(triangle, {0, 3, 5});
  EXPECT_DOUBLE_EQ(d.mean, 2.0);
  EXPECT_EQ(d.max, 2);
  EXPECT_EQ(d.dimension, 3);

  // Nodes 0, 1, 7: hops 1, 2, 3.
  d = dilationOf(triangle, {0, 1, 7});
  EXPECT_DOUBLE_EQ(d.mean, 2.0);
  EXPECT_EQ(d.max, 3);
  EXPECT_EQ(d.dimension, 3);

  AdjacencyGraph pair{2, {{0, 1}}};
  d = dilationOf(pair, {2, 3});
  EXPECT_DOUBLE_EQ(d.mean, 1.0);
  EXPECT_EQ(d.max, 1);
  EXPECT_EQ(d.dimension, 2);

  d = dilationOf(AdjacencyGraph{4, {}}, {0, 1, 2, 3});
  EXPECT_EQ(d.mean, 0.0);
  EXPECT_EQ(d.max, 0);

  EXPECT_THROW(dilationOf(pair, {0}), std::invalid_argument);
  EXPECT_THROW(dilationOf(AdjacencyGraph{2, {{0, 2}}}, {0, 1}), std::invalid_argument);
}

TEST(MapToHypercube, TrivialGraphs) {
  EXPECT_TRUE(mapToHypercube(AdjacencyGraph{}).empty());
  EXPECT_EQ(mapToHypercube(AdjacencyGraph{1, {}}), std::vector<std::uint32_t>{0});
  const auto isolated = mapToHypercube(AdjacencyGraph{5, {}});
  expectInjectiveWithin(isolated, 3);
  EXPECT_THROW(mapToHypercube(AdjacencyGraph{2, {{0, 5}}}), std::invalid_argument);
  EXPECT_THROW(mapToHypercube(AdjacencyGraph{-1, {}}), std::invalid_argument);
  EXPECT_THROW(mapToHypercube(AdjacencyGraph{5000, {}}), std::invalid_argument);
}

class MapGrid : public testing::TestWithParam<int> {};

TEST_P(MapGrid, CloseToTheGrayCode) {
  const int side = GetParam();
  const AdjacencyGraph graph = gridAdjacency(side, side);
  const auto mapping = mapToHypercube(graph);
  ASSERT_EQ(mapping.size(), static_cast<std::size_t>(side * side));
  expectInjectiveWithin(mapping, hypercubeDimension(side * side));
  const Dilation dilation = dilationOf(graph, mapping);
  std::cout << "heuristic grid " << side << "x" << side << ": mean " << dilation.mean << " max "
            << dilation.max << " dimension " << dilation.dimension << "\n";
  EXPECT_LE(dilation.mean, 1.3);
  EXPECT_EQ(mapping, mapToHypercube(graph)) << "not deterministic";
}

INSTANTIATE_TEST_SUITE_P(Sides, MapGrid, testing::Values(4, 8));

TEST(MapToHypercube, PathEmbedsWithDilationOne) {
  AdjacencyGraph path{16, {}};
  for (int v = 0; v + 1 < 16; ++v) path.edges.emplace_back(v, v + 1);
  const auto mapping = mapToHypercube(path);
  expectInjectiveWithin(mapping, 4);
  const Dilation dilation = dilationOf(path, mapping);
  std::cout << "heuristic path 16: mean " << dilation.mean << " max " << dilation.max << "\n";
  EXPECT_EQ(dilation.mean, 1.0);
  EXPECT_EQ(dilation.max, 1);
}

class MapSubdivision : public testing::TestWithParam<int> {};

TEST_P(MapSubdivision, InjectiveInSmallestCubeAndBetterThanIdentity) {
  const int processors = GetParam();
  const int dimension = hypercubeDimension(processors);
  constexpr int kSeeds = 8;
  double heuristicSum = 0;
  double identitySum = 0;
  int worstMax = 0;
  for (unsigned seed = 1; seed <= kSeeds; ++seed) {
    const AdjacencyGraph graph = randomRectangleSubdivision(processors, seed);
    const auto mapping = mapToHypercube(graph);
    ASSERT_EQ(mapping.size(), static_cast<std::size_t>(processors));
    expectInjectiveWithin(mapping, dimension);
    const Dilation heuristic = dilationOf(graph, mapping);
    EXPECT_LE(heuristic.dimension, dimension);
    heuristicSum += heuristic.mean;
    identitySum += dilationOf(graph, identityMapping(processors)).mean;
    worstMax = std::max(worstMax, heuristic.max);
  }
  std::cout << "subdivision P=" << processors << ": heuristic mean " << heuristicSum / kSeeds
            << " (worst max " << worstMax << "), identity mean " << identitySum / kSeeds << "\n";
  EXPECT_LT(heuristicSum, identitySum);
}

INSTANTIATE_TEST_SUITE_P(Processors, MapSubdivision, testing::Values(5, 16, 32, 64));

}  // namespace
}  // namespace raycube::host
