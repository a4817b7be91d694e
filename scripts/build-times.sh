#!/usr/bin/env bash
# scripts/build-times.sh [BUILD_DIR=build] [TOP=25]: where a build's time went, from ninja's log
# (.ninja_log: each step's start and end in ms; the newest run of each output). Reads only.
# Prints the time by kind of step (compile, link, archive, shader, other), the targets by compile
# time (sum over their objects) with their link time, and the slowest single objects. Times are
# per step, not wall: with -j N the wall time is about the sum divided by N. A step ccache served
# counts its (short) time as it ran. docs/build.md has the tables this made and how to read them.
set -euo pipefail
BUILD="${1:-build}"
TOP="${2:-25}"
LOG="$BUILD/.ninja_log"
[[ -f "$LOG" ]] || { echo "build-times.sh: no $LOG (build with ninja first)" >&2; exit 2; }

# The newest line per output (a log spans several runs), then one record per step:
# kind target seconds output.
steps() {
  # One record per step: an edge with several outputs (a link and its test list, a shader's
  # binary and source) logs each output with the same times and command hash.
  awk -F'\t' '!/^#/ { last[$4] = $0 } END { for (o in last) print last[o] }' "$LOG" | sort |
    awk -F'\t' '{ key = $1 FS $2 FS $5; if (!(key in seen)) { seen[key] = 1; print } }' |
    awk -F'\t' '{
      s = ($2 - $1) / 1000.0; o = $4; kind = "other"; target = o
      if (o ~ /\.o$/ && match(o, /CMakeFiles\/[^\/]+\.dir\//)) {
        kind = "compile"; target = substr(o, RSTART + 11, RLENGTH - 16)
      } else if (o ~ /_tests\.cmake$/) {  # a test executable: its link, then its test list
        kind = "link"; sub(/.*\//, "", target); sub(/\[1\]_tests\.cmake$/, "", target)
      } else if (o ~ /\.a$/) { kind = "archive"; sub(/.*\/lib/, "", target); sub(/\.a$/, "", target)
      } else if (o ~ /\.so(\.[0-9.]+)?$/) { kind = "link"; sub(/.*\/lib/, "", target); sub(/\.so.*$/, "", target)
      } else if (o ~ /\.(spv|spvasm)$/ || o ~ /spirv/ || o ~ /shaders\//) { kind = "shader"
      } else if (o ~ /\.(h|hpp|cpp|c|cmake|txt|stamp)$/ || o ~ /CMakeFiles/) { kind = "other"
      } else { kind = "link"; sub(/.*\//, "", target) }
      printf "%s\t%s\t%.3f\t%s\n", kind, target, s, o
    }'
}

STEPS="$(steps)"
echo "Steps by kind (sum of step times, s):"
echo "$STEPS" | awk -F'\t' '{ t[$1] += $3; n[$1]++; all += $3 }
  END { for (k in t) printf "  %-8s %8.1f s  %5d steps  %5.1f %%\n", k, t[k], n[k], 100 * t[k] / all;
        printf "  %-8s %8.1f s\n", "total", all }' | sort -k2 -n -r

echo
echo "Targets by compile time (sum over objects, s), with the link or archive step:"
printf '  %-40s %9s %7s %9s %9s\n' target compile objects slowest link
echo "$STEPS" | awk -F'\t' '
  $1 == "compile" { c[$2] += $3; n[$2]++; if ($3 > m[$2]) m[$2] = $3 }
  $1 == "link" || $1 == "archive" { l[$2] += $3 }
  END { for (t in c) printf "  %-40s %9.1f %7d %9.1f %9.1f\n", t, c[t], n[t], m[t], l[t] }' |
  sort -k2 -n -r | head -n "$TOP"

echo
echo "Links by time (s):"
echo "$STEPS" | awk -F'\t' '$1 == "link" { printf "  %-40s %8.2f\n", $2, $3 }' | sort -k2 -n -r |
  head -n "$TOP"
echo "$STEPS" | awk -F'\t' '$1 == "link" { t += $3; n++ }
  END { if (n) printf "  %d links, %.1f s in all, %.2f s on average\n", n, t, t / n }'

echo
echo "Slowest objects (s):"
echo "$STEPS" | awk -F'\t' '$1 == "compile" { printf "  %8.1f  %s\n", $3, $4 }' | sort -n -r |
  head -n "$TOP"
