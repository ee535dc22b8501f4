#!/usr/bin/env bash
# The main job: installs what is missing, builds the `release` preset and runs the cylinder-pile
# scene (the paper's benchmark) headless until its batch has settled, writing the run's metrics
# (JSON) and the granules at the end (CSV) to out/.
# Usage: scripts/run-sample.sh [extra sandphys-samples options]
# Environment:
#   FRAMES   most frames of 1/60 s to run (default 150; the run stops earlier once settled)
#   BATCH    cylinder-pile granules per batch "X Y Z" (default "8 4 8", 256 granules, a few
#            minutes on llvmpipe with 2 cores; BATCH= uses the scene's own 32 16 32)
#   SCENE    scene to run (default cylinder-pile; `sandphys-samples --list` shows them)
#   OUT_DIR  where the outputs go (default out, in the repository)
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

args=(--scene "${scene}" --headless --frames "${frames}" --until-done
  --metrics "${metrics}" --export "${export_csv}")
if [[ -n "${batch}" ]]; then
  read -r -a batch_counts <<<"${batch}"
  args+=(--batch "${batch_counts[@]}")
fi

echo
echo "== ${scene}: at most ${frames} frames, headless"
build/release/samples/sandphys-samples "${args[@]}" "$@"

# Paths as the user can open them, whatever directory the script was started from.
if [[ "${out_dir}" != /* ]]; then
  metrics="${repo_root}/${metrics}"
  export_csv="${repo_root}/${export_csv}"
fi
echo
echo "run-sample: wrote"
echo "  metrics:   ${metrics}"
echo "  granules:  ${export_csv}"
