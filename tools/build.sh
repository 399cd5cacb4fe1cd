#!/bin/sh
# build.sh: configure (once) and build quadgl in ./build. Extra arguments go to meson setup.
set -eu
cd "$(dirname "$0")/.."
[ -f build/build.ninja ] || meson setup build "$@" >/dev/null
ninja -C build >/dev/null
