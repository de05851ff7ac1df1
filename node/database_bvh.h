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

template <class Real>
struct DatabaseBvh {
  // sceneShape: the whole scene's BVH to keep the shape of (see NodeSetup::sceneShape), or none: built anew.
  DatabaseBvh(std::shared_ptr<const RegionDatabase> held, const core::ShadingOptions& options,
              const core::BvhShape* sceneShape)
      : database(std::move(held)),
        shading(database->scene, options),
        bvh(sceneShape ? core::BasicBvh<Real>(database->scene, shading, core::everyObjectOf(database->scene), *sceneShape,
                                              database->globalIds)
                       : core::BasicBvh<Real>(database->scene, shading)) {}
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
