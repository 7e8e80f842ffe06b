#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build, and render the paper's Figure 1 scene to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/dicsynth render scenes/figure1.lua -o out
echo "dicsynth: built; the Python module: PYTHONPATH=$PWD/build /usr/bin/python3 -c 'import dicsynth'" >&2
