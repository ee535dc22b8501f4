#include "scenes/registry.h"

#include <array>
#include <string>

#ifdef SANDPHYS_HAS_BULLET
#include "scenes/block_avalanche.h"
#endif
#include "scenes/box_drop.h"
#include "scenes/bulldozer.h"
#include "scenes/compression.h"
#include "scenes/cylinder_pile.h"
#include "scenes/dunes.h"
#include "scenes/hourglass.h"
#include "scenes/repose_heap.h"
#include "scenes/repose_scupper.h"
#include "scenes/rock_drop.h"
#include "scenes/sand_box_pour.h"
#include "scenes/slope_avalanche.h"

namespace sandphys::scenes {

namespace {

template <typename SceneType>
std::unique_ptr<Scene> make() {
  return std::make_unique<SceneType>();
}

// An explicit table rather than self-registering statics in each scene file: the scenes live in
// a static library, and the linker drops object files that nothing references, together with
// their registration.
constexpr std::array kScenes{
#ifdef SANDPHYS_HAS_BULLET
    SceneEntry{"Avalanches", "avalanche",
               "the slope's sand released onto two wooden blocks that Bullet simulates: it runs "
               "over the low one and topples the plank standing on it",
               &make<BlockAvalanche>},
#endif
    SceneEntry{"Avalanches", "slope-avalanche",
               "a block of sand on a tilted floor runs down the slope when its retaining wall is "
               "removed",
               &make<SlopeAvalanche>},
    SceneEntry{"Basics", "box-drop", "a block of granules dropped into a smooth box",
               &make<BoxDrop>},
    SceneEntry{"Basics", "sand-box-pour",
               "an emitter pours granules at a set rate into a smooth box, where they heap up",
               &make<SandBoxPour>},
    SceneEntry{"Benchmark", "cylinder-pile",
               "batches of granules poured into a cylinder on a rough floor (Longmore et al. "
               "2013, section 5)",
               &make<CylinderPile>},
    SceneEntry{"Bodies", "bulldozer",
               "a kinematic blade pushes a berm of sand along the floor; its drag is recorded",
               &make<Bulldozer>},
    SceneEntry{"Bodies", "rock-drop",
               "a rock (a mesh file, assets/rock.obj unless --mesh names another) dropped into a "
               "settled bed of sand, where it digs in and comes to rest",
               &make<RockDrop>},
    SceneEntry{"Validation", "hourglass",
               "granules drain from a 45 degree funnel through its outlet at a constant mean rate "
               "(Longmore et al. 2013, Fig. 16); --metrics records the granules remaining",
               &make<Hourglass>},
    SceneEntry{"Validation", "repose-heap",
               "a narrow emitter pours granules onto a rough floor; the heap's flank stands at the "
               "angle of repose (Longmore et al. 2013, Fig. 22), which --metrics reports",
               &make<ReposeHeap>},
    SceneEntry{"Validation", "repose-scupper",
               "sand runs from a reservoir through a slot into the sump below, where its pile "
               "stands at the angle of repose (Longmore et al. 2013, Fig. 15), which --metrics "
               "reports",
               &make<ReposeScupper>},
    SceneEntry{"Validation", "dunes",
               "sand dropped in two columns onto a rough floor forms a dune with two crests and a "
               "saddle between them (Longmore et al. 2013, Fig. 25)",
               &make<Dunes>},
    SceneEntry{
        "Validation", "compression",
        "a plunger compresses a settled pile in a cylinder and lets it go: the stress-strain "
        "loop and the strain recovered (Longmore et al. 2013, Fig. 21)",
        &make<Compression>},
};

}  // namespace

std::span<const SceneEntry> sceneRegistry() {
  return kScenes;
}

const SceneEntry* findScene(std::string_view name) {
  for (const SceneEntry& entry : kScenes) {
    if (entry.name == name) return &entry;
  }
  return nullptr;
}

std::unique_ptr<Scene> createScene(std::string_view name) {
  if (const SceneEntry* entry = findScene(name)) return entry->create();
  std::string known;
  for (const SceneEntry& entry : kScenes) {
    known += known.empty() ? "" : ", ";
    known += entry.name;
  }
  throw InvalidArgument("unknown scene '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace sandphys::scenes
