#!/usr/bin/env python3
"""Writes the JSON inputs of the construction timings (docs/engine.md, Timing targets).

The design is the one of the criterion benchmarks (crates/geometry/benches/construction.rs,
crates/nodes/benches/construct_node.rs): a helix-like directrix of M points and a generatrix arc of
N points in the plane through X_0 perpendicular to the first edge.

    python3 scripts/peers/make_inputs.py [SIZE] [DIR]

writes DIR/ctube.json (`ctube.construct`: Monge planes, apex 0.9) and DIR/construct.json
(`cnets.construct`: a per-vertex ratio table, the benchmark's apex profile, assistance 0.5).
Not run in CI.
"""
import json
import math
import os
import sys

import numpy as np


def design(n, m):
    t = np.arange(m) / (m - 1)
    d = np.stack([10 * np.cos(1.2 * t), 10 * np.sin(1.2 * t), 3 * t], axis=1)
    x0, x1 = d[0], d[1]
    e = (x1 - x0) / np.linalg.norm(x1 - x0)
    inward = -x0 - np.dot(-x0, e) * e
    inward /= np.linalg.norm(inward)
    up = np.cross(e, inward)
    phi = math.pi * (0.2 + 0.6 * np.arange(n) / (n - 1))
    g = x0 + np.outer(1.5 * np.sin(phi), inward) + np.outer(1.5 * np.cos(phi), up)
    return d, g


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    out = sys.argv[2] if len(sys.argv) > 2 else "."
    os.makedirs(out, exist_ok=True)
    d, g = design(size, size)
    with open(os.path.join(out, "ctube.json"), "w") as f:
        json.dump({"directrix": d.tolist(), "generatrix": g.tolist(), "apex": 0.9}, f)
    k = np.arange(size - 1)
    apex = 1.0 + 0.3 / size * np.sin(k * 0.05)
    i = np.arange(size)[:, None]
    ratios = 0.5 + 0.1 * np.sin(i * 0.01 + k[None, :] * 0.02)
    with open(os.path.join(out, "construct.json"), "w") as f:
        json.dump(
            {
                "directrix": d.tolist(),
                "generatrix": g.tolist(),
                "apex": apex.tolist(),
                "ratios": ratios.tolist(),
                "assistance": 0.5,
            },
            f,
        )


if __name__ == "__main__":
    main()
