#!/usr/bin/env bash
# The "ball of doom" check of the object database over many sessions of the office: 8 simulated
# sessions (strata sim, 60 frames each, noise on), `strata objects` over the first 4, 6 and 8 of
# them, and per true object the model it lies in: its area / the object's true area ("growth",
# must stay <= 1.2: above 1 a model has grown beyond any one object) and its accuracy (mean
# distance of its vertices to the true mesh) in each run, flagging an object whose accuracy got
# worse by more than 2 mm as sessions were added. Prints a table; writes growth.json in OUT_DIR.
#   scripts/objects-growth.sh [BUILD_DIR] [OUT_DIR] [FRAMES_PER_SESSION]
# BEFORE_AFTER=FILE.png also writes the 8-session run's before / after picture (docs/objects.md).
# (about 10 minutes on 2 lavapipe cores). Exit code 1 when the largest growth exceeds 1.2.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
OUT="${2:-objects_growth}"
FRAMES="${3:-60}"
STRATA="${STRATA:-$BUILD/bin/strata}"
mkdir -p "$OUT"
sim="$OUT/sim"
if [[ ! -f "$sim/session_7/rgb.txt" ]]; then
  "$STRATA" sim "$ROOT/worlds/office.yaml" --sessions 8 --frames "$FRAMES" --quiet --out "$sim" \
    > "$OUT/sim.log"
fi
for n in 4 6 8; do
  if [[ ! -f "$OUT/objects_$n/objects.json" ]]; then
    sessions=()
    for ((i = 0; i < n; ++i)); do sessions+=("$sim/session_$i"); done
    # --min-weight 3: 60 recorded frames per session see a voxel in fewer frames than a full path.
    extra=()
    if [[ $n == 8 && -n "${BEFORE_AFTER:-}" ]]; then extra=(--before-after "$BEFORE_AFTER"); fi
    "$STRATA" objects "${sessions[@]}" --out "$OUT/objects_$n" --min-weight 3 --quiet \
      "${extra[@]}" > "$OUT/objects_$n.log"
  fi
done
python3 - "$OUT" <<'PY'
import json, sys
out = sys.argv[1]
RUNS = (4, 6, 8)
# A model is known across runs by the true object it lies on, the session that founded it and
# where its founding segment lay (model and segment ids differ between runs: change detection
# over more sessions finds other segments): founding centroids within 15 cm are the same model.
def models_of(n):
    doc = json.load(open(f"{out}/objects_{n}/objects.json"))
    founding = {m["id"]: min(m["instances"], key=lambda i: i["session"]) for m in doc["models"]}
    rows = []
    for m in doc["truth"]["models"]:
        if m["object_id"] != 0:
            f = founding[m["model"]]
            rows.append(((m["object_id"], f["session"]), f["centroid_m"], m))
    return doc["truth"], rows
runs = {n: models_of(n) for n in RUNS}
tracks = []  # [base, centroid, {run: model row}]
for n in RUNS:
    for base, centroid, m in runs[n][1]:
        near = [t for t in tracks if t[0] == base and n not in t[2] and
                sum((a - b) ** 2 for a, b in zip(t[1], centroid)) < 0.15 ** 2]
        if near:
            near[0][2][n] = m
        else:
            tracks.append([base, centroid, {n: m}])
tracks.sort(key=lambda t: t[0])
print("object (founded in session) | instances 4/6/8 | growth 4/6/8      | accuracy mm 4/6/8  | worse")
report = {"runs": {}, "models": []}
worse_any = []
for base, _, by_run in tracks:
    rows = [by_run.get(n) for n in RUNS]
    name = next(r["object"] for r in rows if r) + f" ({base[1]})"
    acc = [r["accuracy_m"] * 1e3 for r in rows if r and r["accuracy_m"] > 0]
    worse = any(b - a > 2.0 for i, a in enumerate(acc) for b in acc[i + 1:])
    if worse:
        worse_any.append(name)
    f = lambda r, k, s=1.0, fmt="{:.2f}": fmt.format(r[k] * s) if r else "-"
    print(f"{name[:27]:27} | {'/'.join(f(r, 'instances', 1, '{:d}') for r in rows):15} | "
          f"{'/'.join(f(r, 'growth') for r in rows):17} | "
          f"{'/'.join(f(r, 'accuracy_m', 1e3, '{:.1f}') for r in rows):18} | {'yes' if worse else ''}")
    report["models"].append({"object_id": base[0], "founded_in_session": base[1], "object": name,
                             "runs": {str(n): r for n, r in zip(RUNS, rows)},
                             "accuracy_worse_by_more_than_2mm": worse})
for n in RUNS:
    t = runs[n][0]
    report["runs"][str(n)] = {k: t[k] for k in ("segments", "segments_in_models", "pairs", "pose",
                                                "completeness_mean", "accuracy_mean_m", "growth_max",
                                                "growth_max_model")}
    print(f"{n} sessions: {t['segments']} segments, {len(t['models'])} models, growth max "
          f"{t['growth_max']:.2f} (model {t['growth_max_model']}), accuracy mean "
          f"{1e3 * t['accuracy_mean_m']:.1f} mm, precision {t['pairs']['precision']:.3f}, "
          f"recall {t['pairs']['recall']:.3f}")
report["growth_max"] = max(runs[n][0]["growth_max"] for n in RUNS)
report["models_less_accurate_with_more_sessions"] = worse_any
json.dump(report, open(f"{out}/growth.json", "w"), indent=1)
print(f"largest growth {report['growth_max']:.2f} (limit 1.2); models whose accuracy got worse by "
      f"> 2 mm as sessions were added: {', '.join(worse_any) if worse_any else 'none'}")
sys.exit(0 if report["growth_max"] <= 1.2 else 1)
PY
