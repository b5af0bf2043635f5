#!/usr/bin/env python3
"""The peer of one exact gradient in docs/optimizer.md: PyTorch autograd through the public C-tubes
construction (github.com/EPFL-LGG/C-tubes, `Ctubes.tube_generation.compute_ctube`) on the design of
the construction timings (make_inputs.py), float64, 2 threads.

The objective is a vertex distance, sum |V - T|^2 over the SIZE x SIZE vertices, against a target T
made by the same construction with other apex values (so the gradient is not zero). The variables
are every input C-tubes optimizes: the generatrix (N x 3), the plane normals (M x 3) and the apex
locating function (M - 1). One gradient = one forward construction recorded on the tape plus the
backward pass; the script times both parts, best and median of REPEATS runs.

The C-tubes code is not part of cnets: clone it anywhere and point CTUBES_DIR at its `python/`
folder (it needs torch and numpy):

    CTUBES_DIR=/path/to/C-tubes/python python3 scripts/peers/torch_ctubes_gradient.py [SIZE] [REPEATS]

Not run in CI.
"""
import os
import sys
import time

import numpy as np
import torch

from make_inputs import design

sys.path.insert(0, os.environ.get("CTUBES_DIR", "C-tubes/python"))
from Ctubes.geometry_utils import compute_plane_normals  # noqa: E402
from Ctubes.tube_generation import compute_ctube  # noqa: E402


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    torch.set_num_threads(2)
    torch.set_default_dtype(torch.float64)
    d, g = design(size, size)
    x = torch.tensor(d)
    normals0 = compute_plane_normals(x, kind="bisecting", closed_curve=False)
    k = torch.arange(size - 1, dtype=torch.float64)
    with torch.no_grad():
        target = compute_ctube(
            x, torch.tensor(g), plane_normals=normals0, apex_loc_func=0.95 + 0.02 * torch.sin(0.1 * k),
            closed_curve=False,
        )
    forward, backward, total = [], [], []
    for _ in range(repeats):
        g0 = torch.tensor(g, requires_grad=True)
        normals = normals0.clone().requires_grad_(True)
        apex = torch.full((size - 1,), 0.9, requires_grad=True)
        t0 = time.perf_counter()
        mesh = compute_ctube(x, g0, plane_normals=normals, apex_loc_func=apex, closed_curve=False)
        objective = ((mesh - target) ** 2).sum()
        t1 = time.perf_counter()
        objective.backward()
        t2 = time.perf_counter()
        forward.append(t1 - t0)
        backward.append(t2 - t1)
        total.append(t2 - t0)
        assert torch.isfinite(apex.grad).all() and torch.isfinite(g0.grad).all()
    count = g0.numel() + normals.numel() + apex.numel()
    for name, times in (("forward (taped)", forward), ("backward", backward), ("one gradient", total)):
        times.sort()
        print(
            f"PyTorch C-tubes {size}x{size} {name}: best {times[0] * 1e3:.1f} ms, "
            f"median {times[len(times) // 2] * 1e3:.1f} ms"
        )
    print(
        f"({repeats} runs, {count} variables, objective {objective.item():.4g}, torch {torch.__version__}, "
        f"{torch.get_num_threads()} threads, float64)"
    )


if __name__ == "__main__":
    main()
