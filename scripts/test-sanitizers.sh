#!/usr/bin/env bash
# Builds the CPU-side test suites with AddressSanitizer and UndefinedBehaviorSanitizer (float-cast-
# overflow included; any report fails the test) and runs them: the unit tests (the recording file
# among them), the mesh tests (loading, sampling, sampled bodies in a World on llvmpipe) and the
# corpus tests (every model of assimp-testmodels, damaged recordings). Not part of CI's run: it
# is a second, Debug build; run it after a change to input handling.
# Usage: scripts/test-sanitizers.sh [extra ctest arguments]
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."
scripts/install-deps.sh
cmake --preset asan -DSANDPHYS_SAMPLES=OFF -DSANDPHYS_BENCH=OFF -DSANDPHYS_BULLET=OFF
cmake --build --preset asan --target unit_test mesh_test mesh_world_test corpus_test mesh_probe
ctest --preset asan --parallel "${CTEST_PARALLEL_LEVEL:-$(nproc)}" -L '^(unit|mesh|corpus)$' "$@"
