#!/usr/bin/env bash
# What a live viewer costs the mapper: the same replay (strata-play sim:room:0, paced by the mapper)
# through strata-mapper with and without strata-view attached (and a WebSocket client reading the
# view's stream, as a page would, but drawing nothing), alternating, in a network namespace of its
# own. JSON on stdout: the mapper's mean fusion time per frame of every run, and the median of each
# side. Needs root for `unshare --net` (as the LCM tests).
#   bench/view/mapper_cost.sh [RUNS_EACH] [FRAMES]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
RUNS="${1:-3}"
FRAMES="${2:-60}"
B="$ROOT/build/bin"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cat >"$work/client.cjs" <<'JS'
// Reads everything the view sends, as a page would, drawing nothing (Node 20's WebSocket).
const url = process.argv[2];
let bytes = 0;
const open = () => {
  const ws = new WebSocket(url);
  ws.binaryType = 'arraybuffer';
  ws.onmessage = (m) => { bytes += m.data.byteLength; };
  ws.onerror = () => setTimeout(open, 200);
};
open();
process.on('SIGTERM', () => { console.log(bytes); process.exit(0); });
JS
run() {  # $1: with view (1) or not (0); prints the mapper's mean ms per frame
  local with="$1" log="$work/mapper_$RANDOM.log"
  unshare --net bash -c "
    ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 10
    $B/strata-mapper --map '' --no-change --mesh-rate 0 --esdf-rate 2 > $log 2>&1 &
    M=\$!
    if [ $with = 1 ]; then
      $B/strata-view --port 18766 --quiet > $work/view.log 2>&1 &
      V=\$!
      node --experimental-websocket $work/client.cjs ws://127.0.0.1:18766/ws > $work/client.log 2>&1 &
      C=\$!
    fi
    for i in \$(seq 600); do grep -q 'listening on' $log && break; sleep 0.1; done
    sleep 1
    $B/strata-play sim:room:0 --sim-frames $FRAMES --rate 0 --quiet --mapper-timeout 120 > $work/play.log 2>&1
    kill -TERM \$M; wait \$M
    if [ $with = 1 ]; then kill -TERM \$C; wait \$C; kill -INT \$V; wait \$V; fi
    true"
  grep -o 'fused [0-9]* ([0-9.]* ms each' "$log" | grep -o '([0-9.]*' | tr -d '('
  if [ "$with" = 1 ]; then tail -1 "$work/client.log" >>"$work/client_bytes"; fi
}
with=() without=()
for i in $(seq "$RUNS"); do
  without+=("$(run 0)")
  with+=("$(run 1)")
done
python3 - "${without[*]}" "${with[*]}" "$(cat "$work/client_bytes" | tr '\n' ' ')" <<'PY'
import json, statistics, sys
without = [float(x) for x in sys.argv[1].split()]
with_view = [float(x) for x in sys.argv[2].split()]
client_bytes = [int(x) for x in sys.argv[3].split() if x.isdigit()]
a, b = statistics.median(without), statistics.median(with_view)
print(json.dumps({"mapper_ms_per_frame_without_view": without, "mapper_ms_per_frame_with_view": with_view,
                  "median_without": a, "median_with": b, "change_percent": 100.0 * (b - a) / a,
                  "bytes_read_by_the_client_per_run": client_bytes}, indent=1))
PY
