#!/usr/bin/env python3
"""Two simulated sessions of the shipped room, fused with change detection from Python: the
objects that moved between them, drawn from above over the static map's mesh.

    python3 examples/python/room_objects.py [--frames 40] [--out room_objects.png]
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import strata  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=40, help="frames per session")
    parser.add_argument("--out", default="room_objects.png")
    args = parser.parse_args()

    sessions = [strata.sim.session("room", s, frames=args.frames) for s in (0, 1)]
    recorded = sessions[0].recorded_frames / len(sessions[0])
    config = strata.MapperConfig(strata.MapConfig.for_change_detection(0.05),
                                 change_detection=True, recorded_per_fused=recorded)
    mapper = strata.Mapper(config)
    found = []
    for data in sessions:
        mapper.begin_session()
        for i in range(len(data)):
            f = data[i]
            mapper.integrate(f["depth"], data.intrinsics, f["T_W_C"], f["color"])
        found = mapper.end_session()
    static = mapper.mesh()

    fig, ax = plt.subplots(figsize=(7, 7))
    v = static.vertices
    ax.scatter(v[:, 0], v[:, 1], s=0.2, c=np.clip(v[:, 2], 0, 2.5), cmap="Greys", alpha=0.4)
    colours = plt.cm.tab10(np.arange(max(1, len(found))) % 10)
    for obj, colour in zip(found, colours):
        m = obj.mesh.vertices
        ax.scatter(m[:, 0], m[:, 1], s=1.5, color=colour)
        lo, hi = obj.bbox_min, obj.bbox_max
        ax.add_patch(plt.Rectangle((lo[0], lo[1]), hi[0] - lo[0], hi[1] - lo[1], fill=False,
                                   color=colour, lw=1.5))
        ax.annotate(f"object {obj.id}", (hi[0], hi[1]), color=colour, fontsize=8)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"room, session 1 against session 0: {len(found)} objects moved "
                 f"({len(sessions[0])} frames a session)")
    fig.savefig(args.out, dpi=120, bbox_inches="tight")
    print(f"{len(found)} objects moved; static mesh {len(static.faces)} faces; wrote {args.out}")


if __name__ == "__main__":
    main()
