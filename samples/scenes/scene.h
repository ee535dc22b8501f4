#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::scenes {

/// Three counts, e.g. granules of a block along x, y and z.
using Count3 = std::array<std::uint32_t, 3>;

/// One tunable value of a scene, so that the command line (`--param name=value`) and the viewer's
/// panel can set it without knowing the scene's type. `value` points into the scene that returned
/// it and lives as long as that scene. A change takes effect at the next Scene::build.
struct SceneParameter {
  /// Name on the command line and in the viewer, kebab-case ("batches", "batch", "seed").
  std::string name;
  /// One line for --help and tooltips, with the unit.
  std::string help;
  /// Where the value lives. Count3 values are set as "X,Y,Z" or "X Y Z"; a string (a file name)
  /// takes any text that is not empty, and min and max do not apply to it.
  std::variant<std::uint32_t*, std::uint64_t*, float*, Count3*, std::string*> value;
  /// Smallest valid value (of each component for Count3).
  double min = 0.0;
  /// Largest valid value (of each component for Count3).
  double max = 1.0e9;
};

/// A rigid body of a scene that is not sand (a block Bullet simulates, a sampled rock), as the
/// metrics report it.
struct SceneBody {
  std::string name;    ///< kebab-case, unique in the scene ("upper-block")
  Vec3 position{};     ///< centre of mass, m
  Quat orientation{};  ///< w, x, y, z
  float speed = 0.0f;  ///< of the centre of mass, m/s
  /// Angle between the body's up axis at the start and now, degrees.
  float tiltDegrees = 0.0f;
};

/// A number a scene adds to the run's metrics (written under "scene_metrics" in the JSON).
struct SceneMetric {
  /// snake_case key, with the unit as a suffix where it has one ("pile_top_m").
  std::string name;
  /// The value, in the unit the name states.
  double value = 0.0;
};

/// A quantity a scene records over a run (the granules left in a funnel against time) and the
/// numbers derived from it (a flow rate fitted to it), written at the top level of the metrics
/// JSON: `name` as a list of [x, y] pairs and each derived number under its own name.
struct SceneSeries {
  /// snake_case key of the points ("remaining"); must not be a key the runner writes itself.
  std::string name;
  /// [x, y] pairs in the order recorded, in the units the scene documents ([s, granules]).
  std::vector<std::array<double, 2>> points;
  /// Numbers fitted to or read from the points ("flow_rate"), each a top-level key.
  std::vector<SceneMetric> derived;
};

/// Axis-aligned box around everything a scene puts in the world, m. The viewer frames its camera
/// on it.
struct SceneBounds {
  Vec3 min{};  ///< smallest corner, m
  Vec3 max{};  ///< largest corner, m
};

/// What a body that is not sand is made of, for the picture: each has its colour
/// (render::RenderSettings::materialColours).
enum class BodyMaterial : std::uint32_t { Wood, Stone, Metal };
inline constexpr std::size_t kBodyMaterials = std::size_t(BodyMaterial::Metal) + 1;

/// How a body that is not sand looks: the triangles its particles were sampled from (a Bullet
/// shape, a mesh file, a blade), drawn where the body is in place of its particles.
struct SceneSurface {
  BodyId body;
  /// In the frame BodyDesc::orientation turns, with the body's centre of mass at the origin, m.
  TriangleMesh mesh;
  /// The body's ParticleTemplate::principalRotation: the World moves the body by its principal
  /// frame.
  Quat principalRotation{};
  BodyMaterial material = BodyMaterial::Stone;
};

/// The surface of a body added from `sampled` (sampleMesh of `mesh`) with id `body`.
SceneSurface surfaceOf(BodyId body, const TriangleMesh& mesh, const SampledMesh& sampled,
                       BodyMaterial material);

/// How the camera looks at a scene first, and again on Home: the box it frames (the sand and the
/// bodies, not the containers) and the direction it looks from.
struct SceneView {
  SceneBounds focus;    ///< what the picture must hold, m
  float yaw = 0.6f;     ///< the eye's turn about the vertical, rad; 0 puts it on +z
  float pitch = 0.45f;  ///< the eye's height above the horizontal, rad
};

/// A sample scene: world settings, the initial contents and the scene's own logic over time
/// (dropping the next batch, moving a plunger, ...). Shared by the samples app, the viewer, the
/// tests and the benchmark, which all drive it the same way:
///
///   World world(gpu, scene.settings());
///   scene.build(world);
///   while (!done) { StepReport r = scene.step(world, dt); scene.update(world, r,
///   world.simulatedTime());
///   }
///
/// A scene owns its parameters; build() may be called again on a fresh World to restart.
class Scene {
 public:
  virtual ~Scene() = default;

  /// The registry name, e.g. "cylinder-pile".
  virtual std::string_view name() const = 0;

  /// Settings for the World this scene runs in (worldSettings) under the contact law set with
  /// setContactLaw, with sleep as setSleep says and the rolling friction setRollingFriction set.
  WorldSettings settings() const;

  /// The contact law the scene's World gets (the samples app's --contact-law); HertzMindlin
  /// unless set. Takes effect at the next World built from settings().
  void setContactLaw(ContactLaw law) { m_contactLaw = law; }
  ContactLaw contactLaw() const { return m_contactLaw; }

  /// Sleeping sand (WorldSettings::sleep, the samples app's --sleep) in the scene's World; off
  /// unless set. Takes effect at the next World built from settings().
  void setSleep(bool enabled) { m_sleep = enabled; }
  bool sleep() const { return m_sleep; }

  /// Rolling friction μ_r of every contact (Material::rollingFriction, the samples app's
  /// --rolling-friction); 0 unless set. Takes effect at the next World built from settings().
  void setRollingFriction(float mu) { m_rollingFriction = mu; }
  float rollingFriction() const { return m_rollingFriction; }

  /// The scene's own settings, with capacities sized for everything the scene will ever add
  /// (World::reserve is never needed). Throws InvalidArgument when the parameters ask for more
  /// than a World can hold.
  virtual WorldSettings worldSettings() const = 0;

  /// Adds colliders, floors and the first granules to `world`, which was created from settings()
  /// and is otherwise empty; resets the scene's own state (so that the scene can be rebuilt).
  virtual void build(World& world) = 0;

  /// Advances the scene by one frame of `frameDt` s: World::step, which the default does, or the
  /// step of an engine coupled to the sand (a Bullet bridge steps both worlds).
  virtual StepReport step(World& world, float frameDt) { return world.step(frameDt); }

  /// Scene logic after each World::step: `report` is that step's report and `simTime` the world's
  /// simulated time in s. May add granules; a read-back here is allowed only rarely (once per
  /// batch, never per frame). The default does nothing.
  virtual void update(World& /*world*/, const StepReport& /*report*/, double /*simTime*/) {}

  /// True once the scene has nothing more to do (all batches dropped and settled). Runs may stop
  /// there; scenes without an end never finish.
  virtual bool finished() const { return false; }

  /// One short line about the scene's progress for progress lines and the viewer ("batch 2/4").
  virtual std::string status() const { return {}; }

  /// Whether a granule centre (m) is inside the scene's container; granules outside at the end of
  /// a run are reported as lost. The default accepts every point.
  virtual bool contains(const Vec3& /*centre*/) const { return true; }

  /// Scene-specific numbers for the metrics, from the bodies read back at the end of a run.
  virtual std::vector<SceneMetric> metrics(std::span<const BodyState> /*bodies*/) const {
    return {};
  }

  /// The scene's time series and what was derived from them, at the end of a run (no read-back:
  /// a scene records them in update()). The default has none.
  virtual std::vector<SceneSeries> series() const { return {}; }

  /// The scene's rigid bodies that are not sand, now, in `world` (the one build() filled), for
  /// the metrics and their time series. Bodies that sandphys simulates are read back from `world`
  /// (a sync point: the runner asks only every few frames). The default has none.
  virtual std::vector<SceneBody> bodies(const World& /*world*/) const { return {}; }

  /// The surfaces of the scene's bodies that are not sand, for the renderer (the bodies
  /// build() added; empty before): m_surfaces unless overridden. A body without one is drawn as
  /// its particles.
  virtual std::span<const SceneSurface> surfaces() const { return m_surfaces; }

  /// Body states set from outside the sand during the last step, in order: what a Bullet bridge
  /// pushed (Bridge::pushes). A recording keeps them as the frame's external inputs and a replay
  /// checks them. Scene logic of its own (a plunger, a blade) is not external. The default has
  /// none.
  virtual std::vector<RecordedInput> externalInputs() const { return {}; }

  /// The scene's tunable values (see SceneParameter). The default has none.
  virtual std::vector<SceneParameter> parameters() { return {}; }

  /// Where the scene's contents are, containers included (shadows, planes drawn as patches).
  virtual SceneBounds bounds() const = 0;

  /// The view to open on, given `contents`: the bounds of its granules and movable bodies now
  /// (contentsOf). The default frames them, or the whole scene while it holds none; a scene whose
  /// action goes elsewhere (a run-out, a pour still to come) widens the focus or turns the eye.
  virtual SceneView view(const std::optional<SceneBounds>& contents) const;

 protected:
  /// What surfaces() returns; build() fills it.
  std::vector<SceneSurface> m_surfaces;

 private:
  ContactLaw m_contactLaw = ContactLaw::HertzMindlin;
  bool m_sleep = false;
  float m_rollingFriction = 0.0f;
};

/// The bounds of `world`'s alive bodies that `scene` contains, but for static ones (floors), each
/// grown by its reach; nothing when there are none. Sync point (reads the bodies back).
std::optional<SceneBounds> contentsOf(const Scene& scene, const World& world);

/// Runs `scene` in `world` (the one its build() filled) frame by frame, Scene::step then
/// Scene::update, until the scene finishes or the world has simulated `maxSeconds` s in all.
/// Returns Scene::finished.
bool runUntilFinished(Scene& scene, World& world, float frameDt, double maxSeconds);

/// The name of a contact law on the command line and in recordings: "hertz-mindlin" or "paper".
std::string_view contactLawName(ContactLaw law);
/// The law named `name` (contactLawName), or nothing.
std::optional<ContactLaw> contactLawFromName(std::string_view name);

}  // namespace sandphys::scenes
