# apps-lib.sh: what tools/apps-bench.sh and tools/apps-photo.sh share (sourced, not run).
#
# The real programs come from tools/apps.list (a name, the sets it belongs to, extra
# arguments). Each run starts the program under a private Xvfb (-displayfd: the server picks
# a free display, so runs beside other people's servers do not collide) with the test-only
# shim build/tests/apps/libappshim.so preloaded, after libquadgl-preload.so when a method is
# given ("native" runs the shim alone). The shim, controlled by APPSHIM_* variables, counts
# frames, freezes time, photographs and ends the program from its own swap call.

apps_root=$(cd "$(dirname "$0")/.." && pwd)
apps_xvfb_pid=""
apps_tmp=""

# apps_init BUILD_DIR: the libraries and helpers of a build; fails when they are missing.
apps_init() {
    apps_build=$(cd "$1" && pwd) || return 1
    apps_lib="$apps_build/libquadgl/libquadgl-preload.so"
    apps_shim="$apps_build/tests/apps/libappshim.so"
    apps_diff="$apps_build/tests/apps/appdiff"
    for f in "$apps_lib" "$apps_shim" "$apps_diff"; do
        [ -f "$f" ] || { echo "apps: no $f (build first: tools/build.sh)" >&2; return 1; }
    done
    apps_tmp=$(mktemp -d "${TMPDIR:-/tmp}/quadgl-apps.XXXXXX")
    # The hacks that show images run xscreensaver-getimage from PATH, as the xscreensaver
    # daemon that starts them arranges; with a home of their own its settings are fixed:
    # colour bars, never a grab of the screen (which would hold the hack's own frames).
    mkdir "$apps_tmp/home"
    printf 'grabDesktopImages: False\nchooseRandomImages: False\n' >"$apps_tmp/home/.xscreensaver"
    apps_env="HOME=$apps_tmp/home PATH=${XSCREENSAVER_HACKS:-/usr/libexec/xscreensaver}:$PATH"
    trap apps_cleanup EXIT
    trap 'exit 130' INT TERM
}

apps_cleanup() {
    if [ -n "$apps_xvfb_pid" ]; then
        kill "$apps_xvfb_pid" 2>/dev/null || true
        wait "$apps_xvfb_pid" 2>/dev/null || true
        apps_xvfb_pid=""
    fi
    [ -n "$apps_tmp" ] && rm -rf "$apps_tmp"
    apps_tmp=""
}

# apps_xvfb WxH: starts our own Xvfb and exports DISPLAY; fails if it cannot start.
apps_xvfb() {
    command -v Xvfb >/dev/null || return 1
    : >"$apps_tmp/display"
    Xvfb -displayfd 9 -screen 0 "${1}x24" -nolisten tcp 9>"$apps_tmp/display" 2>/dev/null &
    apps_xvfb_pid=$!
    for _ in $(seq 100); do
        [ -s "$apps_tmp/display" ] && break
        kill -0 "$apps_xvfb_pid" 2>/dev/null || return 1
        sleep 0.1
    done
    [ -s "$apps_tmp/display" ] || return 1
    DISPLAY=":$(head -1 "$apps_tmp/display")"
    export DISPLAY
}

# apps_list SET|all [NAME...]: "name args" lines of the list; names given pick those lines.
# (sh has no local variables: each function's own names carry its prefix.)
apps_list() {
    al_set=$1
    shift
    grep -v '^ *#' "$apps_root/tools/apps.list" | grep . | while read -r name sets args; do
        if [ $# -gt 0 ]; then
            for want in "$@"; do
                if [ "$want" = "$name" ]; then echo "$name $args"; fi
            done
        elif [ "$al_set" = all ] || echo ",$sets," | grep -q ",$al_set,"; then
            echo "$name $args"
        fi
    done
}

# apps_in_set NAME SET: whether the list puts NAME in SET.
apps_in_set() {
    apps_list "$2" | cut -d' ' -f1 | grep -qx "$1"
}

# apps_command NAME ARGS...: the command line (glxgears from PATH, a hack from xscreensaver's
# directory, with -delay 0 so only rendering limits the frame rate), at the window size.
apps_command() {
    ac_name=$1
    shift
    if [ "$ac_name" = glxgears ]; then
        echo "glxgears -geometry $apps_size $*"
    else
        echo "${XSCREENSAVER_HACKS:-/usr/libexec/xscreensaver}/$ac_name -delay 0 -geometry $apps_size $*"
    fi
}

# apps_available NAME: whether the program is installed.
apps_available() {
    if [ "$1" = glxgears ]; then
        command -v glxgears >/dev/null
    else
        [ -x "${XSCREENSAVER_HACKS:-/usr/libexec/xscreensaver}/$1" ]
    fi
}

# apps_run METHOD ERRFILE TIMEOUT NAME ARGS...: one run with the shim, the APPSHIM_* variables
# of the caller's environment, and (unless METHOD is native) quadgl with QUADGL_STATS=1;
# stdout is dropped, stderr goes to ERRFILE; returns the program's exit status.
apps_run() {
    ar_method=$1 ar_err=$2 ar_limit=$3
    shift 3
    ar_cmd=$(apps_command "$@")
    if [ "$ar_method" = native ]; then
        # shellcheck disable=SC2086
        env -u QUADGL_METHOD -u QUADGL_STATS $apps_env LD_PRELOAD="$apps_shim" vblank_mode=0 \
            timeout -k 5 "$ar_limit" $ar_cmd </dev/null >/dev/null 2>"$ar_err"
    else
        # shellcheck disable=SC2086
        env $apps_env LD_PRELOAD="$apps_lib $apps_shim" QUADGL_METHOD="$ar_method" QUADGL_STATS=1 vblank_mode=0 \
            timeout -k 5 "$ar_limit" $ar_cmd </dev/null >/dev/null 2>"$ar_err"
    fi
}

# apps_stats ERRFILE: the last statistics line's counts as "quads mvc split subdiv passthrough",
# or nothing (children such as xscreensaver-getimage print their own, with no quads).
apps_stats() {
    sed -n 's/^quadgl: \([0-9]*\) quads: mvc=\([0-9]*\), split=\([0-9]*\), subdiv=\([0-9]*\), passthrough=\([0-9]*\).*/\1 \2 \3 \4 \5/p' \
        "$1" | sort -n | tail -1
}
