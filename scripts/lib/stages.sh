# Stage timing for the scripts that run many steps (run-tests.sh, run-main.sh). Source it, then
# `stage NAME COMMAND...` runs COMMAND, records its wall time and status, and returns its status.
# At exit (normal, failed or interrupted) the table of every stage's time is printed, the stages
# not reached named as such, and written as JSON to $STRATA_STAGE_JSON when that is set.
# Bash only; not thread safe (one script, stages in sequence).

STRATA_STAGE_NAMES=()
STRATA_STAGE_SECONDS=()
STRATA_STAGE_RESULTS=()
STRATA_STAGE_PLANNED=()
STRATA_STAGE_T0="$(date +%s.%N)"

# stage_plan NAME...: the stages this run means to reach, so the table names those it did not.
stage_plan() { STRATA_STAGE_PLANNED=("$@"); }

stage() {
  local name="$1"
  shift
  local start end status=0
  start="$(date +%s.%N)"
  echo "=== stage: $name ($(date +%H:%M:%S))" >&2
  "$@" || status=$?
  end="$(date +%s.%N)"
  STRATA_STAGE_NAMES+=("$name")
  STRATA_STAGE_SECONDS+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.0f", b - a }')")
  if ((status == 0)); then STRATA_STAGE_RESULTS+=("ok"); else STRATA_STAGE_RESULTS+=("failed ($status)"); fi
  return "$status"
}

stage_table() {
  local i total=0 json="" separator="" name done
  echo
  echo "Stage times (wall, this machine: $(nproc) cores):"
  printf '  %-22s %8s  %s\n' stage seconds result
  for i in "${!STRATA_STAGE_NAMES[@]}"; do
    printf '  %-22s %8s  %s\n' "${STRATA_STAGE_NAMES[$i]}" "${STRATA_STAGE_SECONDS[$i]}" \
      "${STRATA_STAGE_RESULTS[$i]}"
    total=$((total + STRATA_STAGE_SECONDS[i]))
    json+="$separator{\"stage\": \"${STRATA_STAGE_NAMES[$i]}\", \"seconds\": ${STRATA_STAGE_SECONDS[$i]},"
    json+=" \"result\": \"${STRATA_STAGE_RESULTS[$i]}\"}"
    separator=", "
  done
  for name in "${STRATA_STAGE_PLANNED[@]}"; do
    done=0
    for i in "${!STRATA_STAGE_NAMES[@]}"; do [[ "${STRATA_STAGE_NAMES[$i]}" == "$name" ]] && done=1; done
    ((done)) || printf '  %-22s %8s  %s\n' "$name" - "not reached"
  done
  printf '  %-22s %8s  (%.1f min)\n' total "$total" "$(awk -v t="$total" 'BEGIN { print t / 60 }')"
  if [[ -n "${STRATA_STAGE_JSON:-}" ]]; then
    mkdir -p "$(dirname "$STRATA_STAGE_JSON")"
    echo "{\"cores\": $(nproc), \"total_s\": $total, \"stages\": [$json]}" >"$STRATA_STAGE_JSON.tmp" &&
      mv "$STRATA_STAGE_JSON.tmp" "$STRATA_STAGE_JSON"
  fi
}

trap 'status=$?; stage_table >&2; exit $status' EXIT
