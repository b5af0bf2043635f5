"""Shared fixtures: small graph files and curves for the cnets tests, the repository's folders,
and a Hops server started as `python -m cnets.hops` on a free loopback port."""

import os
import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
GRAPHS = REPO / "graphs"
LIBRARY = GRAPHS / "library"

DESIGN = """(
    version: 1,
    name: "test design",
    description: "An arc directrix, a straight generatrix, a cone-net; two sliders.",
    nodes: {
        "radius": (type: "param.number", inputs: {"value": 5.0, "min": 1.0, "max": 20.0}),
        "apex": (type: "param.number", inputs: {"value": 1.0, "min": 0.5, "max": 1.5}),
        "dir": (type: "curve.arc", inputs: {"end": 120.0, "count": 12}),
        "gen": (type: "curve.line", inputs: {"start": (5.0, 0.0, 0.0), "end": (6.0, 0.0, 3.0), "count": 6}),
        "net": (type: "cnets.construct"),
        "len": (type: "curve.length"),
    },
    edges: [
        "radius.value -> dir.radius",
        "apex.value -> net.apex",
        "dir.curve -> net.directrix",
        "gen.curve -> net.generatrix",
        "dir.curve -> len.curve",
    ],
)
"""

CLUSTER = """(
    version: 1,
    name: "arc length",
    description: "The length of an arc of a given radius.",
    nodes: {
        "r": (type: "graph.input", inputs: {"name": "radius", "type": "number", "default": 1.0, "doc": "Radius."}),
        "arc": (type: "curve.arc", inputs: {"end": 180.0, "count": 65}),
        "len": (type: "curve.length"),
        "out": (type: "graph.output", inputs: {"name": "length", "type": "number", "doc": "Arc length."}),
    },
    edges: ["r.value -> arc.radius", "arc.curve -> len.curve", "len.length -> out.value"],
)
"""


@pytest.fixture
def design(tmp_path: Path) -> Path:
    path = tmp_path / "design.ron"
    path.write_text(DESIGN)
    return path


@pytest.fixture
def library(tmp_path: Path) -> Path:
    lib = tmp_path / "library"
    lib.mkdir()
    (lib / "arc-length.ron").write_text(CLUSTER)
    return lib


def arc(n: int, radius: float = 5.0, degrees: float = 120.0) -> np.ndarray:
    t = np.radians(np.linspace(0.0, degrees, n))
    return np.c_[radius * np.cos(t), radius * np.sin(t), np.zeros(n)]


def profile(n: int, radius: float = 5.0, height: float = 3.0) -> np.ndarray:
    """A generatrix starting on the directrix's first point (radius, 0, 0)."""
    s = np.linspace(0.0, 1.0, n)
    return np.c_[radius + 0.8 * s + 0.3 * np.sin(3 * s), np.zeros(n), height * s]


def lifted(n: int, radius: float = 5.0, height: float = 3.0) -> np.ndarray:
    """A generatrix drawn as the docs advise: starting off the directrix (half a unit above)."""
    return profile(n, radius, height) + [0.0, 0.0, 0.5]


class HopsProcess:
    """`python -m cnets.hops` on a loopback port of its own choosing (`--port 0`: no other
    process can take it between a probe and the bind); `log()` is what it printed."""

    def __init__(self, log_path: Path, *args: str) -> None:
        self.log_path = log_path
        self._log = open(log_path, "w+b")
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "cnets.hops", "--port", "0", *args],
            stdout=self._log, stderr=subprocess.STDOUT, cwd=str(REPO),
        )
        deadline = time.monotonic() + 120
        # The port it listens on, from its start line ("... on http://127.0.0.1:PORT/").
        while (found := re.search(r" on http://127\.0\.0\.1:(\d+)/", self.log())) is None:
            if self.proc.poll() is not None or time.monotonic() > deadline:
                self.stop()
                raise RuntimeError(f"the Hops server did not start: {self.log()}")
            time.sleep(0.05)
        self.port = int(found.group(1))
        self.url = f"http://127.0.0.1:{self.port}"
        while True:
            try:
                urllib.request.urlopen(self.url + "/", timeout=30).read()
                break
            except OSError:  # not answering yet (URLError, a refused or timed-out connection)
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    self.stop()
                    raise RuntimeError(f"the Hops server did not answer: {self.log()}")
                time.sleep(0.1)

    def log(self) -> str:
        return self.log_path.read_bytes().decode(errors="replace")

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self._log.close()


@pytest.fixture(scope="session")
def cnets_bin() -> Path:
    """The `cnets` command line (scripts/test-python.sh builds it; CNETS_BIN names another)."""
    path = Path(os.environ.get("CNETS_BIN") or REPO / "target" / "debug" / "cnets")
    assert path.is_file(), f"no cnets binary at {path}: cargo build -p cnets, or set CNETS_BIN"
    return path
