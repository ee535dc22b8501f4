#!/usr/bin/env bash
# The main job: installs what is missing, builds the `release` preset and runs the avalanche: a
# block of sand released down a slope onto two wooden blocks that Bullet simulates; it runs over
# the low one and topples the plank standing on it. With a display it opens the viewer. Without
# one it runs headless until the sand has come to rest and writes the run's metrics (JSON, with
# the plank's tilt), the granules at the end (CSV) and a picture of the last frame, rendered
# offscreen (PNG), to out/, and prints what happened in one line.
# Usage: scripts/run-sample.sh [extra sandphys-samples options]
# Environment:
#   FRAMES   most frames of 1/60 s to run (default 600; the run stops earlier once at rest)
#   SCENE    scene to run (default avalanche; `sandphys-samples --list` shows them)
#   BATCH    cylinder-pile only: granules per batch "X Y Z" (default "8 4 8", 256 granules;
#            BATCH= uses the scene's own 32 16 32)
#   OUT_DIR  where the outputs go (default out, in the repository)
#   HEADLESS set to anything: run headless (and write the PNG) even with a display
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."
repo_root="$(pwd)"

scene="${SCENE:-avalanche}"
frames="${FRAMES:-600}"
out_dir="${OUT_DIR:-out}"
default_batch=""
if [[ "${scene}" == "cylinder-pile" ]]; then default_batch="8 4 8"; fi
batch="${BATCH-${default_batch}}"

scripts/install-deps.sh

cmake --preset release
# Only what this job runs (the library and the samples app); test.sh builds everything.
cmake --build --preset release --target sandphys-samples

mkdir -p -- "${out_dir}"
metrics="${out_dir}/${scene}.json"
export_csv="${out_dir}/${scene}.csv"

picture="${out_dir}/${scene}.png"

# A display means a person is watching: open the viewer. Without one (a server, CI, ssh), run
# headless and render the last frame offscreen into a PNG.
if [[ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" && -z "${HEADLESS:-}" ]]; then
  mode="viewer"
  args=(--scene "${scene}")
else
  mode="headless"
  args=(--scene "${scene}" --headless --frames "${frames}" --until-done
    --metrics "${metrics}" --export "${export_csv}" --screenshot "${picture}" --size 960x540)
fi
if [[ -n "${batch}" ]]; then
  read -r -a batch_counts <<<"${batch}"
  args+=(--batch "${batch_counts[@]}")
fi

echo
if [[ "${mode}" == "viewer" ]]; then
  echo "== ${scene}: in a window (close it or press Esc to quit; HEADLESS=1 runs without one)"
else
  echo "== ${scene}: at most ${frames} frames, headless"
fi
build/release/samples/sandphys-samples "${args[@]}" "$@"

# Paths as the user can open them, whatever directory the script was started from.
if [[ "${out_dir}" != /* ]]; then
  metrics="${repo_root}/${metrics}"
  export_csv="${repo_root}/${export_csv}"
  picture="${repo_root}/${picture}"
fi
if [[ "${mode}" == "headless" ]]; then
  echo
  echo "run-sample: wrote"
  echo "  metrics:   ${metrics}"
  echo "  granules:  ${export_csv}"
  echo "  picture:   ${picture}"
fi
