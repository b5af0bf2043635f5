#!/usr/bin/env python3
"""The peer of `ctube.construct` in docs/engine.md: the same C-tube recurrence as a plain
vectorised numpy loop over the directrix (all generatrix rows at once), Monge (bisecting) planes,
a constant apex value. Vertices only: no configurations, no quality, no checks.

    V = a (G_{:,j-1} - X_{j-1}) + X_j - G_{:,j-1}
    d = ((X_j - G_{:,j-1}) . P_j) / (V . P_j)
    G_{:,j} = G_{:,j-1} + d V

    python3 scripts/peers/numpy_ctube.py [SIZE] [REPEATS]

prints the best and median wall time of the loop (the input design is built outside the timing).
Not run in CI.
"""
import sys
import time

import numpy as np

from make_inputs import design


def bisectors(x):
    """Unit normals of the bisecting planes at X_1 ... X_{M-1} (the last one perpendicular to the
    last edge), oriented along the directrix."""
    e = np.diff(x, axis=0)
    e /= np.linalg.norm(e, axis=1, keepdims=True)
    p = np.empty_like(e)
    p[:-1] = e[:-1] + e[1:]
    p[-1] = e[-1]
    p /= np.linalg.norm(p, axis=1, keepdims=True)
    return p


def ctube(x, g0, a, planes):
    n, m = len(g0), len(x)
    out = np.empty((n, m, 3))
    out[:, 0] = g = g0
    for j in range(1, m):
        p = planes[j - 1]
        v = a * (g - x[j - 1]) + x[j] - g
        d = ((x[j] - g) @ p) / (v @ p)
        g = g + d[:, None] * v
        out[:, j] = g
    return out


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    x, g0 = design(size, size)
    planes = bisectors(x)
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        mesh = ctube(x, g0, 0.9, planes)
        times.append(time.perf_counter() - start)
    assert np.isfinite(mesh).all()
    times.sort()
    print(
        f"numpy ctube {size}x{size}: best {times[0] * 1e3:.1f} ms, "
        f"median {times[len(times) // 2] * 1e3:.1f} ms ({repeats} runs, "
        f"numpy {np.__version__})"
    )


if __name__ == "__main__":
    main()
