#version 450
// First pass of every substep without sleep, one thread: whether the neighbour lists are built
// before the contacts, and their near part marked (common/list_decision.glsl); and the commands
// of the passes whose lists are filled again cleared (clearRunningCommands).
#include "common/layout.glsl"

layout(local_size_x = 1) in;

COUNTERS(coherent)

#include "common/list_decision.glsl"

void main() {
  // With sleep only World::readContacts runs this pass: it builds every list.
  bool built = decideListBuild(true, 0u, 0u);
  clearRunningCommands(built, nearMarkingDue());
}
