#!/usr/bin/env bash
# Installs what is missing, builds with the `ci` preset (warnings are errors) and runs every
# test on whatever OpenGL 4.5 device EGL finds (Mesa's llvmpipe on a machine without a GPU),
# then fails if any C++ file needs clang-format or README.md no longer quotes
# samples/hello_sand/main.cpp verbatim. This is what CI runs (.ci/run).
# Usage: scripts/test.sh [extra ctest arguments, e.g. -L physics]
# CTEST_PARALLEL_LEVEL sets how many tests run at once (default: the number of CPUs).
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."

phase() {
  echo
  echo "== $* ($((SECONDS / 60))m$((SECONDS % 60))s)"
}

phase "dependencies"
scripts/install-deps.sh

# Source checks first because they are quick; a failure is reported again at the end, so that
# one run shows both the test results and what to fix.
phase "source checks"
checks_failed=()
scripts/check-format.sh || checks_failed+=("scripts/check-format.sh --fix")
scripts/check-readme.sh || checks_failed+=("scripts/check-readme.sh --fix")

phase "configure (preset ci)"
cmake --preset ci

phase "build (preset ci)"
cmake --build --preset ci

phase "test (preset ci)"
ctest --preset ci --parallel "${CTEST_PARALLEL_LEVEL:-$(nproc)}" "$@"

phase "done"
if ((${#checks_failed[@]} > 0)); then
  echo "test: every test passed, but the source checks above failed; fix with:" >&2
  printf '  %s\n' "${checks_failed[@]}" >&2
  exit 1
fi
echo "test: every test passed"
