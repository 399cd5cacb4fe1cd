#!/bin/sh
# quadgl-preload-bench.sh: what libquadgl-preload.so costs a real program, side by side.
#
#   tools/quadgl-preload-bench.sh [BUILD_DIR (default build)] [SECONDS per glxgears run (default 11)]
#
# 1. glxgears frames per second under Xvfb with vsync off (vblank_mode=0): native, then
#    preloaded with QUADGL_METHOD=off, replay, split and auto (the target: auto >= 0.9x
#    native). The figure is glxgears' own 5-second report (the last complete one).
# 2. Immediate-mode cost per vertex (quadgl-preload-bench: 1M vertices of small quads per
#    frame, glBegin/glEnd with a colour per vertex), native and preloaded per method
#    (target: <= 1.3x native); then the same quads one per glBegin/glEnd (200k vertices).
set -eu
build=${1:-build}
secs=${2:-11}
lib="$(cd "$build" && pwd)/libquadgl/libquadgl-preload.so"
bench="$build/tests/preload/quadgl-preload-bench"
[ -f "$lib" ] || { echo "no $lib: build first" >&2; exit 1; }

echo "glxgears frames per second (Xvfb, llvmpipe, vblank_mode=0, ${secs}s runs)"
if command -v glxgears >/dev/null && command -v xvfb-run >/dev/null; then
    export lib secs
    xvfb-run -a -s "-screen 0 640x480x24" sh -c '
        gears_fps() { # $1: LD_PRELOAD value (empty: native), $2: method
            { LD_PRELOAD="$1" QUADGL_METHOD="$2" vblank_mode=0 timeout "$secs" glxgears 2>/dev/null || true; } |
                sed -n "s/.*= \([0-9.]*\) FPS.*/\1/p" | tail -1
        }
        native=$(gears_fps "" off)
        printf "  %-8s %8s FPS\n" native "$native"
        for m in off replay split auto; do
            fps=$(gears_fps "$lib" $m)
            printf "  %-8s %8s FPS  %s x native\n" "$m" "$fps" \
                "$(awk -v a="$fps" -v b="$native" "BEGIN { if (b > 0) printf \"%.2f\", a / b; else print \"?\" }")"
        done' || echo "  (Xvfb failed)"
else
    echo "  (glxgears or xvfb-run missing: skipped)"
fi

# immediate TITLE ARGS...: ns per vertex natively and per method, ARGS passed to the bench
immediate() {
    echo "$1"
    shift
    native=$("$bench" "$@" | sed -n 's/.* \([0-9.]*\) ns per vertex.*/\1/p')
    printf "  %-8s %8s ns/vertex\n" native "$native"
    for m in off replay split auto mvc; do
        ns=$(LD_PRELOAD="$lib" QUADGL_METHOD=$m "$bench" "$@" | sed -n 's/.* \([0-9.]*\) ns per vertex.*/\1/p')
        printf "  %-8s %8s ns/vertex  %s x native\n" "$m" "$ns" \
            "$(awk -v a="$ns" -v b="$native" 'BEGIN { if (b > 0) printf "%.2f", a / b; else print "?" }')"
    done
}
immediate "immediate mode, 1M vertices per frame in one glBegin/glEnd (OSMesa, 256x256)"
# the per-primitive cost: text, tiles and facets are drawn a quad per glBegin/glEnd
immediate "immediate mode, 200k vertices per frame, one quad per glBegin/glEnd" 200000 15 1
