#pragma once
// One BVH over everything a processor holds (its RegionDatabase), shared by every processor of this address
// space holding the very same database: when the ground polygon's light volumes reach the whole scene, 64
// processors hold the same objects, and build and keep one tree instead of 64. The database travels as a
// value between address spaces (an MPI rank builds its own tree); only the tree is shared here. Processors
// reading the host's scene in place use the host's tree instead, for their light rays (LightRayTree).
#include <memory>
#include <type_traits>
#include <vector>

#include "core/bvh.h"
#include "core/whitted.h"
#include "node/region_database.h"

namespace raycube::node {

// The database's objects scattered over the whole scene's tree (its light volumes' objects), a branch holding
// this few of them is one leaf: a node per object made 64 processors' trees large; 2 saves memory for the
// same tests, more saves a little more memory for many more object tests.
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

// The host's BVH over the whole scene (the sub-sampling's, 3.7.1) and the shading it answers with, kept for
// the processors that read that scene in place.
struct SceneTree {
  SceneTree(const core::Scene& scene, const core::ShadingOptions& options)
      : shading(scene, options), bvh(scene, shading, core::Bvh::BuildOn::EveryCore) {}
  SceneTree(const SceneTree&) = delete;  // bvh refers to shading
  SceneTree& operator=(const SceneTree&) = delete;

  core::Whitted shading;
  core::Bvh bvh;
};

// What answers a processor's light rays traced where they start (3.7.2): a tree over what it holds. Where it
// reads the host's scene in place (double rays), the host's tree, passing over the objects it does not hold
// untested: the light rays meet what a tree over the database would give them, and 64 processors restrict no
// trees (restricting them was most of the set-up of processors holding much). Otherwise the database's own
// tree, shared (sharedBvhOf).
template <class Real>
class LightRayTree {
 public:
  // sceneTree: the host's, or none; sceneShape: its shape for the database's own tree
  // (NodeSetup::sceneShape).
  LightRayTree(const std::shared_ptr<const RegionDatabase>& database, const core::ShadingOptions& options,
               const core::BvhShape* sceneShape, std::shared_ptr<const SceneTree> sceneTree);

  double transmission(const core::BasicRay<Real>& ray, core::TraceCounters& counters,
                      std::vector<core::Hit>& crossed) const {
    if constexpr (std::is_same_v<Real, double>) {
      if (sceneTree_)
        return sceneTree_->bvh.transmission(ray, counters, crossed,
                                            [this](std::uint32_t o) { return held_[o]; });
    }
    return own_->bvh.transmission(ray, counters, crossed);
  }

 private:
  std::shared_ptr<const SceneTree> sceneTree_;  // or
  std::shared_ptr<const DatabaseBvh<Real>> own_;
  std::vector<bool> held_;  // per object of the host's scene, with sceneTree_
};

}  // namespace raycube::node
