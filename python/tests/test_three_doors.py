"""One answer through every door (issue 27 §1), the Python door.

``crates/headless/tests/it/three_doors.rs`` evaluates every node type on random inputs through a
graph file's RON, ``cnets eval`` JSON (the ``cnets`` binary included) and packed lists, and writes
its cases with the ``cnets eval`` answers to ``<target>/tmp/three_doors_cases.json``. Here each
case's JSON inputs are given to ``cnets.eval`` as a Python user would write them (lists, floats and
ints as JSON has them, ``cnets.Polyline`` / ``QuadMesh`` / ``PolygonMesh`` for geometry objects,
dicts for records and planes), and the outputs must be the CLI's: the same numbers, texts,
booleans and shapes (numpy arrays read as lists), or the same error.
"""

import json
import os
import subprocess
import warnings
from pathlib import Path

import numpy as np
import pytest

import cnets

ROOT = Path(__file__).resolve().parents[2]


def cases_path() -> Path:
    """The cases the Rust test wrote; it is run first when they are missing."""
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    path = target / "tmp" / "three_doors_cases.json"
    if not path.exists():
        subprocess.run(
            ["cargo", "test", "-p", "cnets", "--test", "it", "three_doors::"], cwd=ROOT,
            check=True
        )
    return path


@pytest.fixture(scope="module")
def cases():
    return json.loads(cases_path().read_text())


def base_type(type_name: str) -> str:
    """``tree<list<number>>`` → ``number``."""
    while "<" in type_name:
        type_name = type_name[type_name.index("<") + 1 : type_name.rindex(">")]
    return type_name


def to_python(v, base: str):
    """A JSON input value as a Python user writes it for a port whose items are ``base``."""
    if isinstance(v, list):
        return [to_python(x, base) for x in v]
    if isinstance(v, dict):
        if "rows" in v and "vertices" in v:
            vertices = np.asarray(v["vertices"], dtype=np.float64).reshape(v["rows"], v["cols"], 3)
            return cnets.QuadMesh(vertices, v.get("wrap_rows", False), v.get("wrap_cols", False))
        if "points" in v:
            points = np.asarray(v["points"], dtype=np.float64).reshape(-1, 3)
            return cnets.Polyline(points, v.get("closed", False))
        if "faces" in v:
            vertices = np.asarray(v["vertices"], dtype=np.float64).reshape(-1, 3)
            return cnets.PolygonMesh(vertices, v["faces"], v.get("parts"), v.get("face_parts"))
        if base == "plane":
            return dict(v)
        return {k: to_python(x, "any") for k, x in v.items()}
    return v


def from_python(v):
    """An output of ``cnets.eval`` in the runner's JSON encoding (NaN and ∞ as ``None``)."""
    if isinstance(v, np.ndarray):
        return from_python(v.tolist())
    if isinstance(v, cnets.QuadMesh):
        rows, cols = v.vertices.shape[:2]
        return {
            "rows": rows,
            "cols": cols,
            "wrap_rows": v.wrap_rows,
            "wrap_cols": v.wrap_cols,
            "vertices": from_python(v.vertices.reshape(-1, 3)),
        }
    if isinstance(v, cnets.Polyline):
        return {"points": from_python(v.points), "closed": v.closed}
    if isinstance(v, cnets.PolygonMesh):
        mesh = {"vertices": from_python(v.vertices), "faces": [list(f) for f in v.faces]}
        if v.parts is not None:
            # A joined structure's named parts, as the JSON carries them.
            mesh["parts"] = list(v.parts)
            mesh["face_parts"] = [int(p) for p in v.face_parts]
        return mesh
    if isinstance(v, dict):
        return {k: from_python(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [from_python(x) for x in v]
    if isinstance(v, (np.bool_, bool)):
        return bool(v)
    if isinstance(v, (np.integer, int)):
        return int(v)
    if isinstance(v, (np.floating, float)):
        return float(v) if np.isfinite(v) else None
    return v


def same(a, b, path="") -> str:
    """'' when the Python output ``a`` equals the CLI's JSON ``b``, else where they differ.
    Numbers compare by value (numpy gives floats where JSON has integers in a mixed list), booleans
    only with booleans; a point of NaN (an apex at infinity in a numpy table) is JSON's null."""
    if isinstance(a, bool) or isinstance(b, bool):
        return "" if type(a) is type(b) and a == b else f"{path}: {a!r} != {b!r}"
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return "" if float(a) == float(b) else f"{path}: {a!r} != {b!r}"
    if b is None and isinstance(a, list) and all(x is None for x in a):
        return ""
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return f"{path}: {len(a)} items != {len(b)}"
        for k, (x, y) in enumerate(zip(a, b)):
            d = same(x, y, f"{path}[{k}]")
            if d:
                return d
        return ""
    if isinstance(a, dict) and isinstance(b, dict):
        if list(a) != list(b):
            return f"{path}: fields {list(a)} != {list(b)}"
        for k in a:
            d = same(a[k], b[k], f"{path}.{k}")
            if d:
                return d
        return ""
    return "" if a == b else f"{path}: {a!r} != {b!r}"


def run_case(case) -> str:
    """'' when ``cnets.eval`` answers as ``cnets eval`` did, else what differs."""
    node = case["node"]
    inputs = {
        name: to_python(value, base_type(case["types"][name]))
        for name, value in case["inputs"].items()
    }
    shown = f"{node} {json.dumps(case['inputs'])}"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            outputs = cnets.eval(node, **inputs)
        except cnets.CnetsError as e:
            if "error" not in case:
                return f"{shown}: cnets.eval failed ({e}), cnets eval gave outputs"
            if str(e) != case["error"]:
                return f"{shown}: cnets.eval says {str(e)!r}, cnets eval {case['error']!r}"
            return ""
    if "error" in case:
        return f"{shown}: cnets.eval gave outputs, cnets eval failed with {case['error']!r}"
    got = {k: from_python(v) for k, v in outputs.items() if k != "__files__"}
    diff = same(got, case["outputs"], "outputs")
    if diff:
        return f"{shown}: {diff}"
    # The Rust test records the CLI's warnings with every answer that has outputs (also none).
    said = [str(w.message) for w in caught]
    if said != case["warnings"]:
        return f"{shown}: warnings {said} != {case['warnings']}"
    return ""


def test_every_node_type_is_in_the_cases(cases):
    nodes = {c["node"] for c in cases}
    assert len(nodes) > 100, f"only {len(nodes)} node types"
    assert {"list.cross_reference", "list.flatten", "list.transpose", "view.panel"} <= nodes
    # Inputs on `any` ports include plain lists, tables and integers (the cases of issue 27).
    assert any(
        isinstance(v, list) and v and all(isinstance(x, list) for x in v)
        for c in cases
        for v in c["inputs"].values()
    )


def test_cnets_eval_answers_as_the_cli(cases):
    failures = [f for f in map(run_case, cases) if f]
    assert not failures, f"{len(failures)} of {len(cases)} cases differ:\n" + "\n".join(
        failures[:20]
    )


def test_the_issue_cases_give_the_graph_file_answers():
    """The five calls of issue 27 §1, with the answers a graph file gives."""
    out = cnets.eval("list.cross_reference", a=[1, 2], b=[10, 20, 30])
    assert from_python(out["a"]) == [1, 1, 1, 2, 2, 2]
    assert from_python(out["b"]) == [10, 20, 30, 10, 20, 30]
    out = cnets.eval("list.flatten", tree=[[1, 2, 3], [10, 20, 30]])
    assert from_python(out["list"]) == [1, 2, 3, 10, 20, 30]
    out = cnets.eval("list.transpose", table=[[1, 2, 3], [10, 20, 30]])
    assert from_python(out["table"]) == [[1, 10], [2, 20], [3, 30]]
    out = cnets.eval("list.weave", lists=[[1, 2, 3], [10, 20, 30]], pattern=[0, 1])
    assert from_python(out["list"]) == [1, 10, 2, 20, 3, 30]
