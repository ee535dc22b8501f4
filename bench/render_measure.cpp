#include "render_measure.h"

#include <chrono>

#include "render/camera.h"
#include "render/offscreen_target.h"
#include "render/render_quality.h"
#include "render/renderer.h"

namespace sandphys::bench {

std::vector<RenderTiming> measureRender(const World& world, const scenes::SceneBounds& bounds,
                                        const RenderOptions& options) {
  using Clock = std::chrono::steady_clock;
  std::vector<RenderTiming> timings;
  if (options.width <= 0 || options.height <= 0) return timings;
  render::OffscreenTarget target(options.width, options.height);
  const render::Camera camera =
      render::Camera::framing({bounds}, float(options.width) / float(options.height));
  render::Renderer renderer;
  for (const render::RenderQuality quality :
       {render::RenderQuality::Low, render::RenderQuality::Medium, render::RenderQuality::High}) {
    render::applyRenderQuality(quality, renderer.settings());
    RenderTiming timing;
    timing.quality = std::string(render::renderQualityName(quality));
    timing.shadowMapSize = renderer.settings().shadowMapSize;
    timing.aoSamples = renderer.settings().aoSamples;
    target.bind();
    renderer.draw(world, camera, bounds, options.width, options.height);
    (void)renderer.finishStats();  // the untimed first frame
    for (std::uint32_t frame = 0; frame < options.frames; ++frame) {
      const Clock::time_point start = Clock::now();
      renderer.draw(world, camera, bounds, options.width, options.height);
      const render::RenderStats& stats = renderer.finishStats();
      timing.wallMs += std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      timing.shadowMs += stats.shadowMs;
      timing.sceneMs += stats.sceneMs;
      timing.compositeMs += stats.compositeMs;
      timing.totalMs += stats.totalMs;
      timing.renderWidth = stats.renderWidth;
      timing.renderHeight = stats.renderHeight;
    }
    const double frames = double(std::max<std::uint32_t>(options.frames, 1));
    timing.shadowMs /= frames;
    timing.sceneMs /= frames;
    timing.compositeMs /= frames;
    timing.totalMs /= frames;
    timing.wallMs /= frames;
    timings.push_back(timing);
  }
  return timings;
}

}  // namespace sandphys::bench
