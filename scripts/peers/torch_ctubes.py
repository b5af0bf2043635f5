#!/usr/bin/env python3
"""The peer of `ctube.construct` in docs/engine.md: the public PyTorch C-tubes code
(github.com/EPFL-LGG/C-tubes, `Ctubes.tube_generation.compute_ctube`) on the same design, Monge
(bisecting) planes, apex 0.9, float64, 2 threads.

The C-tubes code is not part of cnets: clone it anywhere and point CTUBES_DIR at its `python/`
folder (it needs torch and numpy):

    CTUBES_DIR=/path/to/C-tubes/python python3 scripts/peers/torch_ctubes.py [SIZE] [REPEATS]

Not run in CI.
"""
import os
import sys
import time

import numpy as np
import torch

from make_inputs import design

sys.path.insert(0, os.environ.get("CTUBES_DIR", "C-tubes/python"))
from Ctubes.tube_generation import compute_ctube  # noqa: E402


def main():
    size = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    torch.set_num_threads(2)
    torch.set_default_dtype(torch.float64)
    d, g = design(size, size)
    x = torch.tensor(d)
    g0 = torch.tensor(g)
    a = torch.full((size - 1,), 0.9)
    times = []
    with torch.no_grad():
        for _ in range(repeats):
            start = time.perf_counter()
            mesh = compute_ctube(x, g0, apex_loc_func=a, closed_curve=False)
            times.append(time.perf_counter() - start)
    assert torch.isfinite(mesh).all()
    times.sort()
    print(
        f"PyTorch C-tubes {size}x{size}: best {times[0] * 1e3:.1f} ms, "
        f"median {times[len(times) // 2] * 1e3:.1f} ms ({repeats} runs, torch {torch.__version__}, "
        f"{torch.get_num_threads()} threads, float64)"
    )


if __name__ == "__main__":
    main()
