#!/bin/sh
# main.sh: the README's main job. Installs what is missing, builds, renders the comparison
# pictures and writes the speed/error report to out/, then prints the report.
set -eu
cd "$(dirname "$0")/.."
tools/deps.sh
tools/build.sh
mkdir -p out
build/tests/core/test_weights --table >out/accuracy.md
cat out/accuracy.md
