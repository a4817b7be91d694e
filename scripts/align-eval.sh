#!/usr/bin/env bash
# Multi-session alignment on every shipped world: 5 simulated sessions per world, odometry drifting
# in frames of their own (strata sim --drift --own-frames), registered by `strata align`, scored
# against the simulator's truth (report.json's "truth"). Prints one line per world.
#   scripts/align-eval.sh [BUILD_DIR] [OUT_DIR] [FRAMES_PER_SESSION] [extra strata sim options]
# e.g. --color-texture (the RGB camera sees the world-anchored texture the grey camera sees).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
OUT="${2:-align_eval}"
FRAMES="${3:-150}"
SIM_OPTIONS=("${@:4}")
STRATA="$BUILD/bin/strata"
mkdir -p "$OUT"
for world in room office warehouse; do
  sim="$OUT/$world-sim"
  if [[ ! -f "$sim/session_4/odometry.txt" ]]; then
    "$STRATA" sim "$ROOT/worlds/$world.yaml" --sessions 5 --frames "$FRAMES" --drift --own-frames \
      "${SIM_OPTIONS[@]}" --out "$sim" > "$OUT/$world-sim.log"
  fi
  rm -rf "$OUT/$world"
  "$STRATA" align "$sim"/session_{0,1,2,3,4} --out "$OUT/$world" --keyframe-every 1 --quiet \
    > "$OUT/$world.log"
  python3 - "$world" "$OUT/$world/report.json" <<'PY'
import json, sys
world, path = sys.argv[1], sys.argv[2]
r = json.load(open(path)); t = r["truth"]; times = r["times"]; loops = r["loops"]
print(f"{world}: aligned {r['aligned_sessions']}/{len(r['sessions'])}, ATE before {t['ate_before_rmse_m']:.3f} m "
      f"-> after {1e3*t['ate_after_rmse_m']:.1f} mm (max {1e3*t['ate_after_max_m']:.1f} mm), "
      f"drift-only ATE per session {[round(1e3*s['ate_drift_only_rmse_m'],1) for s in t['sessions']]} mm, "
      f"loops kept {t['loops_accepted_true']} true / {t['loops_accepted_false']} false "
      f"(switched off {t['loops_switched_off_true']} true / {t['loops_switched_off_false']} false), "
      f"keyframe recall {t['loop_recall']:.3f}; {loops['candidates_verified']} candidates verified; "
      f"{times['keyframes']} keyframes: features {times['features_s']:.1f} s, retrieval {times['retrieval_s']:.1f} s, "
      f"verification {times['verification_s']:.1f} s, graph {times['graph_s']:.2f} s, "
      f"loop detection {times['loop_detection_ms_per_keyframe']:.1f} ms/keyframe")
PY
done
