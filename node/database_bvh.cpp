#include "node/database_bvh.h"

#include <map>
#include <mutex>

namespace raycube::node {

namespace {

// One database's tree: built by the first processor that asks, while the others holding that database wait
// on this slot alone. Processors holding other databases build theirs at the same time.
template <class Real>
struct TreeSlot {
  std::mutex building;
  std::weak_ptr<const DatabaseBvh<Real>> tree;
};

}  // namespace

template <class Real>
std::shared_ptr<const DatabaseBvh<Real>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>& database,
                                                     const core::ShadingOptions& options,
                                                     const core::BvhShape* sceneShape) {
  // A tree keeps its database alive, so a database's address names one database while its tree lives.
  static std::mutex mutex;
  static std::map<const RegionDatabase*, std::shared_ptr<TreeSlot<Real>>> slots;
  std::shared_ptr<TreeSlot<Real>> slot;
  {
    const std::lock_guard lock(mutex);
    // A slot nobody holds and whose tree is gone serves no one. Its tree is read under its own lock (a slot
    // being built is kept); copies of a slot are only made under this lock, so a count read here is never
    // too low, at worst stale and too high, which keeps a slot one call longer.
    std::erase_if(slots, [](const auto& entry) {
      TreeSlot<Real>& slot = *entry.second;
      if (!slot.building.try_lock()) return false;
      const bool gone = slot.tree.expired();
      slot.building.unlock();
      return gone && entry.second.use_count() == 1;
    });
    std::shared_ptr<TreeSlot<Real>>& entry = slots[database.get()];
    if (!entry) entry = std::make_shared<TreeSlot<Real>>();
    slot = entry;
  }
  const std::lock_guard building(slot->building);
  std::shared_ptr<const DatabaseBvh<Real>> tree = slot->tree.lock();
  if (!tree) {
    tree = std::make_shared<const DatabaseBvh<Real>>(database, options, sceneShape);
    slot->tree = tree;
  }
  return tree;
}

template std::shared_ptr<const DatabaseBvh<float>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>&,
                                                               const core::ShadingOptions&, const core::BvhShape*);
template std::shared_ptr<const DatabaseBvh<double>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>&,
                                                                const core::ShadingOptions&, const core::BvhShape*);

template <class Real>
LightRayTree<Real>::LightRayTree(const std::shared_ptr<const RegionDatabase>& database,
                                 const core::ShadingOptions& options, const core::BvhShape* sceneShape,
                                 std::shared_ptr<const SceneTree> sceneTree) {
  if (std::is_same_v<Real, double> && sceneTree != nullptr &&
      database->inPlace == &sceneTree->shading.scene()) {
    sceneTree_ = std::move(sceneTree);
    held_.assign(database->inPlace->objects.size(), false);
    for (std::uint32_t o : database->globalIds) held_[o] = true;
    return;
  }
  own_ = sharedBvhOf<Real>(database, options, sceneShape);
}

template class LightRayTree<float>;
template class LightRayTree<double>;

}  // namespace raycube::node
