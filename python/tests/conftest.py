"""Shared fixtures: small graph files and curves for the cnets tests."""

from pathlib import Path

import numpy as np
import pytest

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
    s = np.linspace(0.0, 1.0, n)
    return np.c_[radius + 0.8 * s + 0.3 * np.sin(3 * s), np.zeros(n), height * s]
