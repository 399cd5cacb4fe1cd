#!/bin/bash
# frame-time.sh: how long a real program takes to draw its first N frames, preloaded against
# native or against another build, as whole processes timed in alternate pairs.
#
#   tools/frame-time.sh [--build DIR] [--vs-build DIR] [--method M] [--frames N] [--pairs P] PROGRAM
#
# A is PROGRAM of tools/apps.list preloaded with DIR's library under QUADGL_METHOD M (default
# split); B is the same program natively, or with --vs-build the other build's library under
# the same method. Both run under a private Xvfb at 640x480 with the time of day and pid frozen
# (every run draws the same frames) and end from their own swap call at frame N (default 1200),
# through the test-only shim. The runs alternate A B A B ... P times (default 8); each pair
# gives A over B in wall time and in CPU time (user + system of the process), and the medians
# of those ratios are printed: a ratio taken pair by pair follows the machine's load, which
# moves a single run's time here by 10-20%. A frame rate hides how the program's thread,
# llvmpipe's threads and the X server overlap; the wall ratio against the CPU ratio shows it.
set -eu
. "$(dirname "$0")/apps-lib.sh"

build="$apps_root/build" vs="" method=split frames=1200 pairs=8 apps_size=640x480
while [ $# -gt 0 ]; do
    case $1 in
    --build) build=$2; shift 2 ;;
    --vs-build) vs=$2; shift 2 ;;
    --method) method=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    --pairs) pairs=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "frame-time: unknown option $1" >&2; exit 2 ;;
    *) break ;;
    esac
done
[ $# -eq 1 ] || { echo "frame-time: name one program (tools/apps.list)" >&2; exit 2; }
prog=$1
if [ -n "$vs" ]; then
    vs_lib="$(cd "$vs" && pwd)/libquadgl/libquadgl-preload.so"
    [ -f "$vs_lib" ] || { echo "frame-time: no $vs_lib" >&2; exit 1; }
fi
apps_init "$build"
apps_xvfb "$apps_size" || { echo "frame-time: Xvfb cannot start" >&2; exit 1; }
apps_available "$prog" || { echo "frame-time: $prog is not installed" >&2; exit 1; }
own_lib=$apps_lib
export APPSHIM_FREEZE=realtime APPSHIM_SHOT="$apps_tmp/shot.ppm" APPSHIM_FRAME=$frames

# Times one run: "wall cpu" in seconds; the run's method, or native.
timed() {
    local TIMEFORMAT='%R %U %S' t
    t=$({ time apps_run "$1" "$apps_tmp/err" 600 "$prog"; } 2>&1) ||
        { echo "frame-time: $prog failed ($1): $(tail -n 3 "$apps_tmp/err")" >&2; exit 1; }
    echo "$t" | awk '{ print $1, $2 + $3 }'
}

walls="" cpus=""
for i in $(seq "$pairs"); do
    apps_lib=$own_lib
    a=$(timed "$method")
    if [ -n "$vs" ]; then
        apps_lib=$vs_lib
        b=$(timed "$method")
    else
        b=$(timed native)
    fi
    r=$(echo "$a $b" | awk '{ printf "%.4f %.4f", $1 / $3, $2 / $4 }')
    echo "pair $i: A $a, B $b, A/B wall and CPU $r"
    walls="$walls ${r% *}" cpus="$cpus ${r#* }"
done
median() { echo "$@" | tr ' ' '\n' | sed '/^$/d' | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
echo "$prog, $frames frames, $method $( [ -n "$vs" ] && echo "against $vs" || echo "against native"), $pairs pairs:" \
    "median A/B wall $(median $walls), CPU $(median $cpus)"
