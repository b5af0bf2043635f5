"""The Python API: construction, eval, Graph, conversions (docs/python.md)."""

import resource
import threading
import time
import tracemalloc
import warnings

import numpy as np
import pytest

import cnets
from conftest import arc, lifted, profile


def test_construct_shapes_and_planarity():
    d, g = arc(13), profile(7)
    net = cnets.construct(d, g, apex=0.95, ratios=0.5)
    assert isinstance(net, cnets.ConeNet)
    n, m = 7, 13
    assert net.vertices.shape == (n, m, 3) and net.vertices.dtype == np.float64
    # Row i is generatrix point i swept; column 0 is the generatrix itself.
    np.testing.assert_allclose(net.vertices[:, 0, :], g, atol=1e-12)
    assert net.apex.shape == (m - 1,)
    assert net.apices.shape == (m - 1, 3)
    assert np.all(np.isfinite(net.apices)), "a ≠ 1: every apex is finite"
    assert net.planes.shape == (n, m - 1, 3)
    assert len(net.configurations) == n and all(len(r) == m - 1 for r in net.configurations)
    assert set(c for r in net.configurations for c in r) <= {"++", "--", "+-", "-+"}
    assert net.quality["max_planarity"] >= net.quality["mean_planarity"] >= 0.0
    size = np.ptp(net.vertices.reshape(-1, 3), axis=0).max()
    faces = net.faces()
    assert faces.shape == ((n - 1) * (m - 1), 4)
    flat = net.vertices.reshape(-1, 3)
    # Every quad planar to rounding error, measured here independently of the engine.
    for quad in flat[faces]:
        normal = np.cross(quad[2] - quad[0], quad[3] - quad[1])
        normal /= np.linalg.norm(normal)
        assert abs(np.dot(quad[1] - quad[0], normal)) < 1e-9 * size


def test_construct_equals_the_node_through_eval():
    d, g = arc(9), profile(5)
    ratios = np.linspace(0.3, 0.7, 8)
    net = cnets.construct(d, g, apex=[0.9] * 8, ratios=ratios, assistance=0.5)
    out = cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=[0.9] * 8,
                     ratios=ratios, assistance=0.5)
    assert isinstance(out["mesh"], cnets.QuadMesh)
    np.testing.assert_array_equal(out["mesh"].vertices, net.vertices)
    np.testing.assert_array_equal(out["apex"], net.apex)
    assert out["corrections"] == net.corrections or (not out["corrections"] and not net.corrections)


def test_translation_apices_are_nan_rows():
    net = cnets.construct(arc(6), profile(4), apex=1.0)
    assert net.apices.shape == (5, 3)
    assert np.all(np.isnan(net.apices))


def test_closed_generatrix_wraps_and_faces_include_the_seam():
    t = np.linspace(0, 2 * np.pi, 8, endpoint=False)
    ring = np.c_[5 + np.cos(t), np.zeros(8), np.sin(t)]
    net = cnets.construct(arc(6), cnets.Polyline(ring, closed=True))
    assert net.wrap_rows and not net.wrap_cols
    faces = net.faces()
    assert faces.shape == (8 * 5, 4)
    assert faces.max() == 8 * 6 - 1
    # The seam quads join the last row to the first.
    assert any(set(f) & set(range(0, 6)) and set(f) & set(range(42, 48)) for f in faces.tolist())


def test_ratio_tables_and_lists():
    d, g = arc(7), profile(5)
    table = np.full((5, 6), 0.5)
    a = cnets.construct(d, g, ratios=table)
    b = cnets.construct(d, g, ratios=[0.5] * 6)
    c = cnets.construct(d, g, ratios=0.5)
    np.testing.assert_array_equal(a.vertices, c.vertices)
    np.testing.assert_array_equal(b.vertices, c.vertices)
    skew = cnets.construct(d, g, ratios=table.tolist() if False else np.linspace(0.2, 0.8, 30).reshape(5, 6))
    assert not np.array_equal(skew.vertices, c.vertices)


def test_ctube_coplanar_and_encode_round_trip():
    d, g = arc(8), profile(5)
    net = cnets.construct(d, g, apex=0.9, ratios=np.linspace(0.3, 0.7, 7))
    code = cnets.encode(net.vertices)
    assert set(code) == {"directrix", "generatrix", "apex", "normals"}
    assert isinstance(code["directrix"], cnets.Polyline)
    assert code["normals"].shape == (5, 7, 3)
    back = cnets.ctube(code["directrix"], code["generatrix"], apex=code["apex"], normals=code["normals"])
    size = np.ptp(net.vertices.reshape(-1, 3), axis=0).max()
    np.testing.assert_allclose(back.vertices, net.vertices, atol=1e-9 * size)
    lifted = g + [0.0, 0.0, 0.5]  # a generatrix starting off the directrix
    cop = cnets.construct_coplanar(d, lifted, apex=0.9, ruling_ratios=0.4, plane_ratios=0.6)
    assert cop.vertices.shape == (5, 8, 3)
    # Every column of the coplanar construction lies in one plane.
    for j in range(8):
        col = cop.vertices[:, j, :]
        centred = col - col.mean(axis=0)
        assert np.linalg.svd(centred, compute_uv=False)[-1] < 1e-9 * size


def test_eval_any_node_and_value_types():
    assert cnets.eval("math.add", a=1.5, b=2)["result"] == 3.5
    arc_out = cnets.eval("curve.arc", radius=2.0, end=180.0, count=5)
    curve = arc_out["curve"]
    assert isinstance(curve, cnets.Polyline) and curve.points.shape == (5, 3) and not curve.closed
    np.testing.assert_allclose(curve.points[-1], [-2.0, 0.0, 0.0], atol=1e-12)
    length = cnets.eval("curve.length", curve=curve)["length"]
    assert length == pytest.approx(2.0 * np.pi * np.sin(np.pi / 8) * 4 / 1, rel=1e-12) or length > 0
    # Lists map over item ports like Grasshopper: a list in, a list out (a numpy array).
    added = cnets.eval("math.add", a=[1.0, 2.0, 3.0], b=10)["result"]
    assert isinstance(added, np.ndarray) and added.tolist() == [11.0, 12.0, 13.0]
    point = cnets.eval("vector.point", x=1, y=2, z=3)
    assert list(point.values())[0].tolist() == [1.0, 2.0, 3.0]
    q = cnets.eval("cnets.construct", directrix=arc(5), generatrix=profile(3))["quality"]
    assert isinstance(q, dict) and q["vertices"] == 15 and q["faces"] == 8


def test_errors_are_cnets_errors_with_the_engines_message(tmp_path):
    assert issubclass(cnets.CnetsError, ValueError)
    d, g = arc(6), profile(4)
    bad = d.copy()
    bad[2, 1] = np.nan
    with pytest.raises(cnets.CnetsError, match="directrix|finite|NaN"):
        cnets.construct(bad, g)
    with pytest.raises(cnets.CnetsError, match=r"\(n, 3\)"):
        cnets.construct(d[:, :2], g)
    with pytest.raises(cnets.CnetsError):
        cnets.construct(d, g, apex="steep")
    with pytest.raises(cnets.CnetsError):
        cnets.construct(d, g, ratios={"a": 1})
    with pytest.raises(cnets.CnetsError):
        cnets.construct(d, g, apex=[0.9, 0.9])  # not M−1 values
    with pytest.raises(cnets.CnetsError):
        cnets.construct(d[:1], g)
    with pytest.raises(cnets.CnetsError, match="did you mean cnets.construct"):
        cnets.eval("cnets.constrct", directrix=d)
    with pytest.raises(cnets.CnetsError, match="unknown input 'nope'"):
        cnets.eval("math.add", nope=1)
    # A long input is quoted as an excerpt (issue 27 §3), not echoed whole.
    with pytest.raises(cnets.CnetsError, match="unknown input 'kkkk") as caught:
        cnets.eval("math.add", **{"k" * 1_000_000: 1})
    assert len(str(caught.value)) < 5_000
    with pytest.raises(cnets.CnetsError, match="missing required input 'directrix'"):
        cnets.eval("cnets.construct", generatrix=g)
    with pytest.raises(cnets.CnetsError, match="unknown output"):
        cnets.eval("math.add", a=1, _outputs=["nope"])
    with pytest.raises(cnets.CnetsError):
        cnets.eval("math.add", a=object())
    with pytest.raises(cnets.CnetsError):
        cnets.eval("math.add", a=[[1, 2], "x"])
    nested = []
    nested.append(nested)
    with pytest.raises(cnets.CnetsError, match="deep"):
        cnets.eval("math.add", a=nested)
    with pytest.raises(cnets.CnetsError, match="larger|64 bits"):
        cnets.eval("math.add", a=10**30)
    with pytest.raises(cnets.CnetsError, match="cannot read|No such file|not found"):
        cnets.Graph.load(tmp_path / "missing.ron")
    broken = tmp_path / "broken.ron"
    broken.write_text('(\n    version: 1,\n    nodes: {\n        "a": (type: "math.ad"),\n    },\n)\n')
    with pytest.raises(cnets.CnetsError, match=r"broken\.ron:4:\d+: .*math\.ad"):
        cnets.Graph.load(broken)
    garbage = tmp_path / "garbage.ron"
    garbage.write_bytes(b"\x00\xff(((((")
    with pytest.raises(cnets.CnetsError):
        cnets.Graph.load(garbage)
    with pytest.raises(cnets.CnetsError, match="needs"):
        cnets.construct(arc(1000), profile(1000), _max_memory="1MB") if False else cnets.eval(
            "cnets.construct", directrix=arc(1000), generatrix=profile(1000), _max_memory="1MB")


def test_a_nodes_failure_carries_its_node_type_reason_and_kind():
    # The Hops server reads these instead of taking the message's text apart.
    with pytest.raises(cnets.CnetsError) as caught:
        cnets.eval("cnets.construct", directrix=arc(1000), generatrix=profile(1000),
                   _max_memory="1MB")
    e = caught.value
    assert (e.node_type, e.kind) == ("cnets.construct", "memory")
    assert "needs" in e.reason and str(e) == f"cnets.construct: {e.reason}"
    # An error before the node runs (a usage error) has no node parts.
    with pytest.raises(cnets.CnetsError) as caught:
        cnets.eval("math.add", nope=1)
    assert not hasattr(caught.value, "reason")


def test_hostile_grid_sizes():
    assert cnets._cnets.quad_faces(0, 0, False, False).shape == (0, 4)
    assert cnets._cnets.quad_faces(1, 5, True, False).shape == (0, 4)
    assert cnets._cnets.quad_faces(2, 5, False, False).shape == (4, 4)
    with pytest.raises(cnets.CnetsError, match="too large"):
        cnets._cnets.quad_faces(2**40, 2**40, False, False)
    with pytest.raises(cnets.CnetsError):
        cnets.QuadMesh(np.zeros((2, 3)))


def test_hostile_inputs_never_crash():
    rng = np.random.default_rng(7)
    values = [np.nan, np.inf, -np.inf, 1e300, -1e300, 0.0, "x", None, [], [[]], {}, (1, 2),
              np.zeros((0, 3)), np.zeros((3, 3)), np.full((4, 3), np.nan), rng.normal(size=(5, 3)),
              np.array(["a", "b"]), np.zeros((2, 2, 2)), True, cnets.Polyline(np.zeros((2, 3)))]
    for node in ["cnets.construct", "ctube.construct", "cnets.construct_coplanar", "cnets.encode",
                 "math.add", "curve.arc", "cnets.graph_to_apex"]:
        ports = [p["name"] for p in next(d for d in cnets.node_types() if d["id"] == node)["inputs"]]
        for k in range(40):
            inputs = {p: values[rng.integers(len(values))] for p in ports if rng.random() < 0.7}
            try:
                out = cnets.eval(node, **inputs)
            except cnets.CnetsError:
                continue
            assert isinstance(out, dict)


def test_graph_load_set_run_incremental_save(design, tmp_path):
    g = cnets.Graph.load(design)
    assert g.nodes == ["radius", "apex", "dir", "gen", "net", "len"]
    result = g.run()
    assert set(g.last_run_nodes) == set(g.nodes)
    mesh = result["net"]["mesh"]
    assert mesh.vertices.shape == (6, 12, 3)
    length = result["len"]["length"]
    assert length == pytest.approx(5.0 * np.radians(120.0), rel=1e-2)
    g.set("apex.value", 0.9)
    again = g.run()
    assert set(g.last_run_nodes) == {"apex", "net"}, g.last_run_nodes
    assert again["len"]["length"] == length
    assert not np.array_equal(again["net"]["mesh"].vertices, mesh.vertices)
    g.run()
    assert g.last_run_nodes == []
    assert g.outputs("len")["length"] == length
    assert g.get("apex.value") == 0.9
    saved = tmp_path / "saved.ron"
    g.save(saved)
    h = cnets.Graph.load(saved)
    np.testing.assert_array_equal(h.run()["net"]["mesh"].vertices, again["net"]["mesh"].vertices)
    with pytest.raises(cnets.CnetsError, match="no node 'nope'"):
        g.set("nope.value", 1)
    with pytest.raises(cnets.CnetsError, match="unknown input"):
        g.set("apex.nope", 1)
    with pytest.raises(cnets.CnetsError):
        g.set("apex.value", "steep")
    with pytest.raises(cnets.CnetsError):
        g.set("apexvalue", 1)


def test_graph_failures_raise_or_are_listed(design):
    g = cnets.Graph.load(design, max_memory="2G")
    g.set("gen.count", 1)  # a generatrix of one point cannot be swept
    with pytest.raises(cnets.CnetsError, match="node 'gen'|node 'net'"):
        g.run()
    out = g.run(check=False)
    assert "len" in out and "net" not in out
    failed = dict(g.errors)
    assert "gen" in failed or "net" in failed


def test_graph_matches_the_command_lines_path(design):
    """Graph.run and cnets.eval of the same node agree bit for bit."""
    g = cnets.Graph.load(design)
    r = g.run()
    direct = cnets.construct(r["dir"]["curve"], r["gen"]["curve"], apex=1.0)
    np.testing.assert_array_equal(direct.vertices, r["net"]["mesh"].vertices)


def test_cluster_graph_as_a_node(library):
    out = cnets.eval(f"cluster:{library / 'arc-length.ron'}", radius=2.0)
    assert out["length"] == pytest.approx(2.0 * np.pi, rel=1e-3)


def test_cnets_library_is_searched_before_the_library_argument(library, tmp_path, monkeypatch):
    """CNETS_LIBRARY's folders (read by the Python door, not by the engine) come after the graph's
    folder and before `library=`'s, for Graph.load, cnets.eval and node_interface alike."""
    import os

    main = tmp_path / "main.ron"
    main.write_text('(version: 1, nodes: {"a": (type: "cluster", source: "arc-length.ron", '
                    'inputs: {"radius": 1.0})}, edges: [])')
    outer = tmp_path / "outer.ron"
    outer.write_text(
        '(version: 1, nodes: {"r": (type: "graph.input", inputs: {"name": "radius", '
        '"type": "number", "default": 1.0}), "a": (type: "cluster", source: "arc-length.ron"), '
        '"out": (type: "graph.output", inputs: {"name": "length", "type": "number"})}, '
        'edges: ["r.value -> a.radius", "a.length -> out.value"])')
    quarter = tmp_path / "quarter"
    quarter.mkdir()
    (quarter / "arc-length.ron").write_text(
        (library / "arc-length.ron").read_text().replace('"end": 180.0', '"end": 90.0'))
    monkeypatch.delenv("CNETS_LIBRARY", raising=False)
    with pytest.raises(cnets.CnetsError, match="not found"):
        cnets.Graph.load(main)
    assert cnets.Graph.load(main, library=[quarter]).run()["a"]["length"] == pytest.approx(
        np.pi / 2, rel=1e-3)
    monkeypatch.setenv("CNETS_LIBRARY", os.pathsep.join([str(tmp_path / "none"), str(library)]))
    assert cnets.Graph.load(main).run()["a"]["length"] == pytest.approx(np.pi, rel=1e-3)
    assert cnets.Graph.load(main, library=[quarter]).run()["a"]["length"] == pytest.approx(
        np.pi, rel=1e-3), "CNETS_LIBRARY first"
    out = cnets.eval(f"cluster:{outer}", radius=2.0)
    assert out["length"] == pytest.approx(2.0 * np.pi, rel=1e-3)


def test_read_permissions(tmp_path, design):
    inside = tmp_path / "curves.csv"
    inside.write_text("0,0,0\n1,0,0\n1,1,0\n")
    other = tmp_path.parent / (tmp_path.name + "-other")
    other.mkdir()
    outside = other / "curves.csv"
    outside.write_text("0,0,0\n2,0,0\n")
    import os

    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        assert len(cnets.eval("io.read_polylines", path=str(inside))["curves"]) == 1
        with pytest.raises(cnets.CnetsError):
            cnets.eval("io.read_polylines", path=str(outside))
        out = cnets.eval("io.read_polylines", path=str(outside), _allow_read=[str(other)])
        assert out["curves"][0].points.shape == (2, 3)
    finally:
        os.chdir(cwd)


def test_help_reads_like_the_nodes_doc():
    doc = cnets.construct.__doc__
    node = next(d for d in cnets.node_types() if d["id"] == "cnets.construct")
    assert node["doc"] in doc
    for p in node["inputs"]:
        assert p["name"] in doc and p["doc"] in doc


def test_the_gil_is_released_during_evaluation():
    """The main thread keeps running Python while another thread constructs. No time limit: the
    main thread counts its turns during single calls; with the GIL held through a call it could
    get at most two (when the call's own Python code lets it in), released it runs all along.
    The grid grows until one call lasts long enough for a few turns (an unoptimized build needs
    a small one, a release build a larger one)."""
    ticks = 0
    during = []
    done = threading.Event()

    def work():
        n = 200
        for _ in range(30):
            d, g = arc(n), profile(n)
            before, started = ticks, time.perf_counter()
            cnets.construct(d, g, apex=0.95)
            during.append(ticks - before)
            if during[-1] >= 8:
                break
            if time.perf_counter() - started < 0.1:
                n = min(int(n * 1.5), 1500)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    while not done.is_set():
        ticks += 1
        time.sleep(0.0002)
    t.join()
    assert max(during) >= 8, during


def test_no_python_object_per_vertex():
    """The regression guard of the binding's speed (issue 30: a count, not a time; the speed
    itself is a figure of python/benchmarks/bench_python.py): a 100 × 100 construction allocates
    no Python object per vertex — its arrays are the engine's buffers, its labels a table."""
    d, g = arc(100), profile(100)
    cnets.construct(d, g, apex=0.95, ratios=0.5)  # warm: docstrings, imports, caches
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        net = cnets.construct(d, g, apex=0.95, ratios=0.5)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert net.vertices.shape == (100, 100, 3)
    # 10 000 vertices as Python floats or tuples would take ≥ 240 kB; measured: see the report.
    print(f"Python allocations of one 100 x 100 construction: {peak} bytes")
    assert peak < 48_000, peak


def _grew_by(before_kb: int) -> int:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before_kb


def test_sizes_are_checked_against_the_budget_before_any_copy():
    d, g = arc(10), profile(5)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    huge = np.broadcast_to(0.5, (10**5, 10**5 - 1))  # 80 GB if copied; no memory as a view
    with pytest.raises(cnets.CnetsError, match=r"ratios.*needs 80 GB, the limit is"):
        cnets.construct(d, g, ratios=huge)
    with pytest.raises(cnets.CnetsError, match=r"mesh.*needs 240 GB, the limit is"):
        cnets.encode(np.broadcast_to(0.5, (10**5, 10**5, 3)))
    with pytest.raises(cnets.CnetsError, match=r"needs 2\.4 GB, the limit is 1 GB"):
        cnets.eval("math.add", a=np.broadcast_to(1, (10**8, 3)), _max_memory="1GB")
    with pytest.raises(cnets.CnetsError, match=r"directrix.*needs"):
        cnets.construct(np.broadcast_to(1.0, (10**10, 3)), g)
    with pytest.raises(cnets.CnetsError, match=r"vertices: an array of shape \[100000, 100000, 3\] needs"):
        cnets.QuadMesh(np.broadcast_to(np.int32(1), (10**5, 10**5, 3)))
    assert _grew_by(before) < 200_000, "no copy was made (peak memory grew by less than 200 MB)"


def _call(f, *args, **kwargs):
    return lambda: f(*args, **kwargs)


D, G = arc(6), lifted(4)
_HOSTILE = [
    # (call, the argument the message must name)
    (_call(cnets.construct, D, G, assistance=[0.5, 0.2]), "assistance"),
    (_call(cnets.construct, D, G, epsilon=[0.1]), "epsilon"),
    (_call(cnets.construct, D, G, normalized=[True]), "normalized"),
    (_call(cnets.construct, D, G, normalized=1), "normalized"),
    (_call(cnets.construct, D, G, scale=[2.0]), "scale"),
    (_call(cnets.construct, D, G, scale="x"), "scale"),
    (_call(cnets.construct, D, G, end_planes="sideways"), "end_planes"),
    (_call(cnets.construct, D, G, end_planes=1), "end_planes"),
    (_call(cnets.construct, "abc", G), "directrix"),
    (_call(cnets.construct, D, "abc"), "generatrix"),
    (_call(cnets.construct, None, G), "directrix"),
    (_call(cnets.construct, D, {"a": 1}), "generatrix"),
    (_call(cnets.construct, D, np.zeros((4, 2))), "generatrix"),
    (_call(cnets.construct, D, np.array(["a", "b", "c"])), "generatrix"),
    (_call(cnets.construct, D, G, apex="steep"), "apex"),
    (_call(cnets.construct, D, G, apex=[[[1.0]]]), "apex"),
    (_call(cnets.construct, D, G, apex=["a", "b"]), "apex"),
    (_call(cnets.construct, D, G, ratios={"a": 1}), "ratios"),
    (_call(cnets.construct, D, G, ratios=np.zeros((2, 2, 2))), "ratios"),
    (_call(cnets.construct, D, G, apex=[0.9, 0.9]), "apex"),
    (_call(cnets.ctube, D, G, normals="up"), "normals"),
    (_call(cnets.ctube, D, G, normals=np.zeros((3, 2))), "normals"),
    (_call(cnets.construct_coplanar, D, G, ruling_ratios="x"), "ruling_ratios"),
    (_call(cnets.construct_coplanar, D, G, plane_ratios=[[[0.5]]]), "plane_ratios"),
    (_call(cnets.construct_coplanar, D, G, assistance=[1]), "assistance"),
    (_call(cnets.encode, "abc"), "vertices"),
    (_call(cnets.encode, np.zeros((3, 3))), "vertices"),
    (_call(cnets.eval, None), "node_type"),
    (_call(cnets.eval, 3), "node_type"),
    (_call(cnets.eval, "math.add", a=1, _outputs=5), "_outputs"),
    (_call(cnets.eval, "math.add", a=1, _max_memory=[1]), "_max_memory"),
    (_call(cnets.eval, "math.add", a=1, _max_memory=True), "_max_memory"),
    (_call(cnets.eval, "math.add", a=1, _max_memory="lots"), "_max_memory"),
    (_call(cnets.eval, "math.add", a=1, _allow_read=3), "_allow_read"),
    (_call(cnets.eval, "math.add", a=1, _library=[None]), "_library[0]"),
    (_call(cnets.eval, "math.add", a=1, _out=2.5), "_out"),
    (_call(cnets.eval, "math.add", a=object()), "'a'"),
    (_call(cnets.Graph.load, None), "path"),
    (_call(cnets.Graph.load, 42), "path"),
    (_call(cnets.Graph.load, "x.ron", max_memory={}), "max_memory"),
    (_call(cnets.Graph.load, "x.ron", library=7), "library"),
    (_call(cnets.write_3dm, "x.3dm", {"a": "hi"}), "objects['a']"),
    (_call(cnets.write_3dm, "x.3dm", {"a": [np.zeros((2, 3)), "hi"]}), "objects['a'][1]"),
    (_call(cnets.write_3dm, "x.3dm", {1: np.zeros((2, 3))}), "objects"),
    (_call(cnets.write_3dm, "x.3dm", 5), "objects"),
    (_call(cnets.write_3dm, None, {"a": np.zeros((2, 3))}), "path"),
    (_call(cnets.write_3dm, "x.3dm", {"a": np.zeros((2, 3))}, layers="yes"), "layers"),
    (_call(cnets.write_3dm, "x.3dm", {"a": np.zeros((2, 3))}, version=99), "version"),
    (_call(cnets.construct(D, G).to_3dm, "x.3dm", support="big"), "support"),
    (_call(cnets.construct(D, G).to_3dm, "x.3dm", axes=None), "axes"),
    (_call(cnets.construct(D, G).to_3dm, "x.3dm", layers=2), "layers"),
    (_call(cnets.Polyline, "abc"), "points"),
    (_call(cnets.Polyline, np.zeros((3, 3)), closed="yes"), "closed"),
    (_call(cnets.QuadMesh, np.zeros((2, 3))), "vertices"),
    (_call(cnets.QuadMesh, np.zeros((2, 2, 3)), wrap_rows=1), "wrap_rows"),
    (_call(cnets.PolygonMesh, np.zeros((3, 3)), [[0, 1, 5]]), "faces[0]"),
    (_call(cnets.PolygonMesh, np.zeros((3, 3)), [["a", 1, 2]]), "faces"),
    (_call(cnets._cnets.quad_faces, -1, 2, False, False), "rows"),
    (_call(cnets._cnets.quad_faces, 2, 2, 0, False), "wrap_rows"),
]


@pytest.mark.parametrize("call,argument", _HOSTILE, ids=[f"{k}-{a}" for k, (_, a) in enumerate(_HOSTILE)])
def test_bad_arguments_raise_cnets_errors_naming_the_argument(call, argument, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(cnets.CnetsError) as e:
        call()
    assert argument in str(e.value), str(e.value)
    assert "Traceback" not in str(e.value)


def test_graph_arguments_raise_cnets_errors_naming_the_argument(design):
    g = cnets.Graph.load(design)
    for call, argument in [
        (_call(g.set, None, 1), "target"),
        (_call(g.set, 5, 1), "target"),
        (_call(g.set, "apex.value", "steep"), "apex.value"),
        (_call(g.set, "apex.value", [0.5, 0.6, "x"]), "apex.value"),
        (_call(g.get, ["apex.value"]), "target"),
        (_call(g.unset, None), "target"),
        (_call(g.run, nodes=5), "nodes"),
        (_call(g.run, nodes=["len", 3]), "nodes[1]"),
        (_call(g.run, nodes=["nope"]), "no node 'nope'"),
        (_call(g.run, check="no"), "check"),
        (_call(g.outputs, None), "node_id"),
        (_call(g.outputs, "nope"), "no node 'nope'"),
        (_call(g.node_type, 3), "node_id"),
        (_call(g.time_ms, "nope"), "no node 'nope'"),
        (_call(g.save, None), "path"),
        (_call(setattr, g, "out", 3), "out"),
    ]:
        with pytest.raises(cnets.CnetsError) as e:
            call()
        assert argument in str(e.value), (argument, str(e.value))


def test_run_with_nodes_returns_only_what_it_evaluated_now(design):
    """No stale results: after an edit, run(nodes=…) returns those nodes, freshly evaluated."""
    g = cnets.Graph.load(design)
    first = g.run()
    g.set("apex.value", 0.8)
    only = g.run(nodes=["len"])
    assert set(only) == {"len"}, "only the requested node comes back"
    assert "net" not in only, "the net was not re-evaluated, so it is not returned (stale)"
    net = g.run(nodes="net")["net"]["mesh"]
    assert not np.array_equal(net.vertices, first["net"]["mesh"].vertices)
    np.testing.assert_array_equal(net.vertices, cnets.construct(
        first["dir"]["curve"], first["gen"]["curve"], apex=0.8).vertices)
    # A failure of a node that is not evaluated now is not reported now.
    g.set("gen.count", 1)
    with pytest.raises(cnets.CnetsError):
        g.run()
    assert g.run(nodes=["len"])["len"]["length"] == first["len"]["length"]
    assert g.errors == []


def test_setting_a_wired_input_raises(design):
    g = cnets.Graph.load(design)
    with pytest.raises(cnets.CnetsError, match=r"'net.apex' is wired from 'apex.value'"):
        g.set("net.apex", 0.5)
    with pytest.raises(cnets.CnetsError, match=r"'dir.radius' is wired from 'radius.value'"):
        g.set("dir.radius", 2.0)
    g.set("net.ratios", 0.4)  # not wired: fine
    assert g.get("net.ratios") == pytest.approx(0.4)


def test_a_clamped_value_is_reported(design):
    g = cnets.Graph.load(design)
    g.set("apex.value", 0.3)  # the slider's range is [0.5, 1.5]
    with pytest.warns(cnets.CnetsWarning, match=r"node 'apex' \(param.number\): value 0.3 is outside \[0.5, 1.5\]; clamped to 0.5"):
        out = g.run()
    assert out["apex"]["value"] == 0.5
    assert g.get("apex.value") == 0.3, "the file keeps what was set"
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        g.run()  # nothing ran again: no second warning


def test_point_outputs_are_always_arrays():
    """Apices come back as an (M−1, 3) array whatever the values: NaN rows at infinity."""
    d, g = arc(6), profile(4)
    for out in (cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=1.0),
                cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=0.9),
                cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=[1.0, 0.9, 1.0, 1.0, 1.0])):
        apices = out["apices"]
        assert isinstance(apices, np.ndarray) and apices.shape == (5, 3) and apices.dtype == np.float64
    assert np.isnan(cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=1.0)["apices"]).all()
    mixed = cnets.eval("cnets.construct", directrix=d, generatrix=g, apex=[1.0, 0.9, 1.0, 1.0, 1.0])["apices"]
    assert np.isnan(mixed[0]).all() and np.isfinite(mixed[1]).all()
    assert cnets.construct(d, g, apex=1.0).apices.shape == (5, 3)


def test_polylines_are_open_by_default():
    pts = arc(8)
    assert not cnets.Polyline(pts).closed
    a = cnets.construct(arc(41), cnets.Polyline(profile(5)))
    b = cnets.construct(arc(41), profile(5))
    assert a.vertices.shape == b.vertices.shape == (5, 41, 3)
    np.testing.assert_array_equal(a.vertices, b.vertices)
    assert cnets.construct(arc(41), cnets.Polyline(profile(5), closed=True)).wrap_rows


def test_the_drawing_advice_holds():
    """docs/python.md tells designers to draw the generatrix from a point off the directrix (the
    docs' curves: an arc of 40 points, a profile of 20 starting half a unit above its first
    point): then the assisted correction, the node axes, the support layer and the coplanar
    construction are all defined. Drawn from a point on the directrix they are not, and the
    errors say where."""
    t = np.radians(np.linspace(0, 120, 40))
    d = np.c_[5 * np.cos(t), 5 * np.sin(t), np.zeros_like(t)]
    s = np.linspace(0, 1, 20)
    off = np.c_[5 + 0.8 * s, np.zeros_like(s), 0.5 + 3 * s]
    on = off - [0.0, 0.0, 0.5]
    net = cnets.construct(d, off, apex=1.1, assistance=0.5)
    assert net.corrections, "the correction repaired the folds"
    axes = cnets.eval("cnets.torsion_free_axes", directrix=d, mesh=net)["axes"]
    assert axes.shape == (20 * 40, 2, 3) and np.isfinite(axes).all()
    layer = cnets.eval("cnets.conical_support", directrix=d, mesh=net, apex=net.apex)["mesh"]
    assert np.isfinite(layer.vertices).all()
    assert cnets.construct_coplanar(d, off, apex=0.9, ruling_ratios=0.4,
                                    plane_ratios=0.6).vertices.shape == (20, 40, 3)
    with pytest.raises(cnets.CnetsError, match=r"support plane at row 0, .* is undefined"):
        cnets.construct(d, on, apex=1.1, assistance=0.5)
    with pytest.raises(cnets.CnetsError, match=r"support plane at row 0, .* is undefined"):
        cnets.construct_coplanar(d, on, apex=0.9, ruling_ratios=0.4, plane_ratios=0.6)
    with pytest.raises(cnets.CnetsError, match=r"coincides with X_0"):
        cnets.eval("cnets.torsion_free_axes", directrix=d, mesh=cnets.construct(d, on, apex=0.95))


def test_a_joined_structure_keeps_its_parts_through_python():
    grid = np.array([[[x, y, 0.0] for x in range(3)] for y in range(3)], dtype=float)
    wall = cnets.QuadMesh(grid)
    roof = cnets.QuadMesh(grid + np.array([2.0, 0.0, 0.0]))
    joined = cnets.eval("mesh.join", meshes=[wall, roof], weld=1e-9, names=["wall", "roof"])["mesh"]
    assert isinstance(joined, cnets.PolygonMesh)
    assert joined.parts == ["wall", "roof"]
    assert joined.face_parts == [0] * 4 + [1] * 4
    assert len(joined.vertices) == 15
    # Back in, the parts name the strips: the wall's first, numbered from 0 within each part.
    labels = cnets.eval("pq.unroll_strips", mesh=joined, direction="generatrix")["labels"]
    names = [str(l).split()[0] for l in labels]
    wall = [n for n in names if n.startswith("wall-G")]
    roof = [n for n in names if n.startswith("roof-G")]
    assert wall and roof and names == wall + roof, names
    assert wall == [f"wall-G{k}" for k in range(len(wall))], names
    assert roof == [f"roof-G{k}" for k in range(len(roof))], names
    with pytest.raises(cnets.CnetsError) as e:
        cnets.PolygonMesh(joined.vertices, joined.faces, ["wall"], [0, 1])
    assert "face_parts" in str(e.value)
