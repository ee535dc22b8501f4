#pragma once

#include <span>
#include <vector>

#include "scenes/kit/geometry.h"
#include "scenes/kit/parameters.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// The base of a scene with a Config: it owns the config, hands out its parameters from the
/// scene's table (Param rows, one per field that a user may set) and gives d, the particle
/// diameter every scene measures its lengths in (Config::particleDiameter, m). A Config's lengths
/// are in d unless its comments say otherwise; the scene's table describes each field.
template <class C>
class SceneWith : public Scene {
 public:
  using Config = C;
  SceneWith() = default;
  explicit SceneWith(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  /// Inside bounds(), unless the scene says otherwise.
  bool contains(const Vec3& centre) const override { return inBounds(bounds(), centre); }

  /// The table's rows and the standard ones (withStandardRows); a scene built on another adds its
  /// own after them.
  std::vector<SceneParameter> parameters() override {
    const std::vector<Param<Config>> rows = withStandardRows(table());
    return bind(std::span<const Param<Config>>(rows), m_config);
  }

 protected:
  /// The scene's own parameter table (a static array in its .cpp), without the standard rows.
  virtual std::span<const Param<Config>> table() const = 0;
  float d() const { return m_config.particleDiameter; }

  Config m_config;
};

}  // namespace sandphys::scenes::kit
