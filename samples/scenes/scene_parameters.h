#pragma once

#include <span>
#include <string>
#include <string_view>

#include "scenes/scene.h"

namespace sandphys::scenes {

// A scene's parameters as text: the command line, recordings, goldens and the viewer's panel set
// and show them through these.

/// Sets the parameter named `name` of `scene` from text ("12", "0.5", "8,8,4" or "8 8 4").
/// Throws InvalidArgument naming the parameter, the value and the valid range when the name is
/// unknown, the text does not parse or the value is out of range.
void setSceneParameter(Scene& scene, std::string_view name, std::string_view text);

/// Shrinks `scene` to the size the tests and the goldens run it at, seconds on llvmpipe: every
/// block of granules ("batch", "block", "berm", "bed") 4 × 2 × 4, "granules" 32 and "layers" 2.
/// The scene's geometry stays as it is.
void useTestSize(Scene& scene);

/// The current value of a parameter as text, in the form setSceneParameter accepts.
std::string formatSceneParameter(const SceneParameter& parameter);

/// Throws InvalidArgument naming `scene`, the parameter, its value and the valid range when a
/// value is outside its range (a Count3 component included) or a text is empty.
void checkRanges(std::string_view scene, std::span<const SceneParameter> parameters);

}  // namespace sandphys::scenes
