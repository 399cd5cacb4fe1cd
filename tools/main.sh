#!/bin/sh
# main.sh: the README's main job. Installs what is missing, builds, then writes to out/:
#   report.md       the weights' accuracy table, the software methods' speed-against-error
#                   table and the GL path's frame-time ratios against the native split
#   sheet.png       software methods side by side with error heat maps (scenes x methods)
#   plot.png        time against error, log-log, one panel per scene
#   drift.png       one textured planar quad from four viewpoints, screen-space against
#                   view-invariant weights, with the view drift as a heat map
#   bench.csv       one row per scene x method
#   demo/contact_sheet.png   the same scenes drawn through GL (OSMesa): native split, quadgl, reference
# and prints the report. Extra arguments go to quadgl-bench (e.g. --quick).
set -eu
cd "$(dirname "$0")/.."
tools/deps.sh
tools/build.sh
mkdir -p out
{
    echo "# quadgl report"
    echo
    echo "## Weights: accuracy on the hard-case suite"
    echo
    build/tests/core/test_weights --table
    echo
    echo "## Software methods: speed against error (one core)"
    echo
    build/demos/quadgl-bench --sheet out/sheet.png --plot out/plot.png --csv out/bench.csv \
        --drift-sheet out/drift.png "$@"
    echo
    echo "## GL path on this machine's driver: frame time against the native split"
    echo
    echo '```'
    build/demos/quadgl-glbench
    echo '```'
} >out/report.md
build/demos/quadgl-demo --headless --out out/demo >out/demo.log
cat out/report.md
echo
echo "quadgl: pictures in out/sheet.png, out/plot.png, out/drift.png and out/demo/contact_sheet.png; report in out/report.md"
