#!/bin/sh
# conformance.sh: does a legacy GL program see any difference with libquadgl-preload.so, other
# than smoother quads? Runs Debian's piglit tests chosen by tools/piglit-tests.txt natively and
# preloaded (QUADGL_METHOD auto, mvc and split) under Xvfb through tools/piglit.py: every test
# that passes natively must pass preloaded (a failure is run again once before it counts). Then,
# when present, the real-program photographs (tools/apps-photo.sh, see the hook below). Prints
# one row per test (native, then each method) and ends with "N passed, N failed".
#
#   tools/conformance.sh [--ci] [--piglit-only] [--methods auto,mvc,split] [--jobs N]
#                        [--filter REGEX] [--timeout SECONDS] [--lib PATH [--preload-first PATH]]
#
#   --ci            only the fixed subset of the list marked "ci" (what .ci/run runs)
#   --piglit-only   skip the real-program photographs
#   --lib           another build of the library (default build/libquadgl/libquadgl-preload.so)
#   --preload-first a library to preload before it: a sanitizer build's runtime, as .ci/run
#                   does with "$(gcc -print-file-name=libasan.so)"
#
# Writes out/conformance/: table.txt, results.json and logs/ (the output of every run that did
# not pass). The whole list takes about an hour on a shared 2-core machine; --ci about ten
# minutes (README, "Conformance").
set -eu
cd "$(dirname "$0")/.."
ci="" apps=1 methods=auto,mvc,split jobs=$(nproc) filter="" timeout=300
lib=build/libquadgl/libquadgl-preload.so first=""
while [ $# -gt 0 ]; do
    case "$1" in
    --ci) ci=--ci ;;
    --piglit-only) apps=0 ;;
    --methods) methods=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --filter) filter=$2; shift ;;
    --timeout) timeout=$2; shift ;;
    --lib) lib=$2; shift ;;
    --preload-first) first=$2; shift ;;
    *) echo "usage: $0 [--ci] [--piglit-only] [--methods M,M] [--jobs N] [--filter REGEX] [--timeout S]" \
            "[--lib PATH [--preload-first PATH]]" >&2; exit 2 ;;
    esac
    shift
done
tools/deps.sh
tools/build.sh
out=out/conformance
rm -rf "$out"
mkdir -p "$out/logs"
status=0
passed=0
failed=0

if [ ! -d /usr/lib/x86_64-linux-gnu/piglit/bin ]; then
    echo "conformance: piglit is not installed (tools/packages.txt lists it)" >&2
    exit 1
fi
# One Xvfb for the whole run (-a: a free display); the tests that piglit runs concurrently
# draw into their own framebuffer objects, the others one at a time into the window.
xvfb-run -a -s "-screen 0 1024x768x24 -nolisten tcp" \
    python3 tools/piglit.py --lib "$lib" ${first:+--preload-first "$first"} --methods "$methods" \
    --jobs "$jobs" --timeout "$timeout" ${filter:+--filter "$filter"} $ci \
    --logs "$out/logs" --json "$out/results.json" >"$out/table.txt" || status=$?
cat "$out/table.txt"
line=$(tail -n 1 "$out/table.txt")
case "$line" in
*" passed, "*" failed") passed=${line%% passed*}; failed=${line#*passed, }; failed=${failed%% failed*} ;;
*) echo "conformance: the piglit run did not finish (status $status)" >&2; failed=$((failed + 1)) ;;
esac

# Hook: the real-program photographs. tools/apps-photo.sh, when it exists and is executable,
# is run with no arguments after piglit; it is expected to end its output with a line
# "N passed, N failed" (as this script does) and to exit non-zero when something failed. Its
# counts join the totals; without such a line its exit status counts as one pass or failure.
if [ "$apps" = 1 ] && [ -x tools/apps-photo.sh ]; then
    echo
    echo "== real programs (tools/apps-photo.sh)"
    astatus=0
    tools/apps-photo.sh >"$out/apps-photo.txt" 2>&1 || astatus=$?
    cat "$out/apps-photo.txt"
    aline=$(grep -E '^[0-9]+ passed, [0-9]+ failed' "$out/apps-photo.txt" | tail -n 1 || true)
    if [ -n "$aline" ]; then
        ap=${aline%% passed*}
        af=${aline#*passed, }
        af=${af%% failed*}
        passed=$((passed + ap))
        failed=$((failed + af))
    elif [ "$astatus" = 0 ]; then
        passed=$((passed + 1))
    else
        failed=$((failed + 1))
    fi
    [ "$astatus" = 0 ] || status=1
fi

echo
echo "$passed passed, $failed failed"
[ "$failed" = 0 ] && [ "$status" = 0 ]
