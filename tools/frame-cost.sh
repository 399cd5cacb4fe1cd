#!/bin/sh
# frame-cost.sh: what a frame of a real program costs in instructions, natively and preloaded:
# a figure the machine's load does not move, where frame rates on a shared 2-core machine do.
#
#   tools/frame-cost.sh [--build DIR] [--methods "off split"] [--frames "A B"] PROGRAM...
#
# Each program of tools/apps.list runs under callgrind and a private Xvfb at 640x480, the time
# of day and pid frozen (so every run draws the same frames), natively and under each method,
# twice: ended by the test-only shim from its swap call at frame A and at frame B (default 10
# and 50). The difference of the two runs over B - A frames is the cost of a frame without the
# start (loading, shader compilation). Two figures a frame, in millions of instructions: the
# program's own thread (its GL calls, quadgl, the driver's vertex stage and binning), and all
# other threads together (llvmpipe's rasterizer threads), which only the picture's pixels
# should move. The planner's costs are fixed (QUADGL_COSTS, unless set: this machine's
# calibration, rounded), since a calibration timed under callgrind would move `auto`'s
# choices from run to run. A program that animates by anything but the frozen time draws
# other frames under callgrind's slowness, and its figures then differ between runs ("-" where
# the later frame took fewer instructions than the earlier one).
set -eu
. "$(dirname "$0")/apps-lib.sh"

build="$apps_root/build" methods="off split" frames="10 50" apps_size=640x480
while [ $# -gt 0 ]; do
    case $1 in
    --build) build=$2; shift 2 ;;
    --methods) methods=$2; shift 2 ;;
    --frames) frames=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "frame-cost: unknown option $1" >&2; exit 2 ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || { echo "frame-cost: name the programs (tools/apps.list)" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "frame-cost: needs valgrind (tools/deps.sh)" >&2; exit 1; }
apps_init "$build"
apps_xvfb "$apps_size" || { echo "frame-cost: Xvfb cannot start" >&2; exit 1; }
first=${frames% *} last=${frames#* }
export APPSHIM_FREEZE=realtime
export QUADGL_COSTS="${QUADGL_COSTS:-713,8.79,5.69,310}"

# count NAME METHOD FRAMES: "main others" instructions of a run to that frame.
count() {
    rm -f "$apps_tmp"/cg.out*
    if [ "$2" = native ]; then pre="$apps_shim"; else pre="$apps_lib $apps_shim"; fi
    # shellcheck disable=SC2046 # the command is words
    env $apps_env LD_PRELOAD="$pre" QUADGL_METHOD="$2" APPSHIM_SHOT="$apps_tmp/shot.ppm" APPSHIM_FRAME="$3" \
        vblank_mode=0 timeout -k 5 1200 valgrind --tool=callgrind --separate-threads=yes \
        --callgrind-out-file="$apps_tmp/cg.out" $(apps_command "$1") </dev/null >/dev/null 2>&1 || true
    # thread 1 is the program's own; the files' "totals:" lines hold each thread's count
    for f in "$apps_tmp"/cg.out-*; do
        [ -f "$f" ] || continue
        t=$(awk '/^(summary|totals):/ { print $2; exit }' "$f")
        case $f in *-01) echo "main ${t:-0}" ;; *) echo "other ${t:-0}" ;; esac
    done | awk '{ s[$1] += $2 } END { printf "%d %d\n", s["main"], s["other"] }'
}

echo "planner costs (QUADGL_COSTS): $QUADGL_COSTS; frames $first to $last"
printf '| program | method | own thread, M instructions a frame | other threads | own thread over native |\n'
printf '|---|---|---:|---:|---:|\n'
for name in "$@"; do
    native=""
    for m in native $methods; do
        a=$(count "$name" "$m" "$first") b=$(count "$name" "$m" "$last")
        # fewer instructions to the later frame: the two runs drew different frames
        line=$(echo "$a $b" | awk -v n="$((last - first))" '{ if ($3 < $1 || $4 < $2) print "- -";
            else printf "%.2f %.2f", ($3 - $1) / n / 1e6, ($4 - $2) / n / 1e6 }')
        own=${line% *} other=${line#* }
        [ "$m" = native ] && native=$own
        ratio=$(awk -v o="$own" -v n="$native" 'BEGIN { if (n > 0 && o != "-") printf "%.2f", o / n; else print "-" }')
        printf '| %s | %s | %s | %s | %s |\n' "$name" "$m" "$own" "$other" "$ratio"
    done
done
