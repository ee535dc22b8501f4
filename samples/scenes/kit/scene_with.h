#pragma once

#include <span>
#include <vector>

#include "scenes/kit/parameters.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// The base of a scene with a Config: it owns the config, hands out its parameters from the
/// scene's table (Param rows, one per field that a user may set) and gives d, the particle
/// diameter every scene measures its lengths in (Config::particleDiameter, m).
template <class Config>
class SceneWith : public Scene {
 public:
  SceneWith() = default;
  explicit SceneWith(const Config& config) : m_config(config) {}

  /// The parameters (change them before build()).
  Config& config() { return m_config; }
  const Config& config() const { return m_config; }

  /// The table's rows; a scene built on another adds its own after them.
  std::vector<SceneParameter> parameters() override { return bind(table(), m_config); }

 protected:
  /// The scene's parameter table (a static array in its .cpp).
  virtual std::span<const Param<Config>> table() const = 0;
  float d() const { return m_config.particleDiameter; }

  Config m_config;
};

}  // namespace sandphys::scenes::kit
