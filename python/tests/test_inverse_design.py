"""Inverse design from Python: `Graph.drag` (the same solve as `cnets drag`) and `Graph.optimize`
with faces kept convex (docs/optimizer.md, docs/editor/3d-view.md, Dragging the net)."""

import json
import subprocess

import pytest

import cnets
from conftest import REPO

DEFAULT = REPO / "graphs" / "editor-default.ron"


def vertex_at(apex, ratio, i, j):
    g = cnets.Graph.load(DEFAULT)
    g.set("apex.value", apex)
    g.set("ratio.value", ratio)
    mesh = g.outputs("construct")["mesh"]
    return [float(c) for c in mesh.vertices[i, j]]


def test_drag_matches_the_command_line(cnets_bin):
    target = vertex_at(0.9, 0.42, 5, 9)
    g = cnets.Graph.load(DEFAULT)
    report = g.drag("construct", (5, 9), target)
    assert report["distance_left"] < 1e-9
    assert report["not_convex"] == {"construct": 0}
    py = {c["input"]: c["new"] for c in report["changes"]}
    # The graph keeps the new values.
    assert g.get("apex.value") == pytest.approx(py["apex.value"], abs=0)
    out = subprocess.run(
        [str(cnets_bin), "drag", str(DEFAULT), "--node", "construct", "--vertex", "5,9",
         "--to", ",".join(repr(c) for c in target), "--json"],
        capture_output=True, text=True, check=True,
    )
    cli = {c["input"]: c["new"] for c in json.loads(out.stdout)["changes"]}
    assert py.keys() == cli.keys()
    for k in py:
        assert abs(py[k] - cli[k]) <= 1e-9, (k, py[k], cli[k])


def test_drag_with_pins_and_free_inputs():
    target = vertex_at(1.0, 0.45, 5, 9)
    g = cnets.Graph.load(DEFAULT)
    report = g.drag("construct", (5, 9), target, pins=[(0, 0)], free=["ratio.value"])
    assert [c["input"] for c in report["changes"]] == ["ratio.value"]
    # Row 0 column 0 is the generatrix's first point: no slider moves it.
    assert report["pin_drift"] == 0.0
    assert report["distance_left"] < 1e-9
    with pytest.raises(cnets.CnetsError, match="out of range"):
        g.drag("construct", (99, 0), target)
    with pytest.raises(cnets.CnetsError, match="no node 'nope'"):
        g.drag("nope", (0, 0), target)


def test_optimize_keeps_faces_convex():
    g = cnets.Graph.load(REPO / "graphs" / "catamaran-hull.ron")
    report = g.optimize(max_iter=8, convex="hull")
    assert report["not_convex"] == {"hull": 0}
    assert report["objective"] < report["start"]
    assert set(report) >= {"finite_difference_nodes", "exact_gradients", "variables", "notes"}
