#!/usr/bin/env bash
# scripts/fuzz.sh [seconds_per_target=60] | --total SECONDS: runs every libFuzzer target of fuzz/
# for the given time, two at a time (one per core); with --total, one budget of wall time for all
# of them (each target gets budget * 2 / targets seconds, at least 5: what CI runs), each from a fresh copy of its committed corpus fuzz/corpus/<name>/
# (the committed corpus is never written), with its dictionary fuzz/dict/<name>.dict when there is
# one. Builds nothing when build-san/ exists (configures and builds it otherwise, like
# scripts/sanitize.sh). Prints executions per second and total executions per target, writes
# build-san/fuzz/summary.json, and exits non-zero naming the target and its artifact when any
# target crashed, leaked, timed out or ran out of memory. Limits and layout: docs/fuzzing.md.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${STRATA_SANITIZE_BUILD_DIR:-$ROOT/build-san}"
JOBS=2
TOTAL_SECONDS=""
if [[ "${1:-}" == --total ]]; then
  TOTAL_SECONDS="${2:?fuzz.sh: --total needs a number of seconds}"
  [[ "$TOTAL_SECONDS" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: --total '$TOTAL_SECONDS' is not a whole number of seconds" >&2; exit 2; }
  SECONDS_PER_TARGET=""
else
  SECONDS_PER_TARGET="${1:-60}"
  [[ "$SECONDS_PER_TARGET" =~ ^[0-9]+$ ]] || { echo "fuzz.sh: '$SECONDS_PER_TARGET' is not a whole number of seconds per target" >&2; exit 2; }
fi
# Per input: 1 s of run time, 2 GiB of resident memory, and no single allocation over 1 GiB (the
# parsers' own limits keep every allocation proportional to the input, far below this).
MALLOC_LIMIT_MB=1024
RSS_LIMIT_MB=2048
RUN="$BUILD/fuzz/run"

# Largest input per target, bytes: a little above the seeds, so the fuzzer mutates structure
# rather than growing inputs the parsers read linearly.
max_len() {
  case "$1" in
    fuzz_map_file | fuzz_object_database) echo 16384 ;;
    fuzz_depth_png | fuzz_color_image) echo 8192 ;;
    fuzz_lcm_rgbd_frame) echo 4096 ;;
    fuzz_world_yaml | fuzz_ply_mesh | fuzz_obj_mesh) echo 4096 ;;
    *) echo 1024 ;;
  esac
}

if [[ ! -d "$BUILD" ]]; then
  CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTRATA_BUILD_FUZZ=ON -DSTRATA_BUILD_BENCH=OFF -DSTRATA_WITH_OPEN3D=OFF -DSTRATA_BUILD_TESTS=ON
  targets=()
  for source in "$ROOT"/fuzz/fuzz_*.cpp; do targets+=("$(basename "$source" .cpp)"); done
  cmake --build "$BUILD" -j "$JOBS" --target "${targets[@]}"
fi
source "$ROOT/scripts/sanitizers/env.sh"

TARGETS=()
for source in "$ROOT"/fuzz/fuzz_*.cpp; do
  name="$(basename "$source" .cpp)"
  if [[ ! -x "$BUILD/fuzz/$name" ]]; then
    echo "fuzz.sh: $BUILD/fuzz/$name is not built (cmake --build $BUILD --target $name)" >&2
    exit 2
  fi
  TARGETS+=("$name")
done
if [[ -n "$TOTAL_SECONDS" ]]; then
  SECONDS_PER_TARGET=$((TOTAL_SECONDS * JOBS / ${#TARGETS[@]}))
  ((SECONDS_PER_TARGET >= 5)) || SECONDS_PER_TARGET=5
  echo "fuzz.sh: ${TOTAL_SECONDS} s in all for ${#TARGETS[@]} targets, ${JOBS} at a time: ${SECONDS_PER_TARGET} s each"
fi

run_target() {
  local name="$1" work="$RUN/$1"
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp -r "$ROOT/fuzz/corpus/$name/." "$work/corpus/"
  local args=(-max_total_time="$SECONDS_PER_TARGET" -timeout=1 -rss_limit_mb="$RSS_LIMIT_MB"
              -malloc_limit_mb="$MALLOC_LIMIT_MB" -max_len="$(max_len "$name")" -detect_leaks=1
              -print_final_stats=1 -artifact_prefix="$work/artifacts/")
  [[ -f "$ROOT/fuzz/dict/$name.dict" ]] && args+=(-dict="$ROOT/fuzz/dict/$name.dict")
  local status=0
  "$BUILD/fuzz/$name" "${args[@]}" "$work/corpus" >"$work/log.txt" 2>&1 || status=$?
  echo "$status" >"$work/status"
}

# A stat of libFuzzer's -print_final_stats=1 block, 0 when absent (the run died before it).
final_stat() {
  local value
  value="$(grep -o "stat::$2: *[0-9]*" "$1" | tail -1 | grep -o '[0-9]*$' || true)"
  echo "${value:-0}"
}

# Executions per second: the final stat, else (a run that stopped early on a finding) the last
# status line's "exec/s: N".
exec_rate() {
  local rate
  rate="$(final_stat "$1" average_exec_per_sec)"
  if [[ "$rate" == 0 ]]; then
    rate="$(grep -o 'exec/s: [0-9]*' "$1" | tail -1 | grep -o '[0-9]*$' || true)"
  fi
  echo "${rate:-0}"
}

# Whether a timeout artifact times out again, run alone three times. NOTE: on a shared 2-core
# machine a process can be descheduled for over a second; a timeout that does not reproduce is
# that, not a slow input (the parsers are deterministic).
timeout_reproduces() {
  ! "$BUILD/fuzz/$1" -timeout=1 -runs=3 -rss_limit_mb="$RSS_LIMIT_MB" \
    -malloc_limit_mb="$MALLOC_LIMIT_MB" "$2" >"$(dirname "$2")/../replay.txt" 2>&1
}

# What went wrong, from the artifact libFuzzer wrote (crash-, leak-, timeout-, oom-).
finding() {
  local artifact kind
  artifact="$(find "$1/artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o \
    -name 'timeout-*' -o -name 'oom-*' \) | head -1)"
  if [[ -n "$artifact" ]]; then
    kind="$(basename "$artifact" | cut -d- -f1)"
    if [[ "$kind" == timeout ]] && ! timeout_reproduces "$(basename "$1")" "$artifact"; then
      kind="timeout-not-reproduced"
    fi
    echo "$kind $artifact"
  elif [[ "$(cat "$1/status")" != 0 ]]; then
    echo "failed $1/log.txt"
  fi
}

start_s=$(date +%s)
for name in "${TARGETS[@]}"; do
  while (($(jobs -rp | wc -l) >= JOBS)); do wait -n || true; done
  run_target "$name" &
done
wait
elapsed_s=$(($(date +%s) - start_s))

failed=0
json="{\"seconds_per_target\": $SECONDS_PER_TARGET, \"wall_s\": $elapsed_s, \"targets\": ["
separator=""
printf '%-24s %12s %16s  %s\n' target exec/s executions result
for name in "${TARGETS[@]}"; do
  work="$RUN/$name"
  execs="$(final_stat "$work/log.txt" number_of_executed_units)"
  rate="$(exec_rate "$work/log.txt")"
  rss="$(final_stat "$work/log.txt" peak_rss_mb)"
  result="ok" artifact=""
  read -r kind path <<<"$(finding "$work")" || true
  if [[ -n "${kind:-}" ]]; then
    result="$kind" artifact="$path"
    [[ "$kind" == timeout-not-reproduced ]] || failed=1
  fi
  printf '%-24s %12s %16s  %s\n' "$name" "$rate" "$execs" "$result${artifact:+ $artifact}"
  json+="$separator{\"name\": \"$name\", \"exec_per_s\": $rate, \"executions\": $execs,"
  json+=" \"peak_rss_mb\": $rss, \"result\": \"$result\", \"artifact\": \"$artifact\"}"
  separator=", "
  kind="" path=""
done
json+="]}"
echo "$json" >"$BUILD/fuzz/summary.json"
echo "fuzz.sh: ${#TARGETS[@]} targets, ${SECONDS_PER_TARGET} s each, ${elapsed_s} s in all;" \
  "summary in $BUILD/fuzz/summary.json"
if ((failed)); then
  echo "fuzz.sh: findings above (reproduce: <build>/fuzz/<target> <artifact>)" >&2
  exit 1
fi
