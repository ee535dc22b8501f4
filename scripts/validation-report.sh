#!/usr/bin/env bash
# The validation report in one command: installs what is missing (and python3-matplotlib),
# builds sandphys-validation with the `release` preset, runs the paper's validation experiments
# headless into build/validation/results.json, then draws the plots and writes
# docs/validation/README.md from them (scripts/validation/make_report.py), with the measurements
# beside it (docs/validation/results.json).
# Usage: scripts/validation-report.sh [sandphys-validation options, e.g. --heap-granules 800,
# given to both runs; not --contact-law or --only]
# (sandphys-validation --help lists them; on 2 cores without a GPU the defaults take about two
# hours, the paper's law's sweeps about one more).
set -euo pipefail

cd -- "$(dirname -- "${BASH_SOURCE[0]}")/.."

scripts/install-deps.sh python3-matplotlib
cmake --preset release
cmake --build --preset release --target sandphys-validation
build/release/samples/sandphys-validation --out build/validation/results.json "$@"
# The angle-of-repose sweeps again under the paper's law, shown beside the default law's.
build/release/samples/sandphys-validation --out build/validation/results-paper-law.json \
  --only repose,repose-scupper --contact-law paper "$@"
# Debian's Python, where apt installed matplotlib (a python3 earlier in PATH, from pyenv or a
# virtualenv, may not have it).
python=/usr/bin/python3
[[ -x "${python}" ]] || python=python3
"${python}" scripts/validation/make_report.py build/validation/results.json docs/validation \
  build/validation/results-paper-law.json
# The measurements go with the report, so that make_report.py can redraw it without a rerun.
cp build/validation/results.json build/validation/results-paper-law.json docs/validation/
