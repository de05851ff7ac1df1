#pragma once
// The read-only world every processor shares (Priol & Bouatouch 3.2): the view, the shading options and
// the screen's partition; the objects each processor holds come in its own NodeSetup (RegionDatabase).
// Values only, so a host can send it to a node in another address space (an MPI rank); processors in one
// address space share one.
#include <cstdint>
#include <vector>

#include "core/box.h"
#include "core/view.h"
#include "core/whitted.h"
#include "node/region_map.h"

namespace raycube::node {

// What a processor's synthesis task does when the FIFO towards a neighbour is full (3.5.2).
enum class FifoFull : std::uint8_t {
  // Keep the ray in an overflow list, in order, and go on consuming incoming rays: a cycle of full FIFOs
  // always drains (2.2's deadlock answered).
  Overflow,
  // The paper's: the synthesis task "remains locked until there is an entry in the FIFO queue"; a cycle of
  // processors each locked on a full FIFO of the next is a deadlock, which the engines report.
  Lock,
};

struct MachineContext {
  core::View view;
  core::ShadingOptions shading;
  RegionMap regions;  // owns its screen lines
  // Where the scene's objects lie: a few world boxes holding them all, padded as the cells pad them (and
  // for float hits); none when rays are to travel on to the screen's edge as in the paper (the emulated
  // machine). A ray leaving its region that cannot meet these boxes again ends there, not after crossing
  // empty regions.
  std::vector<core::Box> sceneBounds;
  // Where each region's objects lie: per processor, a world box holding the objects that touch its region,
  // padded as sceneBounds (empty where it holds none); none where sceneBounds are none. A ray leaving its
  // region that would cross only regions whose boxes it misses, on its way out of sceneBounds, ends there
  // too (node/regions_ahead.h).
  std::vector<core::Box> regionBounds;
  FifoFull fifoFull = FifoFull::Overflow;
  const ScreenLines& lines() const { return regions.lines(); }
};

}  // namespace raycube::node
