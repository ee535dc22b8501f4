#pragma once

// Every registered scene as the parameter of a value-parameterised test, one test per scene with
// the scene's name in the test's:
//   INSTANTIATE_TEST_SUITE_P(EveryScene, Suite, ::testing::ValuesIn(testing::registeredScenes()),
//                            testing::sceneTestName);
// gives EveryScene/Suite.Test/rock_drop. Header only: it needs the samples' scenes
// (sandphys_scenes), which sandphys_testing does not link.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "scenes/registry.h"

namespace sandphys::scenes {

/// How GoogleTest prints a scene parameter: its name, quoted ("rock-drop"), in failure messages
/// and in the test list, whose comment CTest's test names carry. Without it, an address.
inline void PrintTo(const SceneEntry* entry, std::ostream* out) {
  *out << '"' << entry->name << '"';
}

}  // namespace sandphys::scenes

namespace sandphys::testing {

/// Every entry of scenes::sceneRegistry(), in its order; the entries live as long as the program.
inline std::vector<const scenes::SceneEntry*> registeredScenes() {
  std::vector<const scenes::SceneEntry*> entries;
  for (const scenes::SceneEntry& entry : scenes::sceneRegistry()) entries.push_back(&entry);
  return entries;
}

/// A scene's name as a test name ("rock-drop" -> "rock_drop": GoogleTest takes only letters,
/// digits and underscores).
inline std::string sceneTestName(const ::testing::TestParamInfo<const scenes::SceneEntry*>& info) {
  std::string name(info.param->name);
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace sandphys::testing
