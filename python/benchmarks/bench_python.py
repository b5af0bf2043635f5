"""Speed figures of the cnets Python package, reported, never asserted (issue 30: a busy machine
must not fail a test). Run with the interpreter whose cnets you measure, from the repository root:

    python python/benchmarks/bench_python.py            # both figures
    python python/benchmarks/bench_python.py hops       # only the Hops solve
    python python/benchmarks/bench_python.py construct  # only cnets.construct's overhead

- ``construct``: ``cnets.construct`` at 100 × 100 end to end from Python against the node's own
  evaluation time in the same call (``cnets._cnets.last_eval_seconds()``), best of 60 calls.
- ``hops``: the Hops server (``python -m cnets.hops`` on a free loopback port, its output to a
  file) solving ``/cnets_construct`` for a 150-point directrix, a 100-point generatrix, 149 apex
  values and a 100 × 149 ratio tree (a 100 × 150 mesh, 15 000 vertices), posted as Grasshopper's
  Hops component posts it; end to end on the client (request sent → whole response read), best
  and median of 30 solves after 3 warm-up solves.

The figures are in docs/python.md (Speed).
"""

from __future__ import annotations

import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

import numpy as np


def construct_overhead(calls: int = 60) -> None:
    import cnets

    t = np.radians(np.linspace(0.0, 120.0, 100))
    d = np.c_[5 * np.cos(t), 5 * np.sin(t), np.zeros(100)]
    s = np.linspace(0.0, 1.0, 100)
    g = np.c_[5.5 + 0.8 * s, np.zeros(100), 3 * s]
    totals, nodes = [], []
    for _ in range(calls):
        t0 = time.perf_counter()
        cnets.construct(d, g, apex=0.95, ratios=0.5)
        totals.append(time.perf_counter() - t0)
        nodes.append(cnets._cnets.last_eval_seconds())
    best_total, best_node = min(totals), min(nodes)
    print(f"cnets.construct 100 x 100: end to end {best_total * 1e3:.3f} ms (median "
          f"{statistics.median(totals) * 1e3:.3f}), the node {best_node * 1e3:.3f} ms (median "
          f"{statistics.median(nodes) * 1e3:.3f}), ratio {best_total / best_node:.2f}")


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _number_items(values):
    return [{"type": "System.Double", "data": json.dumps(float(v))} for v in values]


def hops_payload(rows: int = 100, cols: int = 150) -> bytes:
    """The request Grasshopper's Hops component sends for /cnets_construct."""
    import rhino3dm

    t = np.radians(np.linspace(0.0, 120.0, cols))
    directrix = np.c_[8 * np.cos(t), 8 * np.sin(t), np.zeros(cols)]
    s = np.linspace(0.0, 1.0, rows)
    generatrix = np.c_[8.5 + 0.8 * s, np.zeros(rows), 4 * s]

    def curve(points):
        c = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in points.tolist()])
        return {"type": "Rhino.Geometry.PolylineCurve", "data": json.dumps(c.Encode())}

    ratios = 0.5 + 0.08 * np.sin(np.linspace(0, 3, rows))[:, None] * np.cos(
        np.linspace(0, 2, cols - 1))[None, :]
    values = [
        {"ParamName": "Directrix", "InnerTree": {"{0}": [curve(directrix)]}},
        {"ParamName": "Generatrix", "InnerTree": {"{0}": [curve(generatrix)]}},
        {"ParamName": "Apex", "InnerTree": {"{0}": _number_items(np.linspace(0.97, 1.02, cols - 1))}},
        {"ParamName": "Ratios", "InnerTree": {f"{{{i}}}": _number_items(ratios[i]) for i in range(rows)}},
        {"ParamName": "Assistance", "InnerTree": {"{0}": _number_items([-1.0])}},
    ]
    return json.dumps({"values": values}).encode()


def hops_solve(solves: int = 30) -> None:
    port = _free_port()
    with tempfile.TemporaryDirectory() as tmp:
        log = open(os.path.join(tmp, "hops.log"), "w+b")
        proc = subprocess.Popen([sys.executable, "-m", "cnets.hops", "--port", str(port)],
                                stdout=log, stderr=subprocess.STDOUT)
        url = f"http://127.0.0.1:{port}"
        try:
            deadline = time.time() + 60
            while True:
                try:
                    urllib.request.urlopen(url + "/", timeout=5).read()
                    break
                except OSError:
                    if proc.poll() is not None or time.time() > deadline:
                        log.seek(0)
                        raise RuntimeError("the Hops server did not start: "
                                           + log.read().decode(errors="replace"))
                    time.sleep(0.1)
            body = hops_payload()
            times = []
            for k in range(solves + 3):
                request = urllib.request.Request(url + "/cnets_construct", data=body, method="POST",
                                                 headers={"Content-Type": "application/json"})
                t0 = time.perf_counter()
                with urllib.request.urlopen(request, timeout=120) as r:
                    answer = r.read()
                elapsed = time.perf_counter() - t0
                if k >= 3:
                    times.append(elapsed)
            response = json.loads(answer)
            if response.get("errors"):
                raise RuntimeError(f"the solve failed: {response['errors']}")
            print(f"Hops /cnets_construct 100 x 150 (15 000 vertices, ratio tree 100 x 149, "
                  f"{len(body) / 1e6:.2f} MB request, {len(answer) / 1e6:.2f} MB response): best "
                  f"{min(times) * 1e3:.1f} ms, median {statistics.median(times) * 1e3:.1f} ms "
                  f"over {solves} solves")
        finally:
            proc.terminate()
            proc.wait(timeout=10)
            log.close()


if __name__ == "__main__":
    which = sys.argv[1:] or ["construct", "hops"]
    if "construct" in which:
        construct_overhead()
    if "hops" in which:
        hops_solve()
