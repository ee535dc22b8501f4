#pragma once

// The World's internals for the library's GL interop and the test suite (a test that reads or
// flips a bit of a GPU buffer); not installed, so a game cannot reach them.

#include "core/world_impl.h"

namespace sandphys::detail {

struct WorldAccess {
  static World::Impl& impl(World& world) { return world.impl(); }
  static const World::Impl& impl(const World& world) { return world.impl(); }
};

}  // namespace sandphys::detail
