#!/bin/sh
# apps-bench.sh: what libquadgl-preload.so costs real programs, each against itself native.
#
#   tools/apps-bench.sh [--build DIR] [--out DIR] [--seconds S] [--reps N] [--size WxH]
#                       [--methods "off replay split auto"] [--mvc] [--set NAME|all] [--all]
#                       [--quick] [--memory] [--no-freeze] [PROGRAM...]
#
# Every program of tools/apps.list's `bench` set (--all: the whole list; or the programs
# named) runs under a private Xvfb at 640x480, natively and preloaded with each method, for S
# seconds (default 4) of frames counted from its first swap by the test-only shim, which ends
# the program from its own swap call (so quadgl's statistics line prints). The time of day
# and the pid are frozen (APPSHIM_FREEZE=realtime: the hacks seed their random numbers from
# them and animate by the time of day, which then advances 40 ms per frame), so every run of
# a program draws the same sequence of frames and a ratio compares the same work; the driver
# and quadgl still see real time on CLOCK_MONOTONIC. Runs of one program are interleaved
# (native, off, replay, split, auto, then again in an order rotated by one), N times
# (default 3); a cell is the median frame rate of its runs and its ratio is to the native
# median of the same bench run, so the machine's load drifts into both alike; "spread" is
# the fastest native run over the slowest, the noise a ratio has to be read against. The
# statistics line of the last `auto` run shows which path the program's quads took (mvc:
# the shader path, subdiv: the grid or CPU fallback); a program is "split" when no quad took
# a smooth path and "smooth" when most did. The column "auto, CPU" is the same ratio in
# frames per second of the process's own CPU time, which other load on the machine moves
# less (it leaves out the X server's work and the time spent waiting for it). "longest frame"
# is the longest time between two swaps of a run, "first frame" the time from the program's
# start to the end of its first swap (loading, quadgl's calibration and first shaders), each
# the median over the runs, natively and under auto: a stall or a slow start is what a user
# notices that a frame rate hides. --mvc adds the
# mvc column; --quick is --seconds 2 --reps 1. Targets printed against `auto`: every "split"
# program >= 0.97x, the median >= 0.98x, none below 0.9x, "smooth" programs >= 0.9x; each
# program below 0.9x gets a line on why, from the run's own figures: the share of its quads that
# took a smooth path, its `split` and `off` ratios (quadgl's cost without smooth quads, and of
# passing calls through) and the native spread.
#
# --memory: the resident size instead (VmRSS at the end of a 30-second run, native and
# auto, one run each unless told; the time of day and pid frozen as for frame rates, so that
# both runs draw the same scene: engine, for one, picks its engine at random, and sonar aborts
# on the frozen clock, natively too): target within 10% of native. --no-freeze: real time
# always.
#
# Writes OUT/apps-bench.md (table), OUT/apps-bench.csv (one row per run), OUT/apps-bench.png
# (the ratio per program and method; needs gnuplot), or OUT/apps-memory.md and .csv.
set -eu
. "$(dirname "$0")/apps-lib.sh"

build="$apps_root/build" out="$apps_root/out" secs=4 reps=3 apps_size=640x480
methods="off replay split auto" set=bench memory=0 methods_given=0 reps_given=0 freeze=realtime
while [ $# -gt 0 ]; do
    case $1 in
    --build) build=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --seconds) secs=$2; shift 2 ;;
    --reps) reps=$2; reps_given=1; shift 2 ;;
    --size) apps_size=$2; shift 2 ;;
    --methods) methods=$2; methods_given=1; shift 2 ;;
    --mvc) methods="$methods mvc"; shift ;;
    --set) set=$2; shift 2 ;;
    --all) set=all; shift ;;
    --quick) secs=2 reps=1 reps_given=1; shift ;;
    --memory) memory=1 secs=30; shift ;;
    --no-freeze) freeze=0; shift ;;
    -h|--help) sed -n '2,/^set -eu/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) echo "apps-bench: unknown option $1" >&2; exit 2 ;;
    *) break ;;
    esac
done
if [ "$memory" = 1 ]; then
    [ "$methods_given" = 1 ] || methods=auto
    [ "$reps_given" = 1 ] || reps=1
    base=apps-memory
else
    base=apps-bench
fi
apps_init "$build"
apps_xvfb "$apps_size" || { echo "apps-bench: Xvfb cannot start" >&2; exit 1; }
mkdir -p "$out"
export APPSHIM_FREEZE=$freeze
cells="native $methods"
ncells=$(echo "$cells" | wc -w)
csv="$out/$base.csv"
echo "program,method,run,exit,frames,seconds,fps,rss_kib,cpu_s,longest_ms,first_ms,quads,mvc,split,subdiv,passthrough" >"$csv"
: >"$apps_tmp/ratios"
: >"$apps_tmp/cpu"
: >"$apps_tmp/longest"
: >"$apps_tmp/statlines"
: >"$apps_tmp/why"
start=$(date +%s)

# rotated K: the cells in order rotated by K.
rotated() {
    echo "$cells" | awk -v k="$1" '{ for (i = 0; i < NF; i++) printf "%s ", $((i + k) % NF + 1); print "" }'
}

# median FILE: the median of the numbers in FILE (one a line), or nothing.
median() {
    sort -g "$1" | awk '{ v[NR] = $1 } END { if (NR) printf "%.6g\n", NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

# One run of a cell: appends to the CSV and to $tmp/CELL.fps (and .rss).
# (sh has no local variables: the names here are the function's own.)
run_cell() {
    rc_cell=$2 rc_k=$3
    rc_res="$tmp/$rc_cell-$rc_k.run" rc_err="$tmp/$rc_cell-$rc_k.err"
    rm -f "$rc_res"
    rc=0
    # shellcheck disable=SC2086 # the list's arguments are words
    APPSHIM_SECONDS=$secs APPSHIM_OUT=$rc_res apps_run "$rc_cell" "$rc_err" $((secs + 120)) "$1" $args || rc=$?
    rc_st=$(apps_stats "$rc_err")
    if [ "$rc_cell" = auto ] && [ -n "$rc_st" ]; then
        grep '^quadgl: [0-9]* quads' "$rc_err" | sort -t' ' -k2 -n | tail -1 >"$tmp/auto.statline"
        echo "$rc_st" >"$tmp/auto.stats"
    fi
    if [ $rc -eq 0 ] && [ -s "$rc_res" ]; then
        read -r frames seconds rss cpu longest first <"$rc_res"
        fps=$(awk -v f="$frames" -v s="$seconds" 'BEGIN { printf "%.3f", f / s }')
        echo "$fps" >>"$tmp/$rc_cell.fps"
        echo "$rss" >>"$tmp/$rc_cell.rss"
        awk -v f="$frames" -v c="$cpu" 'BEGIN { if (c > 0) printf "%.3f\n", f / c }' >>"$tmp/$rc_cell.cpf"
        echo "$longest" >>"$tmp/$rc_cell.longest"
        echo "$first" >>"$tmp/$rc_cell.first"
    else
        frames="" seconds="" fps="" rss="" cpu="" longest="" first=""
        echo "$rc" >"$tmp/$rc_cell.failed"
        echo "apps-bench: $1 ($rc_cell, run $rc_k) exited with $rc" >&2
        tail -3 "$rc_err" | sed "s/^/  $1: /" >&2
    fi
    echo "$1,$rc_cell,$rc_k,$rc,$frames,$seconds,$fps,$rss,$cpu,$longest,$first,$(echo "$rc_st" | tr ' ' ,)" >>"$csv"
}

# pair DIR WHAT: the medians of native's and auto's WHAT (milliseconds) as "native / auto".
pair() {
    awk -v a="$(median "$1/native.$2" 2>/dev/null)" -v b="$(median "$1/auto.$2" 2>/dev/null)" \
        'BEGIN { printf "%s / %s", (a == "" ? "-" : sprintf("%.1f", a)), (b == "" ? "-" : sprintf("%.1f", b)) }'
}

# ratio A B: A / B to two places, or "-".
ratio() {
    awk -v a="$1" -v b="$2" 'BEGIN { if (a != "" && b != "" && b > 0) printf "%.2f", a / b; else printf "-" }'
}

if [ "$memory" = 1 ]; then
    header="| program | native MiB" rule="|---|---:"
    for m in $methods; do header="$header | $m MiB | ratio" rule="$rule|---:|---:"; done
    header="$header |" rule="$rule|"
else
    header="| program | native fps | spread" rule="|---|---:|---:"
    for m in $methods; do header="$header | $m" rule="$rule|---:"; done
    case " $methods " in *" auto "*) header="$header | auto, CPU | longest frame ms | first frame ms" rule="$rule|---:|---:|---:" ;; esac
    header="$header | auto: quads mvc/split/subdiv/pass | class |" rule="$rule|---|---|"
fi
printf '%s\n%s\n' "$header" "$rule" >"$out/$base.md"

apps_list "$set" "$@" >"$apps_tmp/list"
while read -r name args; do
    apps_available "$name" || { echo "apps-bench: $name is not installed: skipped" >&2; continue; }
    tmp="$apps_tmp/$name"
    mkdir -p "$tmp"
    k=0
    while [ $k -lt "$reps" ]; do
        for cell in $(rotated $((k % ncells))); do
            run_cell "$name" "$cell" $((k + 1))
        done
        k=$((k + 1))
    done
    if [ "$memory" = 1 ]; then
        nat=$(median "$tmp/native.rss" 2>/dev/null || true)
        row="| $name | $(awk -v r="$nat" 'BEGIN { if (r != "") printf "%.1f", r / 1024; else printf "-" }')"
        for m in $methods; do
            r=$(median "$tmp/$m.rss" 2>/dev/null || true)
            row="$row | $(awk -v r="$r" 'BEGIN { if (r != "") printf "%.1f", r / 1024; else printf "-" }') | $(ratio "$r" "$nat")"
            echo "$name $m $(ratio "$r" "$nat")" >>"$apps_tmp/ratios"
        done
        echo "$row |" >>"$out/$base.md"
        echo "apps-bench: $name done" >&2
        continue
    fi
    nat=$(median "$tmp/native.fps" 2>/dev/null || true)
    spread=$(sort -g "$tmp/native.fps" 2>/dev/null | awk 'NR == 1 { lo = $1 } { hi = $1 } END { if (NR > 1 && lo > 0) printf "%.2f", hi / lo; else printf "-" }')
    row="| $name | $nat | $spread"
    for m in $methods; do
        r=$(ratio "$(median "$tmp/$m.fps" 2>/dev/null || true)" "$nat")
        [ -f "$tmp/$m.failed" ] && r="$r (exit $(cat "$tmp/$m.failed"))"
        row="$row | $r"
        echo "$name $m $r" >>"$apps_tmp/ratios"
    done
    if [ -f "$tmp/auto.cpf" ]; then
        r=$(ratio "$(median "$tmp/auto.cpf")" "$(median "$tmp/native.cpf" 2>/dev/null || true)")
        row="$row | $r | $(pair "$tmp" longest) | $(pair "$tmp" first)"
        echo "$name $r" >>"$apps_tmp/cpu"
        echo "$name $(median "$tmp/native.longest" 2>/dev/null) $(median "$tmp/auto.longest" 2>/dev/null)" >>"$apps_tmp/longest"
    else
        case " $methods " in *" auto "*) row="$row | - | - | -" ;; esac
    fi
    st=$(cat "$tmp/auto.stats" 2>/dev/null || true)
    class=$(echo "$st" | awk '{ if (!NF) print "-"; else if ($2 + $4 == 0) print "split"; else if (2 * ($2 + $4) > $1) print "smooth"; else print "mixed" }')
    echo "$name $class" >>"$apps_tmp/classes"
    echo "$name $spread $(echo "$st" | awk '{ if (NF && $1 > 0) { p = 100 * ($2 + $4) / $1; printf (p < 1 ? "%.2g" : "%.0f"), p } else printf "-" }')" \
        >>"$apps_tmp/why"
    [ -f "$tmp/auto.statline" ] && echo "$name: $(cat "$tmp/auto.statline")" >>"$apps_tmp/statlines"
    echo "$row | $(echo "$st" | awk '{ if (NF) printf "%s: %s/%s/%s/%s", $1, $2, $3, $4, $5 }') | $class |" >>"$out/$base.md"
    echo "apps-bench: $name done" >&2
done <"$apps_tmp/list"
took=$(($(date +%s) - start))

# The summary: medians per method and the targets.
summary() {
    if [ "$memory" = 1 ]; then
        echo "VmRSS at the end of a ${secs}-second run from the first swap, $reps run(s) per cell (median)."
        echo
        awk '$3 != "-" { n[$2]++; if ($3 > 1.10) bad[$2] = bad[$2] " " $1 " (" $3 "x)" }
             END { for (m in n) printf "- %s: %s\n", m, (bad[m] == "" ? "every program within 10% of native (target met)" : "over 10%:" bad[m] " (target missed)") }' \
            "$apps_tmp/ratios"
        return
    fi
    echo "Frames per second over ${secs} s from the first swap, median of $reps run(s) per cell,"
    echo "ratios to the native median of this bench run; $apps_size under Xvfb (llvmpipe)."
    echo
    for m in $methods; do
        awk -v m="$m" '$2 == m && $3 != "-" { print $3 + 0 }' "$apps_tmp/ratios" >"$apps_tmp/m.$m"
        printf -- "- %s: median %s over %s programs, lowest %s\n" "$m" "$(median "$apps_tmp/m.$m")" \
            "$(wc -l <"$apps_tmp/m.$m")" "$(sort -g "$apps_tmp/m.$m" | head -1)"
    done
    case " $methods " in *" auto "*) ;; *) return ;; esac
    awk '$2 != "-" { print $2 + 0 }' "$apps_tmp/cpu" >"$apps_tmp/m.cpu"
    printf -- "- auto, frames per CPU second of the process: median %s, lowest %s\n" "$(median "$apps_tmp/m.cpu")" \
        "$(sort -g "$apps_tmp/m.cpu" | head -1)"
    awk '$2 > 0 && $3 != "" { printf "%.2f %s\n", $3 / $2, $1 }' "$apps_tmp/longest" | sort -g >"$apps_tmp/m.longest"
    awk '{ print $1 }' "$apps_tmp/m.longest" >"$apps_tmp/m.lr"
    printf -- "- auto, longest frame over native's longest: median %s, highest %s\n" "$(median "$apps_tmp/m.lr")" \
        "$(tail -1 "$apps_tmp/m.longest" | awk '{ printf "%s (%s)", $1, $2 }')"
    echo
    echo "Targets (auto):"
    awk 'NR == FNR { class[$1] = $2; next } $2 == "auto" && $3 != "-" { print $1, $3 + 0, class[$1] }' \
        "$apps_tmp/classes" "$apps_tmp/ratios" >"$apps_tmp/auto"
    awk '$3 == "split" { n++; if ($2 < 0.97) bad = bad " " $1 " (" $2 ")" }
         END { printf "- programs whose quads all split >= 0.97x: %d programs, %s\n", n, (bad == "" ? "met" : "below:" bad) }' "$apps_tmp/auto"
    printf -- "- median over the list >= 0.98x: %s\n" \
        "$(awk '{ print $2 }' "$apps_tmp/auto" >"$apps_tmp/a"; median "$apps_tmp/a" | awk '{ printf "%s (%s)", $1, ($1 >= 0.98 ? "met" : "missed") }')"
    awk '$2 < 0.9 { bad = bad " " $1 " (" $2 ")" }
         END { printf "- no program below 0.9x: %s\n", (bad == "" ? "met" : "below:" bad) }' "$apps_tmp/auto"
    awk '$3 == "smooth" { n++; if ($2 < 0.9) bad = bad " " $1 " (" $2 ")" }
         END { printf "- programs dominated by smooth quads >= 0.9x: %d programs, %s\n", n, (bad == "" ? "met" : "below:" bad) }' "$apps_tmp/auto"
    echo
    echo "Below 0.9x under auto, and what this run's own figures say of why:"
    echo
    why
}

# why: a line for each program below 0.9x under auto. Its ratio with every quad split (where
# measured) parts the gap into quadgl's own cost (1 - split) and the smooth quads' (split -
# auto); the share of quads on a smooth path, the ratio with every call passed through and the
# native spread go with it.
why() {
    awk -v whyf="$apps_tmp/why" -v ratiof="$apps_tmp/ratios" '
        FILENAME == whyf { spread[$1] = $2; share[$1] = $3; next }
        FILENAME == ratiof { r[$1, $2] = $3; next }
        $2 < 0.9 {
            n++
            s = (($1, "split") in r) ? r[$1, "split"] : "-"
            o = (($1, "off") in r) ? r[$1, "off"] : "-"
            tail = sprintf("off %s (every call passed through); native spread %s", o, spread[$1])
            if ($3 == "-")
                printf "- %s %s: no statistics line from quadgl under auto\n", $1, $2
            else if ($3 == "split")
                printf "- %s %s (every quad split): quadgl'"'"'s own cost (capture, planning, upload); %s\n", $1, $2, tail
            else if (s == "-")
                printf "- %s %s (%s%% of quads smooth): no split run to tell the smooth quads'"'"' cost from quadgl'"'"'s own; %s\n", $1, $2, share[$1], tail
            else
                printf "- %s %s (%s%% of quads smooth): with every quad split it runs at %s, so of the gap %.2f is quadgl'"'"'s own cost and %.2f the smooth quads'"'"' (per-fragment weights: CPU time on a software rasterizer); %s\n", $1, $2, share[$1], s, (s < 1 ? 1 - s : 0), (s > $2 ? s - $2 : 0), tail
        }
        END { if (!n) print "- none" }' "$apps_tmp/why" "$apps_tmp/ratios" "$apps_tmp/auto"
}
{
    echo
    summary
    echo
    echo "Run took $took s."
    if [ -s "$apps_tmp/statlines" ]; then
        echo
        echo "Statistics lines under auto (last run of each program):"
        echo
        echo '```'
        cat "$apps_tmp/statlines"
        echo '```'
    fi
} >>"$out/$base.md"

# The plot: one bar per method and program.
if [ "$memory" = 0 ] && command -v gnuplot >/dev/null && [ -s "$apps_tmp/ratios" ]; then
    awk -v ms="$methods" 'BEGIN { n = split(ms, m, " ") }
        { r[$1, $2] = $3; if (!($1 in seen)) { seen[$1] = 1; order[++k] = $1 } }
        END { for (i = 1; i <= k; i++) { printf "%s", order[i]; for (j = 1; j <= n; j++) printf " %s", (order[i], m[j]) in r && r[order[i], m[j]] != "-" ? r[order[i], m[j]] + 0 : "NaN"; print "" } }' \
        "$apps_tmp/ratios" >"$apps_tmp/plot.dat"
    nprog=$(wc -l <"$apps_tmp/plot.dat")
    {
        echo "set terminal pngcairo noenhanced size $((300 + 28 * nprog)),480 font 'DejaVu Sans,9'"
        echo "set output '$out/$base.png'"
        echo "set title 'frame rate preloaded / native (median of $reps runs of ${secs} s, $apps_size, Xvfb)'"
        echo "set style data histogram; set style histogram clustered gap 1; set style fill solid 0.8 noborder"
        echo "set xtics rotate by -60 scale 0; set yrange [0:*]; set grid ytics; set key outside top center horizontal"
        echo "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc 'black'"
        echo "set arrow from graph 0, first 0.9 to graph 1, first 0.9 nohead dt 3 lc 'red'"
        printf "plot "
        j=2
        for m in $methods; do
            [ $j -gt 2 ] && printf ", "
            printf "'%s' using %d:xtic(1) title '%s'" "$apps_tmp/plot.dat" $j "$m"
            j=$((j + 1))
        done
        echo
    } | gnuplot
fi
cat "$out/$base.md"
