#!/usr/bin/env bash
# VIO accuracy on simulated sessions of every shipped world, stereo and mono: renders each world's
# sessions as grey stereo + IMU (`strata sim --stereo --rest`), runs `strata odometry` on each in
# both modes, and prints one table row per session and mode (ATE after SE(3) for stereo and
# Sim(3) for mono, as RMSE and as a share of the path; RPE; failures; frames per second).
# Usage: scripts/vio-eval.sh [BUILD_DIR] [OUT_DIR]   (default: build/, vio_eval/)
# Env:   WORLDS (default "room office warehouse"), SESSIONS (default 2), REST (seconds of
#        standstill before each path, default 2), DURATION (seconds of each path recorded,
#        0 = all; default 0).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
OUT="${2:-vio_eval}"
WORLDS="${WORLDS:-room office warehouse}"
SESSIONS="${SESSIONS:-2}"
REST="${REST:-2}"
DURATION="${DURATION:-0}"
STRATA="$BUILD/bin/strata"
mkdir -p "$OUT"
for world in $WORLDS; do
  if [ ! -d "$OUT/$world" ]; then
    echo "== rendering $world ($SESSIONS sessions)" >&2
    "$STRATA" sim "$ROOT/worlds/$world.yaml" --sessions "$SESSIONS" --stereo --rest "$REST" \
        --stereo-duration "$DURATION" --frames 2 --out "$OUT/$world" --quiet > /dev/null
  fi
  for session in "$OUT/$world"/session_*; do
    for mode in stereo mono; do
      flag=""; [ "$mode" = mono ] && flag="--mono"
      echo "== $world $(basename "$session") $mode" >&2
      "$STRATA" odometry "$session" $flag --out "$session/vio_$mode.txt" --quiet \
          --plot "$session/vio_$mode.png" > "$session/vio_$mode.log" || true
    done
  done
done
python3 - "$OUT" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
print("| world | session | mode | tracked | failures | path m | ATE RMSE mm | ATE % of path | ATE max mm | RPE % | RPE deg/m | scale | frames/s | frames per CPU s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(out, "*", "session_*", "vio_*.json"))):
    d = json.load(open(path))
    parts = path.split(os.sep)
    world, session, mode = parts[-3], parts[-2], "stereo" if d["stereo"] else "mono"
    a = (d.get("accuracy") or {}).get("se3" if d["stereo"] else "sim3")
    fps = d["timing"]["frames_per_second"]
    cpu_fps = d["timing"].get("frames_per_cpu_second") or float("nan")
    if not a:
        print(f"| {world} | {session} | {mode} | {d['frames_tracked']}/{d['frames_processed']} | {d['failures']} | | | | | | | | {fps:.1f} | {cpu_fps:.1f} |")
        continue
    pct = 100 * a["ate_rmse_m"] / a["path_length_m"] if a["path_length_m"] else float("nan")
    rpe = a["rpe_trans_percent"] if a["rpe_trans_percent"] is not None else float("nan")
    rot = a["rpe_rot_deg_per_m"] if a["rpe_rot_deg_per_m"] is not None else float("nan")
    print(f"| {world} | {session} | {mode} | {d['frames_tracked']}/{d['frames_processed']} | {d['failures']} | "
          f"{a['path_length_m']:.1f} | {1e3*a['ate_rmse_m']:.1f} | {pct:.2f} | {1e3*a['ate_max_m']:.1f} | "
          f"{rpe:.2f} | {rot:.3f} | {a['scale']:.4f} | {fps:.1f} | {cpu_fps:.1f} |")
PY
