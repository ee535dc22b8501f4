// The sandphys-samples command line: usage errors exit non-zero and name the flag and the value.
// None of these reach the GPU.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "process.h"

namespace sandphys::testing {
namespace {

std::string samplesCommand(const std::string& arguments) {
  return std::string("'") + SANDPHYS_SAMPLES_EXE + "' " + arguments;
}

ProcessResult runSamples(const std::string& arguments) {
  return runCommand(samplesCommand(arguments));
}

void expectUsageError(const std::string& arguments, std::initializer_list<const char*> named) {
  expectUsageErrorOf(samplesCommand(arguments), arguments, named);
}

TEST(SamplesCli, UnknownFlag) {
  expectUsageError("--headless --bogus-flag", {"--bogus-flag"});
}

TEST(SamplesCli, NegativeFrames) {
  expectUsageError("--frames -5", {"--frames", "-5"});
}

TEST(SamplesCli, FramesNotANumber) {
  expectUsageError("--frames lots", {"--frames", "lots"});
}

TEST(SamplesCli, FrameDtNotPositive) {
  expectUsageError("--frame-dt 0", {"--frame-dt"});
}

TEST(SamplesCli, UnknownScene) {
  expectUsageError("--headless --scene no-such-scene", {"--scene", "no-such-scene"});
}

TEST(SamplesCli, BatchNeedsThreePositiveCounts) {
  expectUsageError("--batch 8 0 8", {"--batch", "8,0,8"});
  expectUsageError("--batch 8 8", {"--batch"});
  expectUsageError("--batches -2", {"--batches", "-2"});
}

TEST(SamplesCli, ParameterOfAnotherScene) {
  expectUsageError("--scene box-drop --batches 3", {"--batches", "batches"});
  expectUsageError("--param nonsense", {"--param", "nonsense"});
}

TEST(SamplesCli, ExportNeedsAKnownExtension) {
  expectUsageError("--export granules.txt", {"--export", "granules.txt", ".txt"});
}

TEST(SamplesCli, UnwritablePathsAreRefusedBeforeRunning) {
  const std::string missing = "/nonexistent-sandphys-dir/metrics.json";
  expectUsageError("--metrics " + missing, {"--metrics", missing.c_str()});
  expectUsageError("--export /nonexistent-sandphys-dir/g.csv",
                   {"--export", "/nonexistent-sandphys-dir/g.csv"});
  const std::string directory = std::filesystem::temp_directory_path().string();
  expectUsageError("--metrics " + directory, {"--metrics", directory.c_str()});
}

// A file in the temporary folder, unique to this process, removed when the test ends.
class TemporaryFile {
 public:
  TemporaryFile(const std::string& name, const std::string& contents)
      : m_path(std::filesystem::temp_directory_path() /
               ("sandphys-cli-" + std::to_string(::getpid()) + "-" + name)) {
    std::ofstream(m_path) << contents;
  }
  ~TemporaryFile() { std::filesystem::remove(m_path); }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  std::string path() const { return m_path.string(); }

 private:
  std::filesystem::path m_path;
};

TEST(SamplesCli, MissingMeshFileIsNamed) {
  expectUsageError("--headless --scene rock-drop --mesh /nonexistent-sandphys.obj",
                   {"--mesh", "/nonexistent-sandphys.obj", "does not exist"});
}

TEST(SamplesCli, MeshThatCannotMakeABodyIsNamedWithItsProblem) {
  // A tetrahedron with one corner not a number.
  const TemporaryFile nan("nan.obj",
                          "v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\n"
                          "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expectUsageError("--headless --scene rock-drop --mesh " + nan.path(),
                   {"--mesh", nan.path().c_str(), "not finite"});
  const TemporaryFile points("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expectUsageError("--headless --scene rock-drop --mesh " + points.path(),
                   {"--mesh", points.path().c_str(), "no triangles"});
}

TEST(SamplesCli, MeshScaleAndFitMustBePositiveNumbers) {
  expectUsageError("--headless --scene rock-drop --scale -1", {"--scale", "-1", "range"});
  expectUsageError("--headless --scene rock-drop --scale 0", {"--scale", "0", "range"});
  expectUsageError("--headless --scene rock-drop --scale nan", {"--scale", "nan", "not finite"});
  expectUsageError("--headless --scene rock-drop --fit -0.2", {"--fit", "-0.2", "range"});
  expectUsageError("--headless --scene rock-drop --fit inf", {"--fit", "inf"});
}

// Any model of assimp's test set, in whatever unit it was made, becomes a rock of the size asked
// for, on a bed grown to hold it: no scale to compute by hand.
TEST(SamplesCli, AnyMeshFitsTheRockDrop) {
  for (const char* model :
       {"/usr/share/assimp/models/PLY/Wuson.ply", "/usr/share/assimp/models/OBJ/spider.obj",
        "/usr/share/assimp/models/STL/Spider_binary.stl"}) {
    const ProcessResult result = runSamples(
        std::string("--headless --quiet --scene rock-drop --fit 0.2 --frames 2 --mesh ") + model);
    EXPECT_EQ(result.exitCode, 0) << model << "\n" << result.output;
  }
}

// --export-lammps writes the deck of the last frame's World, its scene's script named among what
// does not map; a folder that is a file is refused before anything runs.
TEST(SamplesCli, ExportLammpsWritesTheDeckOfTheLastFrame) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("sandphys-cli-lammps-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const ProcessResult result = runSamples(
      "--headless --scene box-drop --param block=2,2,2 --frames 3 --export-lammps " + dir.string());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("LAMMPS deck"), std::string::npos) << result.output;
  std::ifstream deck(dir / "in.sandphys");
  const std::string text((std::istreambuf_iterator<char>(deck)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("8 rigid clumps of 32 particles"), std::string::npos) << text;
  EXPECT_NE(text.find("the box-drop scene's script"), std::string::npos) << text;
  EXPECT_TRUE(std::filesystem::exists(dir / "sandphys.data"));
  EXPECT_TRUE(std::filesystem::exists(dir / "bodies.rigid"));
  std::filesystem::remove_all(dir);
  const TemporaryFile file("not-a-folder", "x");
  expectUsageError("--headless --scene box-drop --export-lammps " + file.path(),
                   {"--export-lammps", file.path().c_str()});
}

TEST(SamplesCli, MeshOnASceneWithoutOne) {
  expectUsageError("--headless --scene box-drop --mesh rock.obj", {"--mesh", "mesh", "box-drop"});
  expectUsageError("--headless --scene box-drop --scale 2", {"--scale", "scale", "box-drop"});
}

TEST(SamplesCli, ReplayPlayAndGoldensTakeNoRunFlags) {
  expectUsageError("--replay run.sprec --scene box-drop", {"--replay", "--scene"});
  expectUsageError("--replay run.sprec --frames 5", {"--replay", "--frames"});
  expectUsageError("--write-goldens /tmp --granules 5", {"--write-goldens", "--granules"});
  // --play takes the window's own flags only, and the window.
  expectUsageError("--play run.sprec --scene box-drop", {"--play", "--scene", "--size"});
  expectUsageError("--play run.sprec --frame-dt 0.01", {"--play", "--frame-dt"});
  expectUsageError("--play run.sprec --headless", {"--play", "--headless", "--replay"});
  expectUsageError("--headless --snapshot-every 0 --record r.sprec", {"--snapshot-every", "0"});
  expectUsageError("--headless --snapshot-every 5", {"--snapshot-every", "--record"});
  expectUsageError("--headless --record /nonexistent-sandphys-dir/r.sprec",
                   {"--record", "/nonexistent-sandphys-dir/r.sprec"});
}

// The two commands of docs/recording.md, end to end: a run recorded and replayed from its file
// (exit 0), and the same file damaged by one byte (exit 1, the file named).
TEST(SamplesCli, RecordThenReplayAndADamagedRecording) {
  const TemporaryFile recording("run.sprec", "");
  ProcessResult result = runSamples(
      "--headless --quiet --scene box-drop --param block=3,2,3 "
      "--frames 6 --snapshot-every 2 --record " +
      recording.path());
  ASSERT_EQ(result.exitCode, 0) << result.output;
  result = runSamples("--replay " + recording.path());
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("6 frames bit-identical (4 snapshots compared)"), std::string::npos)
      << result.output;

  std::string bytes;
  {
    std::ifstream in(recording.path(), std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 100u);
  bytes[bytes.size() / 2] = char(bytes[bytes.size() / 2] ^ 1);
  std::ofstream(recording.path(), std::ios::binary | std::ios::trunc) << bytes;
  result = runSamples("--replay " + recording.path());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_NE(result.output.find(recording.path() + "' is damaged"), std::string::npos)
      << result.output;
}

TEST(SamplesCli, EmptyValuesAreRefusedNotTakenAsNothing) {
  expectUsageError("--headless --frames ''", {"--frames", "empty"});
  expectUsageError("--headless --metrics ''", {"--metrics", "empty"});
  expectUsageError("--headless --record ''", {"--record", "empty"});
  expectUsageError("--headless --screenshot ''", {"--screenshot", "empty"});
  // Not a window opened on no recording.
  expectUsageError("--replay ''", {"--replay", "empty"});
}

TEST(SamplesCli, AnImageTooLargeToRenderInReasonableTimeIsRefused) {
  expectUsageError("--headless --size 16384x16384", {"--size 16384x16384", "1..8192"});
}

TEST(SamplesCli, AWorldTheParametersWouldMakeIsRefusedNamingTheFlag) {
  expectUsageError(
      "--headless --scene box-drop --param block=1000,1000,1000",
      {"--param block=1000,1000,1000", "WorldSettings.maxParticles = 4000000000", "2097152"});
}

TEST(SamplesCli, OutputsNeitherOverwriteEachOtherNorAnInput) {
  const TemporaryFile out("same.out", "");
  expectUsageError("--headless --metrics " + out.path() + " --record " + out.path(),
                   {"--metrics", "--record", "the same file"});
  expectUsageError("--headless --export " + out.path() + ".csv --screenshot " + out.path() +
                       ".png --export " + out.path() + ".csv",
                   {"--export", "the same file"});
  // The rock's own mesh, named by --mesh or --param mesh=, is never an output.
  const TemporaryFile victim("victim.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  expectUsageError(
      "--headless --scene rock-drop --mesh " + victim.path() + " --record " + victim.path(),
      {"--record", "is the input of --mesh"});
  expectUsageError(
      "--headless --scene rock-drop --param mesh=" + victim.path() + " --metrics " + victim.path(),
      {"--metrics", "is the input of --param mesh"});
  std::ifstream in(victim.path());
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(text.substr(0, 6), "v 0 0 ");
}

TEST(SamplesCli, ListPrintsTheRegistry) {
  const ProcessResult result = runSamples("--list");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  EXPECT_NE(result.output.find("cylinder-pile"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("box-drop"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("batches = 1"), std::string::npos) << result.output;
}

TEST(SamplesCli, HelpNamesTheFlags) {
  const ProcessResult result = runSamples("--help");
  EXPECT_EQ(result.exitCode, 0) << result.output;
  for (const char* flag :
       {"--scene", "--headless", "--frames", "--frame-dt", "--metrics", "--export", "--batches",
        "--batch", "--seed", "--mesh", "--scale", "--list"}) {
    EXPECT_NE(result.output.find(flag), std::string::npos) << flag;
  }
}

}  // namespace
}  // namespace sandphys::testing
