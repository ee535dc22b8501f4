#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "scenes/scene.h"

namespace sandphys::scenes {

/// One entry of the scene registry: what the samples app lists and the viewer's menu shows.
struct SceneEntry {
  /// Menu group, e.g. "Benchmark".
  std::string_view category;
  /// Unique name used by --scene, e.g. "cylinder-pile".
  std::string_view name;
  /// One line describing the scene.
  std::string_view description;
  /// Makes the scene with its default parameters.
  std::unique_ptr<Scene> (*create)();
};

/// Every registered scene, grouped by category and then sorted by name.
std::span<const SceneEntry> sceneRegistry();

/// The entry named `name`, or nullptr.
const SceneEntry* findScene(std::string_view name);

/// Makes the scene named `name` with default parameters; throws InvalidArgument listing the known
/// names when there is none.
std::unique_ptr<Scene> createScene(std::string_view name);

}  // namespace sandphys::scenes
