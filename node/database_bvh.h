#pragma once
// One BVH over everything a processor holds (its RegionDatabase), shared by every processor of this address
// space holding the very same database: when the ground polygon's light volumes reach the whole scene, 64
// processors hold the same objects, and build and keep one tree instead of 64. The database travels as a
// value between address spaces (an MPI rank builds its own tree); only the tree is shared here.
#include <memory>

#include "core/bvh.h"
#include "core/whitted.h"
#include "node/region_database.h"

namespace raycube::node {

// The database's objects scattered over the whole scene's tree (its light volumes' objects), a branch holding
// this few of them is one leaf: jacks 4 at 8 x 8 held 7.5 MB of such trees over 55,000 copies, a node per
// object; 2 saves 3 MB for the same tests, 4 another 2 MB for 15% more object tests on mount 6 and 45% on
// sombrero 3, and looked slower on balls 4.
inline constexpr std::uint32_t kLargestHeldLeaf = 2;

template <class Real>
struct DatabaseBvh {
  // sceneShape: the whole scene's BVH to keep the shape of (see NodeSetup::sceneShape), or none: built anew.
  DatabaseBvh(std::shared_ptr<const RegionDatabase> held, const core::ShadingOptions& options,
              const core::BvhShape* sceneShape)
      : database(std::move(held)),
        shading(database->traced(), options, database->features()),
        bvh(core::bvhOver<Real>(database->traced(), shading, database->heldIndices(), sceneShape,
                                database->wholeIdOf(), kLargestHeldLeaf)) {}
  DatabaseBvh(const DatabaseBvh&) = delete;  // bvh refers to database and shading
  DatabaseBvh& operator=(const DatabaseBvh&) = delete;

  std::shared_ptr<const RegionDatabase> database;
  core::Whitted shading;
  core::BasicBvh<Real> bvh;
};

// The tree over `database`: made on the first call, then the same tree for as long as some processor holds
// it. Every caller for one database must pass the same shading options (those of its machine's run).
template <class Real>
std::shared_ptr<const DatabaseBvh<Real>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>& database,
                                                     const core::ShadingOptions& options,
                                                     const core::BvhShape* sceneShape = nullptr);

}  // namespace raycube::node
