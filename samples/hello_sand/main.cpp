// hello_sand: the whole sandphys game loop. Sand is poured into a cylinder and settles.
#include <cstdio>

#include <sandphys/sandphys.h>

int main() {
  sandphys::GpuContext gpu = sandphys::GpuContext::headless();  // EGL, no window needed
  sandphys::World world(gpu, sandphys::WorldSettings{.maxBodies = 384});

  world.addCollider(sandphys::Plane{.normal = {0, 1, 0}, .offset = 0});  // the ground, y = 0
  world.addCollider(sandphys::Cylinder{.base = {0, 0, 0}, .radius = 0.3f, .height = 0.6f});
  world.addGranules(sandphys::GranuleBlock{
      .center = {0, 0.4f, 0}, .countX = 8, .countY = 6, .countZ = 8});  // 384 granules on a lattice

  for (int frame = 1; frame <= 120; ++frame) {  // two seconds at 60 frames per second
    sandphys::StepReport report = world.step(1.0f / 60);
    if (frame % 30 == 0) {
      std::printf("t = %.1f s: %u granules, kinetic energy %.5f J\n", world.simulatedTime(),
                  report.stats.granulesAlive, report.stats.kineticEnergy);
    }
  }
}
