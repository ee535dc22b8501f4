#include "app/cli.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "app/export.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"

namespace sandphys::samples {

namespace {

constexpr const char* kProgram = "sandphys-samples";

// A usage error: the message names the flag and the offending value.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void printSceneList(std::ostream& out) {
  std::string_view category;
  for (const scenes::SceneEntry& entry : scenes::sceneRegistry()) {
    if (entry.category != category) {
      category = entry.category;
      out << category << ":\n";
    }
    out << "  " << entry.name << " - " << entry.description << '\n';
    std::unique_ptr<scenes::Scene> scene = entry.create();
    for (const scenes::SceneParameter& parameter : scene->parameters()) {
      out << "      " << parameter.name << " = " << scenes::formatSceneParameter(parameter) << "  ("
          << parameter.help << ")\n";
    }
  }
}

// Fails now, before any simulation, if `path` cannot be written: a run of an hour should not end
// in "cannot open file". A file that did not exist is removed again.
void checkWritable(const std::string& flag, const std::filesystem::path& path) {
  std::error_code ignored;
  const bool existed = std::filesystem::exists(path, ignored);
  if (std::filesystem::is_directory(path, ignored)) {
    throw UsageError(flag + ": cannot write '" + path.string() + "': it is a directory");
  }
  errno = 0;
  {
    std::ofstream probe(path, std::ios::app);
    if (!probe) {
      const std::string reason = errno ? std::strerror(errno) : "cannot open";
      throw UsageError(flag + ": cannot write '" + path.string() + "': " + reason);
    }
  }
  if (!existed) std::filesystem::remove(path, ignored);
}

// Largest side of an image or window we accept, px. The renderer's buffers cost about 50 bytes a
// pixel: an 8192 x 8192 picture takes 3.4 GB and some 40 s on llvmpipe (16384 x 16384, the
// common GL limit, four times that, minutes without a word).
constexpr int kMaxImageSide = 8192;

ImageSize parseSize(const std::string& text) {
  static const std::regex sizeRe(R"(^([0-9]{1,6})[xX]([0-9]{1,6})$)");
  std::smatch match;
  const std::string limits = ": expected WIDTHxHEIGHT in pixels, each 1.." +
                             std::to_string(kMaxImageSide) + " (e.g. 960x540)";
  if (!std::regex_match(text, match, sizeRe)) throw UsageError("--size " + text + limits);
  const ImageSize size{std::stoi(match[1].str()), std::stoi(match[2].str())};
  if (size.width < 1 || size.height < 1 || size.width > kMaxImageSide ||
      size.height > kMaxImageSide) {
    throw UsageError("--size " + text + limits);
  }
  return size;
}

double parseFrameBudget(const std::string& text) {
  std::ostringstream limits;
  limits << ": expected a frame budget in milliseconds, 0.." << kMaxFrameBudgetMs
         << " (0 turns pacing off)";
  // strtod alone would take "nan", "inf" and hexadecimal; a budget is a plain decimal number.
  static const std::regex numberRe(R"(^[0-9]+(\.[0-9]*)?$|^\.[0-9]+$)");
  if (!std::regex_match(text, numberRe)) throw UsageError("--frame-budget " + text + limits.str());
  const double milliseconds = std::strtod(text.c_str(), nullptr);
  if (!std::isfinite(milliseconds) || milliseconds > kMaxFrameBudgetMs) {
    throw UsageError("--frame-budget " + text + limits.str());
  }
  return milliseconds;
}

// "auto" is the empty optional.
std::optional<render::RenderQuality> parseQuality(const std::string& text, bool headless) {
  if (text == "auto") {
    if (headless) {
      throw UsageError(
          "--quality auto: a headless run has no frame times to adapt to; use low, medium or "
          "high (the default)");
    }
    return std::nullopt;
  }
  if (const std::optional<render::RenderQuality> quality = render::parseRenderQuality(text)) {
    return quality;
  }
  throw UsageError("--quality " + text + ": expected auto, low, medium or high");
}

bool endsWithPng(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".png";
}

// Creates the folder if needed and proves that a file can be made in it.
void checkWritableDirectory(const std::string& flag, const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (!std::filesystem::is_directory(directory)) {
    throw UsageError(flag + ": cannot create or use the folder '" + directory.string() + "'" +
                     (error ? ": " + error.message() : std::string()));
  }
  checkWritable(flag, directory / ".sandphys-write-probe");
}

void applyParameter(scenes::Scene& scene, const std::string& flag, const std::string& name,
                    const std::string& value) {
  try {
    scenes::setSceneParameter(scene, name, value);
  } catch (const Error& error) {
    throw UsageError(flag + " " + value + ": " + error.what());
  }
}

// A run whose settings come from elsewhere (a recording, the goldens' fixed ones) takes only the
// flags in `allowed` beside `flag` itself: any other flag given is a usage error naming both.
void refuseOtherFlags(const CLI::App& app, const std::string& flag, const std::string& value,
                      std::initializer_list<std::string_view> allowed) {
  std::string list;
  std::size_t index = 0;
  for (const std::string_view name : allowed) {
    if (index > 0) list += index + 1 == allowed.size() ? " and " : ", ";
    list += name;
    ++index;
  }
  for (const CLI::Option* option : app.get_options()) {
    const std::string name = option->get_name();
    if (option->count() == 0 || name == flag ||
        std::find(allowed.begin(), allowed.end(), name) != allowed.end()) {
      continue;
    }
    throw UsageError(flag + " " + value + ": " + name + " cannot be combined with it (only " +
                     list + " may be added)");
  }
}

// CLI11 takes an empty string as a value, and for a number as the default: "--metrics ''" would
// write nothing and "--frames ''" run no frame, without a word. Every option that takes a value
// must get one.
void refuseEmptyValues(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->count() == 0 || option->get_type_size() == 0) continue;  // not given, or a flag
    for (const std::string& value : option->results()) {
      if (value.empty()) {
        // The first sentence of the flag's help says what it takes (unit, range, default).
        const std::string help = option->get_description();
        throw UsageError(
            option->get_name() + ": the value is empty; expected " +
            (option->get_type_name().empty() ? std::string("a value") : option->get_type_name()) +
            ": " + help.substr(0, help.find(". ")));
      }
    }
  }
}

// The same file, whether or not it exists yet: compared by canonical path (symbolic links and
// "." resolved), or as files when both exist (hard links).
bool samePath(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  if (std::filesystem::equivalent(a, b, error) && !error) return true;
  const std::filesystem::path ca = std::filesystem::weakly_canonical(a, error);
  if (error) return false;
  const std::filesystem::path cb = std::filesystem::weakly_canonical(b, error);
  return !error && ca == cb;
}

// A flag and the file it names.
struct NamedPath {
  std::string flag;
  std::filesystem::path path;
};

// Two outputs that are one file would overwrite each other, and an output that is an input
// would destroy it: both are refused, naming the flags.
void refuseClobbering(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      if (samePath(outputs[i].path, outputs[j].path)) {
        throw UsageError(outputs[i].flag + " " + outputs[i].path.string() + " and " +
                         outputs[j].flag + " " + outputs[j].path.string() +
                         ": the same file for two outputs; give each its own");
      }
    }
    for (const NamedPath& input : inputs) {
      if (samePath(outputs[i].path, input.path)) {
        throw UsageError(outputs[i].flag + " " + outputs[i].path.string() + ": is the input of " +
                         input.flag + "; writing it would destroy it");
      }
    }
  }
}

}  // namespace

std::optional<int> parseCommandLine(int argc, char** argv, RunOptions& options) {
  CLI::App app{"sandphys sample scenes: runs a scene headless and writes metrics and exports.",
               kProgram};
  bool list = false;
  std::int64_t frames = static_cast<std::int64_t>(options.frames);
  std::optional<std::string> batches;
  std::vector<std::string> batch;
  std::optional<std::string> seed;
  std::optional<std::string> mesh;
  std::optional<std::string> scale;
  std::optional<std::string> fit;
  std::optional<std::string> friction;
  std::optional<std::string> outlet;
  std::optional<std::string> granules;
  std::vector<std::string> assignments;
  std::string metrics;
  std::vector<std::string> exports;
  std::string lammps;
  std::string screenshot;
  std::optional<std::string> size;
  std::string screenshots;
  std::optional<std::int64_t> every;
  std::optional<std::string> frameBudget;
  std::optional<std::string> quality;
  std::string record;
  std::optional<std::int64_t> snapshotEvery;
  std::string replay;
  std::string play;
  std::string goldens;
  std::optional<std::string> contactLaw;
  bool sleep = false;
  float rollingFriction = 0.0f;

  app.add_option("--scene", options.sceneName, "scene to run (see --list)")->capture_default_str();
  app.add_flag("--list", list, "list the scenes and their parameters, then exit");
  app.add_flag("--headless", options.headless,
               "run without a window (always so in a build without the viewer, "
               "SANDPHYS_VIEWER=OFF); with a window, --frames N quits after N frames");
  CLI::Option* framesOption =
      app.add_option("--frames", frames, "frames to run (the cap with --until-done)")
          ->capture_default_str();
  app.add_option("--frame-dt", options.frameDt, "duration of one frame, s")->capture_default_str();
  app.add_flag("--until-done", options.untilDone,
               "stop as soon as the scene is finished (e.g. the last batch settled)");
  app.add_flag("--quiet", options.quiet, "no progress line");
  app.add_option("--metrics", metrics, "write run metrics to this JSON file");
  app.add_option("--export", exports,
                 "write the granules at the end to FILE.csv or FILE.vtk (repeatable)");
  app.add_option("--export-lammps", lammps,
                 "write a LAMMPS deck of the World at the end to folder DIR (in.sandphys; run it "
                 "with lmp -in in.sandphys, or mpirun -np N lmp -in in.sandphys)")
      ->type_name("DIR");
  app.add_option("--batches", batches, "cylinder-pile: batches dropped in total");
  app.add_option(
         "--batch,--batch-size", batch,
         "cylinder-pile: granules per batch X Y Z: X·Z columns laid out as a disc, Y layers "
         "high (default 32 16 32)")
      ->expected(3);
  app.add_option("--seed", seed, "random seed of the scene's granules");
  app.add_option("--mesh", mesh, "rock-drop: the mesh file to drop (OBJ, STL, PLY, glTF/GLB)")
      ->type_name("FILE");
  app.add_option("--scale", scale, "rock-drop: scale factor applied to the mesh")->type_name("S");
  app.add_option("--fit", fit,
                 "rock-drop: scale the mesh so that its largest extent is M metres (in place of "
                 "--scale); the bed grows to fit the rock")
      ->type_name("M");
  app.add_option(
         "--friction", friction,
         "friction coefficient (hourglass: of the grains, the wall's is --param wall-friction; "
         "repose-heap: of "
         "every contact; repose-scupper: of the grains and the sump's floor; slope-avalanche, "
         "avalanche: of the slope and the walls)")
      ->type_name("MU");
  app.add_option("--outlet", outlet,
                 "hourglass: outlet diameter; repose-heap: width of the pouring emitter; "
                 "repose-scupper: height of the open scupper; particle diameters")
      ->type_name("D");
  app.add_option("--granules", granules,
                 "granules (hourglass: in the funnel; sand-box-pour, repose-heap: poured in total; "
                 "repose-scupper: in the reservoir)")
      ->type_name("N");
  app.add_option("--param", assignments, "set a scene parameter NAME=VALUE (see --list)");
  app.add_option("--contact-law", contactLaw,
                 "hertz-mindlin (default: tangential springs with history, friction at the "
                 "contact point, damping from body masses) or paper (Longmore et al. 2013 as "
                 "published: memoryless viscous friction at particle centres, overlap capped at "
                 "d/10)")
      ->type_name("LAW");
  app.add_flag("--sleep", sleep,
               "sleeping sand: granules at rest fall asleep and cost less until touched "
               "(WorldSettings::sleep)");
  app.add_option("--rolling-friction", rollingFriction,
                 "rolling friction mu_r of every contact (Material::rollingFriction; default 0: "
                 "none). Stops granules rocking on two contacts; it has no static part, so loaded "
                 "sand creeps slowly (docs/architecture.md, \"contacts\")")
      ->check(CLI::Range(0.0f, 10.0f))
      ->type_name("MU");
  app.add_option("--screenshot", screenshot,
                 "write a PNG of the last frame to this file (headless: rendered offscreen)");
  app.add_option("--size", size,
                 "WIDTHxHEIGHT of screenshots and of the window, px (default 1280x720)");
  app.add_option("--screenshots", screenshots,
                 "write an image sequence DIR/frame_NNNNNN.png every --every frames");
  app.add_option("--every", every, "frames between images of --screenshots (default 10)");
  app.add_option("--frame-budget", frameBudget,
                 "window: wall-clock time one frame may take, ms (default 50, 0..10000). Each "
                 "frame runs as many substeps as fit beside the rendering, in slow motion when "
                 "that is less than --frame-dt; 0 = off: every frame simulates all of --frame-dt")
      ->type_name("MS");
  app.add_option("--quality", quality,
                 "render quality: auto, low, medium or high (render scale, shadow map, AO "
                 "samples). Window: default auto, which picks it from the render time and the "
                 "frame budget; headless: default high, auto refused")
      ->type_name("QUALITY");
  app.add_option("--record", record,
                 "record the run to FILE (docs/recording.md): settings, per-frame inputs and state "
                 "hashes, snapshots every --snapshot-every frames")
      ->type_name("FILE");
  app.add_option("--snapshot-every", snapshotEvery,
                 "frames between two full snapshots of --record (default 60; 1 lets a replay name "
                 "the body and field at the very frame that differs)")
      ->type_name("K");
  app.add_option("--replay", replay,
                 "re-simulate the recording FILE headless and check every frame; exit 1 at the "
                 "first difference, which is named (frame, body, field, both values)")
      ->type_name("FILE");
  app.add_option("--play", play,
                 "window: show the recording FILE on a timeline, re-simulated and checked frame by "
                 "frame; Left and Right jump between its snapshots")
      ->type_name("FILE");
  app.add_option("--write-goldens", goldens,
                 "run every scene for a fifth of a second at its test size and write its headline "
                 "metrics to DIR/<scene>.json: regenerates tests/golden on purpose")
      ->type_name("DIR");
  app.add_flag("--panel-in-screenshots", options.panelInScreenshots,
               "window: screenshots (F, --screenshot, --screenshots) show the whole window with "
               "the panel, not the scene alone");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) {
      return app.exit(error);  // --help
    }
    std::cerr << kProgram << ": error: " << error.what() << "\nRun with --help for usage.\n";
    return kExitUsage;
  }
  if (list) {
    printSceneList(std::cout);
    return kExitOk;
  }

  try {
    refuseEmptyValues(app);
    // A replay takes everything from its recording, and the goldens have fixed settings: nothing
    // else may shape those runs.
    if (!goldens.empty()) {
      refuseOtherFlags(app, "--write-goldens", goldens, {"--quiet"});
      options.goldenDir = goldens;
      checkWritableDirectory("--write-goldens", options.goldenDir);
      options.headless = true;
      return std::nullopt;
    }
    if (!replay.empty()) {
      refuseOtherFlags(app, "--replay", replay, {"--quiet"});
      options.replayPath = replay;
      options.headless = true;
      return std::nullopt;
    }
    if (!play.empty()) {
      // The recording gives the scene and its settings; only the window's own flags may be added.
      if (options.headless) {
        throw UsageError("--play " + play +
                         ": shows the recording in the window, not with --headless (--replay FILE "
                         "checks it headless)");
      }
      refuseOtherFlags(app, "--play", play,
                       {"--quiet", "--frames", "--size", "--quality", "--screenshot",
                        "--screenshots", "--every", "--panel-in-screenshots"});
      options.playPath = play;
    }
    if (frames < 0) {
      throw UsageError("--frames " + std::to_string(frames) + ": must be 0 or more");
    }
    options.frames = static_cast<std::uint64_t>(frames);
    options.framesGiven = framesOption->count() > 0;
    if (size) options.size = parseSize(*size);
    if (every) {
      if (*every < 1) {
        throw UsageError("--every " + std::to_string(*every) + ": must be 1 or more frames");
      }
      if (screenshots.empty()) {
        throw UsageError("--every " + std::to_string(*every) +
                         ": only means something with --screenshots DIR");
      }
      options.every = static_cast<std::uint64_t>(*every);
    }
    if (frameBudget) {
      options.frameBudgetMs = parseFrameBudget(*frameBudget);
      if (options.headless) {
        throw UsageError("--frame-budget " + *frameBudget +
                         ": only means something in the window, not with --headless");
      }
    }
    if (quality) options.quality = parseQuality(*quality, options.headless);
    if (options.panelInScreenshots && options.headless) {
      throw UsageError(
          "--panel-in-screenshots: only means something in the window, not with --headless");
    }
    if (!(options.frameDt > 0.0) || !(options.frameDt <= 1.0)) {
      std::ostringstream value;
      value << options.frameDt;
      throw UsageError("--frame-dt " + value.str() + ": must be in (0, 1] s");
    }
    // A recording to play brings its own scene.
    if (options.playPath.empty()) {
      const scenes::SceneEntry* entry = scenes::findScene(options.sceneName);
      if (!entry) {
        throw UsageError("--scene " + options.sceneName + ": unknown scene (see --list)");
      }
      options.scene = entry->create();
      if (batches) applyParameter(*options.scene, "--batches", "batches", *batches);
      if (!batch.empty()) {
        applyParameter(*options.scene, "--batch", "batch",
                       batch[0] + "," + batch[1] + "," + batch[2]);
      }
      if (seed) applyParameter(*options.scene, "--seed", "seed", *seed);
      if (mesh) applyParameter(*options.scene, "--mesh", "mesh", *mesh);
      if (scale) applyParameter(*options.scene, "--scale", "scale", *scale);
      if (fit) applyParameter(*options.scene, "--fit", "fit", *fit);
      if (friction) applyParameter(*options.scene, "--friction", "friction", *friction);
      if (outlet) applyParameter(*options.scene, "--outlet", "outlet", *outlet);
      if (granules) applyParameter(*options.scene, "--granules", "granules", *granules);
      if (contactLaw) {
        const std::optional<ContactLaw> law = scenes::contactLawFromName(*contactLaw);
        if (!law) {
          throw UsageError("--contact-law " + *contactLaw +
                           ": unknown contact law (hertz-mindlin or paper)");
        }
        options.scene->setContactLaw(*law);
      }
      options.scene->setSleep(sleep);
      options.scene->setRollingFriction(rollingFriction);
      for (const std::string& assignment : assignments) {
        const std::size_t equals = assignment.find('=');
        if (equals == std::string::npos || equals == 0) {
          throw UsageError("--param " + assignment + ": expected NAME=VALUE");
        }
        applyParameter(*options.scene, "--param", assignment.substr(0, equals),
                       assignment.substr(equals + 1));
      }
      // Settings validate the parameters together (e.g. batches × batch against the limits), and
      // the World would refuse what they come to (a capacity beyond the GPU's, say): both before
      // any simulation, naming the flags that set the scene's parameters.
      try {
        World::checkSettings(options.scene->settings());
      } catch (const MeshError& error) {
        // Scenes load their mesh files here; name the flag that gave the file.
        throw UsageError((mesh ? "--mesh " + *mesh : std::string("scene parameters")) + ": " +
                         error.what());
      } catch (const Error& error) {
        // The flags that shaped the scene, as given.
        std::string given;
        for (const char* name : {"--batches", "--batch", "--seed", "--mesh", "--scale", "--fit",
                                 "--friction", "--outlet", "--granules", "--param"}) {
          const CLI::Option* option = app.get_option(name);
          if (option->count() == 0) continue;
          given += given.empty() ? "" : ", ";
          given += option->get_name();
          for (const std::string& value : option->results()) given += " " + value;
        }
        throw UsageError("scene parameters" + (given.empty() ? "" : " (" + given + ")") + ": " +
                         error.what());
      }
    }

    std::vector<NamedPath> outputs;
    if (!metrics.empty()) outputs.push_back({"--metrics", metrics});
    for (const std::string& path : exports) outputs.push_back({"--export", path});
    if (!screenshot.empty()) outputs.push_back({"--screenshot", screenshot});
    if (!record.empty()) outputs.push_back({"--record", record});
    if (!screenshots.empty()) outputs.push_back({"--screenshots", screenshots});
    if (!lammps.empty()) outputs.push_back({"--export-lammps", lammps});
    std::vector<NamedPath> inputs;
    if (!play.empty()) inputs.push_back({"--play", play});
    if (options.scene) {
      for (const scenes::SceneParameter& parameter : options.scene->parameters()) {
        if (const auto* file = std::get_if<std::string*>(&parameter.value);
            file && !(*file)->empty()) {
          inputs.push_back(
              {mesh && parameter.name == "mesh" ? "--mesh" : "--param " + parameter.name, **file});
        }
      }
    }
    refuseClobbering(outputs, inputs);
    if (!metrics.empty()) {
      options.metricsPath = metrics;
      checkWritable("--metrics", options.metricsPath);
    }
    for (const std::string& path : exports) {
      if (!exportFormatFor(path)) {
        throw UsageError("--export " + path + ": unknown extension '" +
                         std::filesystem::path(path).extension().string() + "' (use .csv or .vtk)");
      }
      checkWritable("--export", path);
      options.exportPaths.emplace_back(path);
    }
    if (!lammps.empty()) {
      options.lammpsDir = lammps;
      checkWritableDirectory("--export-lammps", options.lammpsDir);
    }
    if (!screenshot.empty()) {
      if (!endsWithPng(screenshot)) {
        throw UsageError("--screenshot " + screenshot + ": the file name must end in .png");
      }
      options.screenshotPath = screenshot;
      checkWritable("--screenshot", options.screenshotPath);
    }
    if (snapshotEvery) {
      if (*snapshotEvery < 1) {
        throw UsageError("--snapshot-every " + std::to_string(*snapshotEvery) +
                         ": must be 1 or more frames");
      }
      if (record.empty()) {
        throw UsageError("--snapshot-every " + std::to_string(*snapshotEvery) +
                         ": only means something with --record FILE");
      }
      options.snapshotEvery = static_cast<std::uint64_t>(*snapshotEvery);
    }
    if (!record.empty()) {
      options.recordPath = record;
      checkWritable("--record", options.recordPath);
    }
    if (!screenshots.empty()) {
      options.screenshotDir = screenshots;
      checkWritableDirectory("--screenshots", options.screenshotDir);
    }
  } catch (const UsageError& error) {
    std::cerr << kProgram << ": error: " << error.what() << "\nRun with --help for usage.\n";
    return kExitUsage;
  }
  return std::nullopt;
}

}  // namespace sandphys::samples
