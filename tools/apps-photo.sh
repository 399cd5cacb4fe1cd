#!/bin/sh
# apps-photo.sh: real programs photographed deterministically, preloaded and natively.
#
#   tools/apps-photo.sh [--build DIR] [--out DIR] [--frame N] [--size WxH]
#                       [--methods "off replay split auto mvc"] [--set NAME|all] [--keep] [PROGRAM...]
#
# Each program of tools/apps.list (all of them by default, or the set or programs named) runs
# under a private Xvfb with the test-only shim, which freezes time (gettimeofday, time and
# clock_gettime start at a fixed instant and advance a fixed step per swap), returns a
# constant getpid (the xscreensaver hacks seed their random numbers from both) and reads the
# back buffer at swap N (default 20) from its own swap wrapper. Two native runs come first
# and must be identical, else the program is skipped as not deterministic; when a check
# fails, up to three more native runs after the others must match too (a picture that drifts
# with the machine's timing, an image loaded by a child process say, is not judged); a
# program the list marks unsteady is skipped without running. Then, against
# the native picture: `off` and `replay` must be identical (no pixel differs at all), `split`
# must differ by at most 2 levels everywhere, and `auto` and `mvc` may differ by more than 2
# levels only inside the quads quadgl drew smooth: the shim also draws, at the photographed
# frame, every draw quadgl's shader path makes (the only GL_LINES_ADJACENCY draws) into a
# mask of its own, with the footprint either of the driver's splits would give the same
# quads (a concave quad's notch, the boundary pixels one split's triangles round in), and the
# pixels over 2 levels outside that mask must be 0, or at most the bound tools/apps-known.txt
# gives with its reason. (Quads the CPU fallback subdivides are not in the mask; the table
# shows their count under `auto`.)
#
# Writes OUT/apps-photo.md (the table), OUT/apps-photo.csv and, per program, OUT/apps-photo/NAME/
# with native.png and, for every mode that differs (every mode with --keep), the picture,
# a heat map of the difference against native (blue 1 level to white 128, the mask tinted
# green) and the mask. Prints the table and "N passed, N failed, N skipped" (checks); exits
# 1 if a check failed, 77 if Xvfb or every program is missing or nothing could be checked.
set -eu
. "$(dirname "$0")/apps-lib.sh"

build="$apps_root/build" out="$apps_root/out" frame=20 apps_size=640x480
methods="off replay split auto mvc" set=all keep=0
while [ $# -gt 0 ]; do
    case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --frame) frame=$2; shift 2 ;;
    --size) apps_size=$2; shift 2 ;;
    --methods) methods=$2; shift 2 ;;
    --set) set=$2; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "apps-photo: unknown option $1" >&2; exit 2 ;;
    *) break ;;
    esac
done
apps_init "$build"
apps_xvfb "$apps_size" || { echo "apps-photo: Xvfb cannot start: skipped" >&2; exit 77; }
mkdir -p "$out/apps-photo"
export APPSHIM_FREEZE=1 APPSHIM_FRAME="$frame"

# png PPM PNG: the picture as PNG (kept as PPM without oiiotool).
png() {
    if command -v oiiotool >/dev/null; then
        oiiotool "$1" -o "$2" && rm -f "$1"
    else
        mv "$1" "${2%.png}.ppm"
    fi
}

# shot NAME MODE: photographs one run into $tmp/MODE.ppm (and MODE-mask.ppm for the smooth
# modes); prints the exit status.
shot() {
    rm -f "$tmp/$2.ppm" "$tmp/$2-mask.ppm"
    mode=$2
    case $mode in native*) mode=native ;; esac
    if [ "$mode" = auto ] || [ "$mode" = mvc ] || [ "$mode" = mvcplane ]; then
        export APPSHIM_MASK="$tmp/$2-mask.ppm"
    else
        unset APPSHIM_MASK
    fi
    rc=0
    # shellcheck disable=SC2086 # the list's arguments are words
    APPSHIM_SHOT="$tmp/$2.ppm" apps_run "$mode" "$tmp/$2.err" 120 "$1" $args || rc=$?
    [ $rc -eq 0 ] && [ ! -s "$tmp/$2.ppm" ] && rc=99
    echo $rc
}

passed=0 failed=0 skipped=0 found=0 failures="" knowns=""
# known NAME MODE: the bound tools/apps-known.txt gives the pixels outside the mask, if any.
known() {
    grep -v '^ *#' "$apps_root/tools/apps-known.txt" | awk -v n="$1" -v m="$2" '$1 == n && $2 == m { print $3; exit }'
}
csv="$out/apps-photo.csv"
echo "program,mode,exit,over2,max,differ,outside_mask,result,quads,mvc,split,subdiv,passthrough" >"$csv"
with_auto=0
case " $methods " in *" auto "*) with_auto=1 ;; esac
header="| program | native x2" rule="|---|---:"
for m in $methods; do header="$header | $m" rule="$rule|---:"; done
[ "$with_auto" = 1 ] && header="$header | auto: quads mvc/split/subdiv/pass" rule="$rule|---"
printf '%s |\n%s|\n' "$header" "$rule" >"$out/apps-photo.md"
start=$(date +%s)
apps_list "$set" "$@" >"$apps_tmp/list"
while read -r name args; do
    apps_available "$name" || { echo "apps-photo: $name is not installed: skipped" >&2; continue; }
    found=$((found + 1))
    if apps_in_set "$name" unsteady; then
        skipped=$((skipped + 1))
        echo "| $name | unsteady in tools/apps.list: skipped |" >>"$out/apps-photo.md"
        echo "$name,native2,,,,,,nondeterministic,,,,," >>"$csv"
        echo "$name: its pictures differ between native runs (tools/apps.list): skipped" >&2
        continue
    fi
    tmp="$apps_tmp/$name" dir="$out/apps-photo/$name"
    mkdir -p "$tmp" "$dir"
    rm -f "$dir"/*.png "$dir"/*.ppm
    row="| $name"
    rc1=$(shot "$name" native) rc2=$(shot "$name" native2)
    if [ "$rc1" != 0 ] || [ "$rc2" != 0 ]; then
        row="$row | exit $rc1/$rc2 FAIL"
        failed=$((failed + 1)) failures="$failures $name:native"
        echo "$name,native,$rc1/$rc2,,,,,fail,,,,," >>"$csv"
        echo "$row |" >>"$out/apps-photo.md"
        continue
    fi
    # shellcheck disable=SC2046 # appdiff prints four numbers
    set -- $("$apps_diff" "$tmp/native.ppm" "$tmp/native2.ppm")
    cp "$tmp/native.ppm" "$tmp/keep.ppm"
    png "$tmp/keep.ppm" "$dir/native.png"
    echo "$name,native2,0,$1,$2,$3,,$([ "$3" = 0 ] && echo pass || echo nondeterministic),,,,," >>"$csv"
    if [ "$3" != 0 ]; then
        row="$row | $1/$2, not deterministic: skipped"
        skipped=$((skipped + 1))
        mv "$tmp/native2.ppm" "$tmp/n2.ppm" && png "$tmp/n2.ppm" "$dir/native2.png"
        echo "$row |" >>"$out/apps-photo.md"
        echo "$name: not deterministic natively ($3 pixels differ, max $2): skipped" >&2
        continue
    fi
    row="$row | 0"
    stats="" p_passed=0 p_failed=0 p_failures=""
    for m in $methods; do
        rc=$(shot "$name" "$m")
        st=$(apps_stats "$tmp/$m.err")
        [ "$m" = auto ] && stats=$st
        if [ "$rc" != 0 ]; then
            row="$row | exit $rc FAIL"
            p_failed=$((p_failed + 1)) p_failures="$p_failures $name:$m"
            echo "$name,$m,$rc,,,,,fail,$(echo "$st" | tr ' ' ,)" >>"$csv"
            continue
        fi
        mask=-
        [ -f "$tmp/$m-mask.ppm" ] && mask="$tmp/$m-mask.ppm"
        # shellcheck disable=SC2046
        set -- $("$apps_diff" "$tmp/native.ppm" "$tmp/$m.ppm" "$mask" "$tmp/$m-diff.ppm")
        case $m in
        off|replay) ok=$([ "$3" = 0 ] && echo 1 || echo 0); cell="$3/$2" ;;
        split) ok=$([ "$1" = 0 ] && echo 1 || echo 0); cell="$1/$2" ;;
        *) ok=$([ "$4" = 0 ] && echo 1 || echo 0); cell="$1 ($4 outside)/$2"
           bound=$([ "$ok" = 1 ] || known "$name" "$m")
           if [ -n "$bound" ] && [ "$4" -le "$bound" ]; then
               ok=1 cell="$cell known" knowns="$knowns $name:$m"
           fi ;;
        esac
        [ "$3" = 0 ] && cell=0
        if [ "$ok" = 1 ]; then
            p_passed=$((p_passed + 1))
        else
            p_failed=$((p_failed + 1)) p_failures="$p_failures $name:$m"
            cell="$cell FAIL"
        fi
        row="$row | $cell"
        echo "$name,$m,0,$1,$2,$3,$([ "$mask" = - ] || echo "$4"),$([ "$ok" = 1 ] && echo pass || echo fail),$(echo "$st" | tr ' ' ,)" >>"$csv"
        if [ "$3" != 0 ] || [ "$keep" = 1 ]; then
            png "$tmp/$m.ppm" "$dir/$m.png"
            png "$tmp/$m-diff.ppm" "$dir/$m-diff.png"
            [ "$mask" = - ] || png "$mask" "$dir/$m-mask.png"
        fi
    done
    [ "$with_auto" = 1 ] && row="$row | $(echo "$stats" | awk '{ if (NF) printf "%s: %s/%s/%s/%s", $1, $2, $3, $4, $5 }')"
    # Native runs after the others (up to three: a program with several outcomes can match
    # twice by chance): a program whose pictures drift with the machine's timing (an image
    # loaded by a child process, say) is caught here too, and not judged.
    n=0
    while [ "$p_failed" -gt 0 ] && [ $n -lt 3 ]; do
        n=$((n + 1))
        rc3=$(shot "$name" native3)
        # shellcheck disable=SC2046
        set -- $([ "$rc3" = 0 ] && "$apps_diff" "$tmp/native.ppm" "$tmp/native3.ppm")
        if [ "${3:-1}" != 0 ]; then
            row="$row | a later native run differs (${1:-?}/${2:-?}): not deterministic, not counted"
            echo "$name,native3,$rc3,${1:-},${2:-},${3:-},,nondeterministic,,,,," >>"$csv"
            echo "$name: a later native run differs: not deterministic, not counted" >&2
            skipped=$((skipped + 1)) p_passed=0 p_failed=0 p_failures=""
        fi
    done
    passed=$((passed + p_passed)) failed=$((failed + p_failed)) failures="$failures$p_failures"
    echo "$row |" >>"$out/apps-photo.md"
    echo "apps-photo: $name done" >&2
done <"$apps_tmp/list"
[ "$found" -gt 0 ] || { echo "apps-photo: no program installed: skipped" >&2; exit 77; }
[ $((passed + failed)) -gt 0 ] || { echo "apps-photo: nothing checked (no deterministic program): skipped" >&2; exit 77; }
{
    echo
    echo "Frame $frame at $apps_size, time frozen. Cells: pixels over 2 levels / largest difference"
    echo "against native (0: identical; off and replay: pixels differing at all). off, replay:"
    echo "identical required; split: no pixel over 2 levels; auto, mvc: no pixel over 2 levels outside"
    echo "the mask of the quads quadgl drew on its shader path (in brackets)."
    echo
    echo "$passed passed, $failed failed, $skipped skipped (not deterministic) in $(($(date +%s) - start)) s"
    [ -z "$failures" ] || echo "failed:$failures"
    [ -z "$knowns" ] || echo "passed within a known, bounded difference (tools/apps-known.txt):$knowns"
} >>"$out/apps-photo.md"
cat "$out/apps-photo.md"
[ "$failed" -eq 0 ]
