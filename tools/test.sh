#!/bin/sh
# test.sh: the README's test command. Installs what is missing, builds, runs every meson test
# suite (core, render, gl, apps, preload, demo) and ends with "N passed, N failed, N skipped".
set -eu
cd "$(dirname "$0")/.."
tools/deps.sh
tools/build.sh
status=0
meson test -C build --print-errorlogs --num-processes 2 "$@" >build/test-output.txt 2>&1 || status=$?
grep -E "^ *[0-9]+/[0-9]+ " build/test-output.txt || cat build/test-output.txt
python3 tools/summary.py build/meson-logs/testlog.json
exit $status
