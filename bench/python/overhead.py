"""What the Python package costs over the C++ library it calls: a benchmark, not a test.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/overhead.py [--out overhead.json]

(PYTHONPATH at the build tree's package, or at an installed one's dist-packages; Debian's
/usr/bin/python3, which has numpy.) Prints one JSON report on stdout (and writes it to --out);
progress goes to stderr. Three figures, on the redkitchen sample (150 frames, 2 cm voxels):

1. integrate: per frame, the time of `Mapper.integrate` seen from Python (perf_counter around the
   call: argument checks, the copy of the arrays into the frame, pybind11, the GIL released and
   taken back) against `Mapper.last_call_s`, the time of `strata::Mapper::integrate` alone,
   measured in C++ around that call, in the same call of the same process. Target: <= 5 %.
2. distance: `Mapper.distance` on 1 M points (N x 3 float32, and float64 which is converted)
   against the C++ batch query `strata::Mapper::distances` inside it, timed the same way, the
   median of REPEATS calls after one that downloads the ESDF. Target: within 10 %.
3. rss: peak resident memory (os.wait4 of a child process) of fusing the 150 frames from
   Python (this script with --child-fuse) against `strata fuse` on the same data and settings;
   also that of a child that only imports strata and creates a Mapper. Target: within 10 %.

Self-checks: the Python map has as many blocks as `strata fuse` reports (same settings, same
map), and the float32 and float64 queries give the same distances.
"""
import argparse
import json
import os
import platform
import re
import statistics
import subprocess
import sys
import time

import numpy as np

import strata

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
# Fixed settings, so that runs compare: the sample, the voxel of `strata fuse`'s default, the
# query count and repeats.
DATA = os.path.join(SOURCE, "..", "shared", "data", "redkitchen")
VOXEL_M = 0.02
QUERY_POINTS = 1_000_000
REPEATS = 5
QUERY_SEED = 7
TARGETS = {"integrate_overhead_percent": 5.0, "distance_overhead_percent": 10.0,
           "rss_overhead_percent": 10.0}


def log(*args):
    print(*args, file=sys.stderr, flush=True)


def fuse_config(esdf=False):
    """`strata fuse`'s settings: MapConfig's defaults at 2 cm (free space with the ESDF)."""
    return strata.MapperConfig(strata.MapConfig(voxel_size_m=VOXEL_M, allocate_free_space=esdf),
                               esdf=esdf)


def percent(python_s, cpp_s):
    return 100.0 * (python_s - cpp_s) / cpp_s


def measure_integrate(data):
    mapper = strata.Mapper(fuse_config())
    python_s, cpp_s = [], []
    for i in range(len(data)):
        f = data[i]
        start = time.perf_counter()
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
        python_s.append(time.perf_counter() - start)
        cpp_s.append(mapper.last_call_s)
    overhead_ms = [1e3 * (p - c) for p, c in zip(python_s, cpp_s)]
    return mapper.block_count, {
        "frames": len(python_s),
        "python_total_s": sum(python_s),
        "cpp_total_s": sum(cpp_s),
        "python_median_ms": 1e3 * statistics.median(python_s),
        "cpp_median_ms": 1e3 * statistics.median(cpp_s),
        "overhead_median_ms": statistics.median(overhead_ms),
        "overhead_max_ms": max(overhead_ms),
        "overhead_percent": percent(sum(python_s), sum(cpp_s)),
    }


def timed_queries(mapper, points):
    python_s, cpp_s, result = [], [], None
    for _ in range(REPEATS):
        start = time.perf_counter()
        result = mapper.distance(points)
        python_s.append(time.perf_counter() - start)
        cpp_s.append(mapper.last_call_s)
    p, c = statistics.median(python_s), statistics.median(cpp_s)
    return result, {"python_median_s": p, "cpp_median_s": c, "overhead_percent": percent(p, c)}


def measure_distance(data):
    mapper = strata.Mapper(fuse_config(esdf=True))
    for i in range(len(data)):
        f = data[i]
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
    mapper.update_esdf()
    # Points around the surface: mesh vertices moved by up to 0.3 m, a fixed seed.
    vertices = mapper.mesh().vertices
    rng = np.random.default_rng(QUERY_SEED)
    points = vertices[rng.integers(0, len(vertices), QUERY_POINTS)]
    points = (points + rng.uniform(-0.3, 0.3, points.shape)).astype(np.float32)
    mapper.distance(points[:1])  # downloads the ESDF: not part of the timing
    (d32, _, known), f32 = timed_queries(mapper, points)
    (d64, _, _), f64 = timed_queries(mapper, points.astype(np.float64))
    assert np.array_equal(d32, d64), "float32 and float64 queries disagree"
    return {"points": QUERY_POINTS, "known_share": float(known.mean()), "float32": f32,
            "float64": f64, "overhead_percent": f32["overhead_percent"]}


def run_child(command):
    """Starts `command`, waits for it with os.wait4 and returns (peak RSS KiB, its output)."""
    proc = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    output = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed ({proc.returncode}): {output[-2000:]}")
    return usage.ru_maxrss, output


def rss_mib():
    """This process's resident memory now (MiB)."""
    with open("/proc/self/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith("VmRSS:")) / 1024


def measure_rss(data_dir, strata_exe):
    me = [sys.executable, os.path.abspath(__file__), "--data", data_dir]
    parent_mib = rss_mib()
    python_kib, python_out = run_child(me + ["--child-fuse"])
    idle_kib, _ = run_child(me + ["--child-idle"])
    cpp_kib, cpp_out = run_child([strata_exe, "fuse", data_dir, "--quiet",
                                  "--voxel-size", str(VOXEL_M)])
    python_blocks = json.loads(python_out.strip().splitlines()[-1])["blocks"]
    match = re.search(r"into (\d+) blocks", cpp_out)
    if not match:
        raise RuntimeError("strata fuse printed no block count: " + cpp_out[-2000:])
    return int(match.group(1)), python_blocks, {
        "python_fuse_mib": python_kib / 1024,
        "cpp_fuse_mib": cpp_kib / 1024,
        "python_import_and_mapper_mib": idle_kib / 1024,
        "parent_rss_at_spawn_mib": parent_mib,
        "overhead_percent": percent(python_kib, cpp_kib),
    }


def child_fuse(data_dir):
    data = strata.io.Dataset(data_dir)
    mapper = strata.Mapper(fuse_config())
    for i in range(len(data)):
        f = data[i]
        mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
    print(json.dumps({"blocks": mapper.block_count}))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--data", default=DATA, help="TUM RGB-D or 7-Scenes folder")
    parser.add_argument("--strata", default=os.path.join(SOURCE, "build", "bin", "strata"),
                        help="the strata program (for the RSS comparison)")
    parser.add_argument("--out", help="also write the report here")
    parser.add_argument("--child-fuse", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--child-idle", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child_fuse:
        return child_fuse(args.data)
    if args.child_idle:
        strata.Mapper(fuse_config())
        return None
    if not os.path.isdir(args.data):
        sys.exit(f"overhead.py: {args.data} is absent (the redkitchen sample of ../shared/data)")
    # The children first, while this process is small: a child's peak RSS starts from its
    # parent's RSS at the fork (Linux keeps the pre-exec high-water mark), so it reads
    # max(parent_rss_at_spawn_mib, the child's own peak).
    log("rss: Python and strata fuse in child processes")
    cpp_blocks, child_blocks, rss = measure_rss(args.data, args.strata)
    data = strata.io.Dataset(args.data)
    log(f"integrate: {len(data)} frames at {VOXEL_M} m")
    blocks, integrate = measure_integrate(data)
    log("distance: fusing with the ESDF, then", QUERY_POINTS, "points x", REPEATS)
    distance = measure_distance(data)
    if not blocks == child_blocks == cpp_blocks:
        raise RuntimeError(f"block counts differ: Python {blocks} and {child_blocks}, "
                           f"strata fuse {cpp_blocks}: not the same map")
    report = {
        "benchmark": "python-overhead",
        "data": os.path.basename(os.path.normpath(args.data)),
        "voxel_size_m": VOXEL_M,
        "blocks": blocks,
        "machine": {"host": platform.node(), "cpus": os.cpu_count(),
                    "python": platform.python_version(), "numpy": np.__version__},
        "integrate": integrate,
        "distance": distance,
        "rss": rss,
        "targets": TARGETS,
        "within_targets": {
            "integrate": integrate["overhead_percent"] <= TARGETS["integrate_overhead_percent"],
            "distance": distance["overhead_percent"] <= TARGETS["distance_overhead_percent"],
            "rss": rss["overhead_percent"] <= TARGETS["rss_overhead_percent"],
        },
    }
    text = json.dumps(report, indent=2)
    print(text)
    if args.out:
        with open(args.out + ".tmp", "w") as f:
            f.write(text + "\n")
        os.replace(args.out + ".tmp", args.out)
    return None


if __name__ == "__main__":
    main()
