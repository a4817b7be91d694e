#!/usr/bin/python3
"""A large mesh for the viewer's load benchmark: a wavy 20 m x 20 m surface of N x N vertices
(2 (N-1)^2 triangles; N = 1001 gives 2 M), coloured by height, written as binary PLY.

    /usr/bin/python3 bench/view/make_mesh.py OUT.ply [--side 1001]
"""
import argparse

import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--side", type=int, default=1001)
    a = parser.parse_args()
    n = a.side
    xs = np.linspace(-10.0, 10.0, n, dtype=np.float32)
    x, y = np.meshgrid(xs, xs)
    z = (0.6 * np.sin(x * 0.9) * np.cos(y * 0.7) + 0.1 * np.sin(3.1 * x + 2.3 * y)).astype(np.float32)
    vertices = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    t = (z.ravel() - z.min()) / max(float(z.max() - z.min()), 1e-6)
    colors = np.stack([60 + 180 * t, 120 + 60 * (1 - t), 200 - 150 * t], axis=1).astype(np.uint8)
    i = np.arange(n - 1)
    r, c = np.meshgrid(i, i, indexing="ij")
    v0 = (r * n + c).ravel()
    quads = np.stack([v0, v0 + 1, v0 + n, v0 + n + 1], axis=1)
    tris = np.concatenate([quads[:, [0, 2, 1]], quads[:, [1, 2, 3]]]).astype(np.int32)
    vertex = np.empty(len(vertices), dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"),
                                            ("red", "u1"), ("green", "u1"), ("blue", "u1")])
    vertex["x"], vertex["y"], vertex["z"] = vertices[:, 0], vertices[:, 1], vertices[:, 2]
    vertex["red"], vertex["green"], vertex["blue"] = colors[:, 0], colors[:, 1], colors[:, 2]
    face = np.empty(len(tris), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    face["n"] = 3
    face["i"] = tris
    header = (f"ply\nformat binary_little_endian 1.0\nelement vertex {len(vertex)}\n"
              "property float x\nproperty float y\nproperty float z\n"
              "property uchar red\nproperty uchar green\nproperty uchar blue\n"
              f"element face {len(face)}\nproperty list uchar int vertex_indices\nend_header\n")
    with open(a.out, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(vertex.tobytes())
        f.write(face.tobytes())
    print(f"{a.out}: {len(vertex)} vertices, {len(face)} triangles")


if __name__ == "__main__":
    main()
