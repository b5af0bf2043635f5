"""Sweeps on Dask: a LocalCluster with 2 workers, a 4 × 3 grid, every row equal to a direct run."""

import os

import numpy as np
import pytest

import cnets

import dask.distributed as distributed
import pandas as pd

OUTPUTS = ["len.length", "net.quality.max_planarity", "net.quality.vertices"]


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def _direct(path, design):
    g = cnets.Graph.load(path)
    for k, v in design.items():
        g.set(k, v)
    r = g.run()
    q = r["net"]["quality"]
    return {"len.length": r["len"]["length"], "net.quality.max_planarity": q["max_planarity"],
            "net.quality.vertices": q["vertices"]}


def test_grid_sweep_rows_equal_direct_runs(design, client):
    parameters = {"radius.value": [3.0, 5.0, 7.0, 9.0], "apex.value": [0.8, 1.0, 1.2]}
    df = cnets.sweep(design, parameters, OUTPUTS, client=client)
    assert isinstance(df, pd.DataFrame)
    assert len(df) == 12
    assert list(df.columns) == ["radius.value", "apex.value", *OUTPUTS, "ok", "error"]
    assert df["error"].isna().all(), df["error"].tolist()
    assert df["ok"].dtype == bool and df["ok"].all()
    for k, row in df.iterrows():
        design_k = {"radius.value": row["radius.value"], "apex.value": row["apex.value"]}
        assert design_k == {"radius.value": parameters["radius.value"][k // 3],
                            "apex.value": parameters["apex.value"][k % 3]}
        expected = _direct(design, design_k)
        for name in OUTPUTS:
            assert row[name] == expected[name], (k, name, row[name], expected[name])
    # Both workers took part, each with its own cached graph.
    assert len(set(df["len.length"])) == 4


def test_list_of_designs_errors_and_exports(design, tmp_path, client):
    text = design.read_text().replace(
        '"len": (type: "curve.length"),',
        '"len": (type: "curve.length"),\n        "obj": (type: "io.export_obj", inputs: {"name": "net"}),',
    ).replace('"dir.curve -> len.curve",', '"dir.curve -> len.curve",\n        "net.mesh -> obj.meshes",')
    path = tmp_path / "exporting.ron"
    path.write_text(text)
    designs = [{"apex.value": 0.9}, {"gen.count": 1}, {"radius.value": 4.0}]
    out = tmp_path / "designs"
    df = cnets.sweep(path, designs, ["len.length", "net.quality.max_planarity"], client=client, out=out)
    assert len(df) == 3
    assert pd.isna(df["error"].iloc[0]) and pd.isna(df["error"].iloc[2])
    assert "gen" in df["error"].iloc[1] or "net" in df["error"].iloc[1]
    assert df["ok"].tolist() == [True, False, True]
    assert np.isnan(df["net.quality.max_planarity"].iloc[1])
    # A design that does not set an input gets the file's value, not the previous design's.
    assert df["len.length"].iloc[0] == pytest.approx(5.0 * np.radians(120), rel=1e-2)
    assert df["len.length"].iloc[2] == pytest.approx(4.0 * np.radians(120), rel=1e-2)
    for k in (0, 2):
        folder = df["out"].iloc[k]
        assert folder == str(out / f"design-{k:04d}")
        assert os.path.isfile(os.path.join(folder, "net.obj"))
    assert not os.path.exists(os.path.join(df["out"].iloc[1], "net.obj"))


def test_bad_requests_fail_before_the_cluster_works(design, client):
    with pytest.raises(cnets.CnetsError, match="no node 'nope'"):
        cnets.sweep(design, {"radius.value": [1.0]}, ["nope.x"], client=client)
    with pytest.raises(cnets.CnetsError):
        cnets.sweep(design, {"radius.nope": [1.0]}, ["len.length"], client=client)


def test_without_a_client_a_local_cluster_is_started(design):
    df = cnets.sweep(design, {"radius.value": [2.0, 3.0]}, ["len.length"], n_workers=1)
    assert df["len.length"].tolist() == pytest.approx([2.0 * np.radians(120), 3.0 * np.radians(120)], rel=1e-2)


def test_a_clamped_parameter_is_reported_and_the_row_holds_the_value_used(design, client):
    """The apex slider's range is [0.5, 1.5]: 0.3 is clamped to 0.5, 2.0 to 1.5. The rows say
    what was used (not what was asked), the sweep warns, and the outputs are those of the values
    used."""
    with pytest.warns(cnets.CnetsWarning) as record:
        df = cnets.sweep(design, {"apex.value": [0.3, 0.8, 2.0]}, ["net.quality.max_planarity"],
                         client=client)
    assert df["apex.value"].tolist() == [0.5, 0.8, 1.5]
    messages = [str(w.message) for w in record]
    assert any("design 0: apex.value = 0.3 was changed by its node to 0.5" in m for m in messages), messages
    assert any("design 2: apex.value = 2.0 was changed by its node to 1.5" in m for m in messages), messages
    assert not any(m.startswith("design 1:") for m in messages), messages
    direct = cnets.sweep(design, {"apex.value": [0.5, 1.5]}, ["net.quality.max_planarity"], client=client)
    assert df["net.quality.max_planarity"].iloc[[0, 2]].tolist() == direct["net.quality.max_planarity"].tolist()


def test_bad_sweep_arguments_name_the_argument(design, client):
    for kwargs, argument in [
        (dict(parameters={"radius.value": 3.0}, outputs=["len.length"]), "parameters['radius.value']"),
        (dict(parameters={"radius": [3.0]}, outputs=["len.length"]), "parameters"),
        (dict(parameters=["radius.value"], outputs=["len.length"]), "parameters[0]"),
        (dict(parameters="radius.value", outputs=["len.length"]), "parameters"),
        (dict(parameters={"radius.value": [3.0]}, outputs=[1]), "outputs"),
        (dict(parameters={"radius.value": [3.0]}, outputs=["len.length"], n_workers=0), "n_workers"),
        (dict(parameters={"radius.value": [3.0]}, outputs=["len.length"], library="lib"), "library"),
    ]:
        with pytest.raises(cnets.CnetsError) as e:
            cnets.sweep(design, client=client, **kwargs)
        assert argument in str(e.value), (argument, str(e.value))
    with pytest.raises(cnets.CnetsError, match="graph"):
        cnets.sweep(None, {"radius.value": [3.0]}, ["len.length"], client=client)


def _explode():
    raise RuntimeError("this value cannot be unpickled")


class Unpicklable:
    """A parameter value that fails on the worker: its task fails, not the sweep."""

    def __reduce__(self):
        return (_explode, ())


def test_bad_designs_are_flagged_with_the_reason(design, client):
    """A design whose node fails, one whose figures are not finite (apex 1: the cones are
    cylinders, their apices at infinity: NaN points) and one whose task fails on its worker come
    back flagged, ok False and the reason in error; the others ok, with no reason."""
    designs = [
        {"apex.value": 0.9},
        {"apex.value": 0.9, "gen.count": 1},     # a one-point generatrix: the construction fails
        {"apex.value": 1.0},                     # apices at infinity
        {"apex.value": Unpicklable()},           # the task fails on its worker
    ]
    outputs = ["net.quality.max_planarity", "net.apices"]
    df = cnets.sweep(design, designs, outputs, client=client)
    assert list(df.columns) == ["apex.value", "gen.count", *outputs, "ok", "error"]
    assert df["ok"].tolist() == [True, False, False, False]
    assert pd.isna(df["error"].iloc[0])
    failed = df["error"].iloc[1]
    assert failed.startswith("node 'gen' (curve.line): degenerate input: count must be at least 2"), failed
    assert "node 'net' (cnets.construct): input 'generatrix' comes from 'gen', which failed" in failed
    assert np.isnan(df["net.quality.max_planarity"].iloc[1])
    assert "is not finite" not in failed, "a failed node's NaN outputs are not reported twice"
    assert df["error"].iloc[2] == "net.apices is not finite (33 of 33 values)"
    assert np.isnan(df["net.apices"].iloc[2]).all(), "the value is kept"
    assert np.isfinite(df["net.quality.max_planarity"].iloc[2])
    lost = df["error"].iloc[3]
    assert lost.startswith("the design's task failed: RuntimeError"), lost
    assert "deserialization" in lost, lost  # dask: the scheduler could not read the task
    assert df[df.ok].index.tolist() == [0]


def test_an_exception_while_evaluating_flags_the_design(design, monkeypatch):
    """In the worker's function itself: a Python exception raised while evaluating a design
    (here from reading an output) is its row's error, not the sweep's."""
    from cnets import sweeps

    def broken(results, graph, name):
        raise KeyError(name)

    monkeypatch.setattr(sweeps, "_output", broken)
    row = sweeps.evaluate_design(str(design), {"apex.value": 0.8}, ["len.length"])
    assert row["ok"] is False
    assert row["error"] == "the evaluation raised KeyError: 'len.length'"
    assert np.isnan(row["len.length"])
    monkeypatch.undo()
    row = sweeps.evaluate_design(str(design), {"apex.value": 0.8}, ["len.length"])
    assert row["ok"] is True and row["error"] is None


def test_not_finite_names_what_is_not_finite():
    from cnets.sweeps import _not_finite

    assert _not_finite(1.0) is None and _not_finite(None) is None and _not_finite("nan") is None
    assert _not_finite(float("nan")) == "nan"
    assert _not_finite(np.float64("-inf")) == "-inf"
    assert _not_finite(np.array([1.0, np.nan, np.inf])) == "2 of 3 values"
    assert _not_finite(np.arange(3)) is None
    assert _not_finite({"a": 1.0, "b": {"c": np.nan}}) == "b: c: nan"
    assert _not_finite([1.0, float("inf")]) == "[1]: inf"


def _newell_areas(vertices, faces):
    """Each face's area by numpy: half the length of Σ p_k × p_{k+1}."""
    areas = []
    for f in faces:
        p = np.asarray(vertices)[f]
        areas.append(0.5 * np.linalg.norm(np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)))
    return np.array(areas)


def test_measure_area_from_python():
    """`cnets.eval("measure.area", mesh=…)`: a cone-net (a quad mesh converts) and a polygon mesh
    give the total and the per-face areas, as numpy's Newell normals say."""
    t = np.radians(np.linspace(0.0, 120.0, 9))
    directrix = np.c_[5 * np.cos(t), 5 * np.sin(t), np.zeros(9)]
    s = np.linspace(0.0, 1.0, 5)
    generatrix = np.c_[5 + 0.8 * s, np.zeros(5), 3 * s + 0.5]
    net = cnets.construct(directrix, generatrix, apex=0.9)
    out = cnets.eval("measure.area", mesh=net)
    expected = _newell_areas(net.vertices.reshape(-1, 3), net.faces())
    np.testing.assert_allclose(out["faces"], expected, rtol=1e-12)
    assert len(out["faces"]) == 4 * 8
    assert out["total"] == pytest.approx(expected.sum(), rel=1e-12)
    mesh = cnets.PolygonMesh([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0], [1, 2, 1]],
                             [[0, 1, 2, 3], [3, 2, 4]])
    out = cnets.eval("measure.area", mesh=mesh)
    np.testing.assert_allclose(out["faces"], [2.0, np.sqrt(2.0)], rtol=1e-14)
    assert out["total"] == pytest.approx(2.0 + np.sqrt(2.0), rel=1e-14)


def test_a_sweep_reports_the_area_and_the_convex_share(design, tmp_path, client):
    """A study's figures: the net's area (`measure.area`) and the share of its faces that are
    convex (`analysis.face_classes`' convex_share) over a design parameter, each row equal to a
    direct run."""
    text = design.read_text().replace(
        '"len": (type: "curve.length"),',
        '"len": (type: "curve.length"),\n'
        '        "area": (type: "measure.area"),\n'
        '        "classes": (type: "analysis.face_classes"),',
    ).replace('"dir.curve -> len.curve",', '"dir.curve -> len.curve",\n'
              '        "net.mesh -> area.mesh",\n'
              '        "net.mesh -> classes.mesh",\n'
              '        "net.configurations -> classes.configurations",')
    path = tmp_path / "study.ron"
    path.write_text(text)
    outputs = ["area.total", "classes.convex_share", "classes.convex"]
    apex = [0.6, 0.8, 1.0, 1.2, 1.4]
    df = cnets.sweep(path, {"apex.value": apex}, outputs, client=client)
    assert df["ok"].all(), df["error"].tolist()
    assert list(df.columns) == ["apex.value", *outputs, "ok", "error"]
    for k, a in enumerate(apex):
        g = cnets.Graph.load(path)
        g.set("apex.value", a)
        r = g.run()
        assert df["area.total"].iloc[k] == r["area"]["total"]
        assert df["area.total"].iloc[k] == pytest.approx(
            _newell_areas(r["net"]["mesh"].vertices.reshape(-1, 3), r["net"]["mesh"].faces()).sum(),
            rel=1e-12)
        assert df["classes.convex_share"].iloc[k] == r["classes"]["convex_share"]
        faces = len(r["classes"]["classes"])
        assert faces == 5 * 11
        assert df["classes.convex"].iloc[k] == int(np.sum(np.asarray(r["classes"]["classes"]) == 0))
        assert df["classes.convex_share"].iloc[k] == df["classes.convex"].iloc[k] / faces
    # The apex function scales the columns: the area grows with it; past 1 some faces stop
    # being convex ((++),(++)), so the share falls from 1.
    assert df["area.total"].is_monotonic_increasing and df["area.total"].nunique() == len(apex)
    assert df["classes.convex_share"].iloc[0] == 1.0
    assert 0.0 < df["classes.convex_share"].iloc[-1] < 1.0
