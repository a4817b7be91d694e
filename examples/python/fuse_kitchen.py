#!/usr/bin/env python3
"""Fuses the redkitchen sample from Python and draws an ESDF slice through the cameras' mean
position, level with the camera's image rows (the dataset's world frame has no "up": the mean of
the cameras' image-down axes stands in for gravity), with the mesh's vertices near the slice as
the surfaces' outline.

    python3 examples/python/fuse_kitchen.py [--data ../shared/data/redkitchen] [--out kitchen.png]
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import strata  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.path.join(HERE, "../../../shared/data/redkitchen"))
    parser.add_argument("--out", default="kitchen_esdf.png")
    parser.add_argument("--voxel", type=float, default=0.04, help="voxel size, metres")
    args = parser.parse_args()

    data = strata.io.Dataset(args.data)
    config = strata.MapperConfig(strata.MapConfig(voxel_size_m=args.voxel, allocate_free_space=True),
                                 esdf=True)
    mapper = strata.Mapper(config)
    centres, downs = [], []
    for i in range(len(data)):
        frame = data[i]
        mapper.integrate(frame["depth"], data.intrinsics, frame["T_W_C"], frame["color"])
        centres.append(frame["T_W_C"][:3, 3])
        downs.append(frame["T_W_C"][:3, 1])  # the camera's y axis: image down
    mapper.update_esdf()
    mesh = mapper.mesh()

    # The slice plane: through the mean camera centre, normal to the mean image-down axis.
    centre = np.mean(centres, axis=0)
    normal = np.mean(downs, axis=0)
    normal /= np.linalg.norm(normal)
    e1 = np.cross(normal, [1.0, 0.0, 0.0] if abs(normal[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    rel = mesh.vertices - centre
    a, b, h = rel @ e1, rel @ e2, rel @ normal
    step = args.voxel / 2
    xs = np.arange(a.min(), a.max(), step)
    ys = np.arange(b.min(), b.max(), step)
    ga, gb = np.meshgrid(xs, ys)
    points = (centre + ga.ravel()[:, None] * e1 + gb.ravel()[:, None] * e2).astype(np.float32)
    distance, _, known = mapper.distance(points)
    image = np.where(known, distance, np.nan).reshape(ga.shape)
    near = np.abs(h) < args.voxel

    fig, ax = plt.subplots(figsize=(7, 6))
    shown = ax.imshow(image, origin="lower", extent=(xs[0], xs[-1], ys[0], ys[-1]),
                      cmap="RdYlBu", vmin=-0.2, vmax=1.0)
    ax.scatter(a[near], b[near], s=0.5, c="k", label="mesh vertices within a voxel of the slice")
    ax.set_title(f"redkitchen, {len(data)} frames fused from Python: ESDF slice at the cameras")
    ax.set_xlabel("along the slice (m)")
    ax.set_ylabel("across (m)")
    ax.legend(loc="upper right", fontsize=8)
    fig.colorbar(shown, ax=ax, label="distance to the nearest surface (m)")
    fig.savefig(args.out, dpi=120, bbox_inches="tight")
    print(f"{len(data)} frames, {mapper.block_count} blocks, {len(mesh.faces)} faces; wrote {args.out}")


if __name__ == "__main__":
    main()
