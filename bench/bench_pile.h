#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::bench {

/// The benchmark scenes of sandphys-bench (--scene).
enum class BenchScene {
  /// The settled cylinder pile of Longmore et al. 2013, section 5 (DensePile).
  Cylinder,
  /// The standard box pile: a settled pile about 15 d high in a square box of flat walls with
  /// friction (BoxPile).
  Box,
};

/// "cylinder" or "box" (the --scene values).
inline std::string_view benchSceneName(BenchScene scene) {
  return scene == BenchScene::Box ? "box" : "cylinder";
}

/// Where the granules of a pile go; computed before any World exists.
struct PileLayout {
  /// Lattice spacing used, m (crystal: between columns; the layers are a little closer).
  float spacing = 0.0f;
  /// Lattice columns in the container (one granule per column and layer).
  std::uint32_t columns = 0;
  /// Complete layers, and granules in the partial top layer (0 when the top layer is complete).
  std::uint32_t fullLayers = 0;
  std::uint32_t topLayerGranules = 0;
  /// Centre height of each layer, m (crystal layers are pressed together by their load).
  std::vector<float> layerY;
  /// Height of the highest particle surface of the initial column, m.
  float columnTop = 0.0f;
  /// Height of the container's wall (cylinder) or of the closed box, d.
  float wallHeight = 0.0f;
  /// Cylinder: the wall is higher than configured because the column does not fit under it.
  bool wallRaised = false;
  /// Box: inner side of the square footprint, d; 0 for the cylinder.
  float boxSide = 0.0f;
};

/// What sandphys-bench needs of a benchmark pile, whichever its container: the settings of a
/// World that holds exactly it, how to fill that World, and how to tell how settled it is.
class BenchPile {
 public:
  virtual ~BenchPile() = default;

  /// Settings (material, diameter, time step, speed guard) with capacities for every granule and
  /// floor particle the pile has.
  virtual WorldSettings settings() const = 0;
  /// Adds the container and the granules to an empty `world` made from settings().
  virtual void build(World& world) const = 0;
  virtual const PileLayout& layout() const = 0;

  /// Granules in the pile.
  virtual std::uint32_t granules() const = 0;
  /// Particle diameter d, m.
  virtual float particleDiameter() const = 0;
  /// Mass of one granule, kg.
  virtual float granuleMass() const = 0;
  /// Height of the top surface of the granules in `bodies` that are alive and inside the
  /// container, m: the 99th percentile of their centre heights plus the granule's outer radius.
  virtual float pileTop(std::span<const BodyState> bodies) const = 0;
  /// Whether a granule centre (m) is inside the container.
  virtual bool contains(const Vec3& centre) const = 0;
  /// The container up to the initial column's top, m (to frame the renderer's camera).
  virtual scenes::SceneBounds bounds() const = 0;
};

}  // namespace sandphys::bench
