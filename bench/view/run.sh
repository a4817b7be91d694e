#!/usr/bin/env bash
# The viewer's load and frame-rate benchmark: a 2 M-triangle mesh (bench/view/make_mesh.py) served by
# strata view, opened and orbited in headless Chromium (bench/view/view_bench.cjs). JSON to
# OUT (default build/bench-view.json).
#   bench/view/run.sh [OUT.json] [MESH.ply]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
OUT="${1:-$ROOT/build/bench-view.json}"
MESH="${2:-}"
work="$(mktemp -d)"
trap 'kill "${server:-0}" 2>/dev/null || true; rm -rf "$work"' EXIT
if [[ -z "$MESH" ]]; then
  MESH="$work/surface2m.ply"
  /usr/bin/python3 "$ROOT/bench/view/make_mesh.py" "$MESH" >&2
fi
"$ROOT/build/bin/strata" view "$MESH" --port 0 >"$work/view.log" 2>&1 &
server=$!
for _ in $(seq 1 600); do
  url="$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/view.log" || true)"
  [[ -n "$url" ]] && break
  kill -0 "$server" 2>/dev/null || { cat "$work/view.log" >&2; exit 1; }
  sleep 0.1
done
[[ -n "$url" ]] || { echo "run.sh: strata view did not start" >&2; exit 1; }
node "$ROOT/bench/view/view_bench.cjs" "$ROOT/web" "$url" 5 >"$work/result.json"
mv "$work/result.json" "$OUT"
cat "$OUT"
