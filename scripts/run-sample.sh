#!/usr/bin/env bash
# The main job: installs what is missing, builds the `release` preset and runs the cylinder-pile
# scene (the paper's benchmark) headless, writing its metrics (JSON) and per-frame export (CSV)
# to out/.
# Usage: scripts/run-sample.sh [extra sandphys-samples options]
# Environment: FRAMES (default 120), SCENE (default cylinder-pile), OUT_DIR (default out).
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."
repo_root="$(pwd)"

frames="${FRAMES:-120}"
scene="${SCENE:-cylinder-pile}"
out_dir="${OUT_DIR:-out}"

scripts/install-deps.sh

cmake --preset release
cmake --build --preset release

mkdir -p -- "${out_dir}"
metrics="${out_dir}/${scene}.json"
export_csv="${out_dir}/${scene}.csv"

echo
echo "== ${scene}: ${frames} frames, headless"
build/release/samples/sandphys-samples --scene "${scene}" --headless --frames "${frames}" \
  --metrics "${metrics}" --export "${export_csv}" "$@"

# Paths as the user can open them, whatever directory the script was started from.
case "${out_dir}" in
  /*) ;;
  *) metrics="${repo_root}/${metrics}" export_csv="${repo_root}/${export_csv}" ;;
esac
echo
echo "run-sample: wrote"
echo "  metrics: ${metrics}"
echo "  export:  ${export_csv}"
