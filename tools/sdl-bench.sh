#!/bin/sh
# sdl-bench.sh: an SDL2 game, Debian's chromium-bsu, under `off` and `auto`: frames, page faults, memory.
#
#   tools/sdl-bench.sh [--build DIR] [--seconds S] [--reps N]
#
# SDL and GLEW find their functions through glXGetProcAddress, and SDL takes glXSwapBuffers
# from its own dlopen of libGL, so the test-only shim alone (the bench's native run) never
# sees a swap: `off`, quadgl passing every call on, stands for native here. Each run is the
# game's menu under a private Xvfb at 800x600 for S seconds (default 4) of frames counted by
# the shim (time of day and pid frozen, as tools/apps-bench.sh does), `off` and `auto`
# alternating N times (default 3). Per run: frames, the process's minor page faults (its
# heap faulted in again shows there), VmRSS at the end and the draws on quadgl's statistics
# line. Installs chromium-bsu when it is missing (as root, or with sudo).
set -eu
. "$(dirname "$0")/apps-lib.sh"

build="$apps_root/build" secs=4 reps=3 game=/usr/games/chromium-bsu
while [ $# -gt 0 ]; do
    case $1 in
    --build) build=$2; shift 2 ;;
    --seconds) secs=$2; shift 2 ;;
    --reps) reps=$2; shift 2 ;;
    -h|--help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "sdl-bench: unknown option $1" >&2; exit 2 ;;
    esac
done
if [ ! -x "$game" ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends chromium-bsu >/dev/null
fi
apps_init "$build"
apps_xvfb 800x600 || { echo "sdl-bench: Xvfb cannot start" >&2; exit 1; }

# run METHOD: one run; prints "frames faults rss_kib draws" ("-" for what did not come).
# Only the game is preloaded: python3 around it counts its page faults.
run() {
    # shellcheck disable=SC2086
    env $apps_env SDL_AUDIODRIVER=dummy APPSHIM_FREEZE=realtime APPSHIM_SECONDS="$secs" QUADGL_METHOD="$1" \
        QUADGL_STATS=1 vblank_mode=0 python3 -c 'import os, resource, subprocess, sys
env = dict(os.environ, LD_PRELOAD=sys.argv[1])
subprocess.run(sys.argv[2:], env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, timeout=120)
print("faults", resource.getrusage(resource.RUSAGE_CHILDREN).ru_minflt, file=sys.stderr)' \
        "$apps_lib $apps_shim" "$game" 2>"$apps_tmp/err" || true
    awk '/^[0-9]+ [0-9.]+ [0-9]+ / { frames = $1; rss = $3 } /^faults / { faults = $2 }
         /^quadgl: [0-9]+ quads:.* draws=/ { d = $0; sub(/.* draws=/, "", d); sub(/,.*/, "", d); draws = d }
         END { printf "%s %s %s %s\n", frames == "" ? "-" : frames, faults == "" ? "-" : faults, rss == "" ? "-" : rss,
               draws == "" ? "-" : draws }' "$apps_tmp/err"
}

echo "| run | method | frames in $secs s | page faults | VmRSS KiB | draws |"
echo "|---|---|---:|---:|---:|---:|"
k=1
while [ "$k" -le "$reps" ]; do
    for m in off auto; do
        # shellcheck disable=SC2046 # the four fields, split on purpose
        set -- $(run "$m")
        echo "| $k | $m | $1 | $2 | $3 | $4 |"
    done
    k=$((k + 1))
done
