#!/usr/bin/env python3
"""Visual-inertial odometry over the EuRoC excerpt from Python: the left camera's trajectory
against the truth, from above, with the ATE after SE(3) alignment.

    python3 examples/python/vio_euroc.py [--data ../shared/data/euroc_v101_micro] [--out vio.png]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import strata  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data",
                        default=os.path.join(HERE, "../../../shared/data/euroc_v101_micro"))
    parser.add_argument("--out", default="vio_trajectory.png")
    parser.add_argument("--mono", action="store_true", help="left camera only")
    args = parser.parse_args()

    run = strata.odometry.run_euroc(args.data, mono=args.mono)
    error = strata.trajectory.evaluate(run.trajectory, run.truth,
                                       alignment="sim3" if args.mono else "se3")
    est = error.aligned_positions
    fig, ax = plt.subplots(figsize=(6, 6))
    ax.plot(run.truth[:, 1], run.truth[:, 2], "k-", lw=1, label="truth (left camera)")
    ax.plot(est[:, 0], est[:, 1], "r.-", ms=3, lw=0.8, label="Strata VIO, aligned")
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{run.frames_tracked} of {run.frames_processed} frames tracked; "
                 f"ATE {1000 * error.ate_rmse_m:.1f} mm")
    ax.legend()
    fig.savefig(args.out, dpi=120, bbox_inches="tight")
    print(f"{run}; ATE RMSE {1000 * error.ate_rmse_m:.1f} mm; wrote {args.out}")


if __name__ == "__main__":
    main()
