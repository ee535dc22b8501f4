#!/usr/bin/env bash
# The main job: installs what is missing, builds the `release` preset and runs the cylinder-pile
# scene (the paper's benchmark). With a display it opens the viewer. Without one it runs headless
# until the batch has settled and writes the run's metrics (JSON), the granules at the end (CSV)
# and a picture of the last frame, rendered offscreen (PNG), to out/.
# Usage: scripts/run-sample.sh [extra sandphys-samples options]
# Environment:
#   FRAMES   most frames of 1/60 s to run (default 150; the run stops earlier once settled)
#   BATCH    cylinder-pile granules per batch "X Y Z" (default "8 4 8", 256 granules, a few
#            minutes on llvmpipe with 2 cores; BATCH= uses the scene's own 32 16 32)
#   SCENE    scene to run (default cylinder-pile; `sandphys-samples --list` shows them)
#   OUT_DIR  where the outputs go (default out, in the repository)
#   HEADLESS set to anything: run headless (and write the PNG) even with a display
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."
repo_root="$(pwd)"

scene="${SCENE:-cylinder-pile}"
frames="${FRAMES:-150}"
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
    --metrics "${metrics}" --export "${export_csv}" --screenshot "${picture}")
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
