#include "node/database_bvh.h"

#include <map>
#include <mutex>

namespace raycube::node {

template <class Real>
std::shared_ptr<const DatabaseBvh<Real>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>& database,
                                                     const core::ShadingOptions& options) {
  // A tree keeps its database alive, so a database's address names one database while its tree lives.
  static std::mutex mutex;
  static std::map<const RegionDatabase*, std::weak_ptr<const DatabaseBvh<Real>>> trees;
  const std::lock_guard lock(mutex);  // processors built at once wait for the one building their tree
  std::erase_if(trees, [](const auto& entry) { return entry.second.expired(); });
  std::weak_ptr<const DatabaseBvh<Real>>& entry = trees[database.get()];
  std::shared_ptr<const DatabaseBvh<Real>> tree = entry.lock();
  if (!tree) {
    tree = std::make_shared<const DatabaseBvh<Real>>(database, options);
    entry = tree;
  }
  return tree;
}

template std::shared_ptr<const DatabaseBvh<float>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>&,
                                                               const core::ShadingOptions&);
template std::shared_ptr<const DatabaseBvh<double>> sharedBvhOf(const std::shared_ptr<const RegionDatabase>&,
                                                                const core::ShadingOptions&);

}  // namespace raycube::node
