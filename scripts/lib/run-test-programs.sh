#!/usr/bin/env bash
# scripts/lib/run-test-programs.sh BUILD_DIR LABELS [EXCLUDE_FILE [PROGRAMS_FILE]]: runs every test
# program of BUILD_DIR whose label matches LABELS (an extended regex, e.g. 'unit|device'; from
# BUILD_DIR/strata_tests.txt) once, all its test cases in one process, two programs at a time,
# with the Vulkan validation layer on (a validation error fails the test case). Test cases named in
# EXCLUDE_FILE (one per line, # comments; "" for none) are filtered out. With PROGRAMS_FILE (program
# names, one per line, # comments) only the programs it names run; a name it lists that the build
# does not have is an error. Each program's output goes to
# BUILD_DIR/test-programs/<name>.log; a failed program's tail is printed. Ends with
# "N passed, N failed" (programs) and exits non-zero when any failed.
#
# Why not ctest here: ctest starts one process per test case, and a case pays its program's start
# (the Vulkan instance with the validation layer) and its suite's shared set-up (a rendered
# session, a fused map) again; under the sanitizers that was most of the stage (docs/build.md).
set -euo pipefail
BUILD="${1:?run-test-programs.sh: BUILD_DIR}"
LABELS="${2:?run-test-programs.sh: LABELS}"
EXCLUDE_FILE="${3:-}"
PROGRAMS_FILE="${4:-}"
LIST="$BUILD/strata_tests.txt"
[[ -f "$LIST" ]] || { echo "run-test-programs.sh: no $LIST (configure with tests first)" >&2; exit 2; }
TIMEOUT_S="${STRATA_TEST_PROGRAM_TIMEOUT_S:-1800}"
LOGS="$BUILD/test-programs"
rm -rf "$LOGS"
mkdir -p "$LOGS"

filter="*"
if [[ -n "$EXCLUDE_FILE" ]]; then
  excluded="$(grep -v '^#' "$EXCLUDE_FILE" | grep . | paste -sd ':' || true)"
  [[ -n "$excluded" ]] && filter="-$excluded"
fi

wanted=""
if [[ -n "$PROGRAMS_FILE" ]]; then
  wanted="$(grep -v '^#' "$PROGRAMS_FILE" | grep . || true)"
  for name in $wanted; do
    grep -q "^$name " "$LIST" || { echo "run-test-programs.sh: $PROGRAMS_FILE names $name, which $LIST does not list" >&2; exit 2; }
  done
fi

programs=()
while read -r name label path; do
  [[ "$label" =~ ^(${LABELS})$ ]] || continue
  [[ -z "$wanted" ]] || grep -qxF "$name" <<<"$wanted" || continue
  [[ -x "$path" ]] || { echo "run-test-programs.sh: $path is not built" >&2; exit 2; }
  programs+=("$name $path")
done <"$LIST"

run_one() {
  local name="$1" path="$2" start status=0
  start=$(date +%s)
  STRATA_VALIDATION=1 timeout "$TIMEOUT_S" "$path" --gtest_filter="$filter" \
    >"$LOGS/$name.log" 2>&1 || status=$?
  local cases
  cases="$(grep -o '^\[==========\] [0-9]* tests\? from' "$LOGS/$name.log" | tail -1 | grep -o '[0-9]*' || true)"
  if ((status == 0)); then
    printf 'passed  %-34s %5d s  %s cases\n' "$name" $(($(date +%s) - start)) "${cases:-0}"
  else
    printf 'FAILED  %-34s %5d s  exit %d (log: %s)\n' "$name" $(($(date +%s) - start)) "$status" \
      "$LOGS/$name.log"
    grep -E '^\[  FAILED  \]|ERROR: AddressSanitizer|runtime error:|LeakSanitizer' \
      "$LOGS/$name.log" | head -20 || true
    tail -30 "$LOGS/$name.log"
  fi
  return "$status"
}
export -f run_one
export LOGS TIMEOUT_S filter

echo "run-test-programs.sh: ${#programs[@]} programs labelled '$LABELS' in $BUILD, two at a time"
results="$(mktemp)"
printf '%s\n' "${programs[@]}" |
  xargs -P 2 -L 1 bash -c 'run_one "$0" "$1"' | tee "$results" || true
passed=$(grep -c '^passed' "$results" || true)
failed=$(grep -c '^FAILED' "$results" || true)
rm -f "$results"
missing=$((${#programs[@]} - passed - failed))
((missing == 0)) || { echo "run-test-programs.sh: $missing programs gave no result" >&2; failed=$((failed + missing)); }
echo "test programs: $passed passed, $failed failed"
((failed == 0))
