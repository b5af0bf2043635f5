"""The Hops server: started as `python -m cnets.hops` on a free loopback port, sent what
Grasshopper's Hops component sends (JSON with rhino3dm-encoded curves) with a plain HTTP client."""

import json
import os
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request

import numpy as np
import pytest

import cnets
from conftest import arc, profile

import ghhops_server  # noqa: F401  (the tests need it: fail, do not skip, without it)
import rhino3dm


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    from conftest import CLUSTER

    lib = tmp_path_factory.mktemp("library")
    (lib / "arc-length.ron").write_text(CLUSTER)
    (lib / "no-interface.ron").write_text('(version: 1, nodes: {"a": (type: "math.add")})')
    port = _free_port()
    # ghhops-server prints every request's inputs: to a file, so that no pipe fills up.
    log = open(tmp_path_factory.mktemp("log") / "hops.log", "w+b")
    proc = subprocess.Popen(
        [sys.executable, "-m", "cnets.hops", "--port", str(port), "--library", str(lib)],
        stdout=log, stderr=subprocess.STDOUT,
    )
    base = f"http://127.0.0.1:{port}"
    deadline = time.time() + 30
    while True:
        try:
            urllib.request.urlopen(base + "/", timeout=2).read()
            break
        except (urllib.error.URLError, ConnectionError):
            if proc.poll() is not None or time.time() > deadline:
                proc.kill()
                log.seek(0)
                out = log.read().decode(errors="replace")
                raise RuntimeError(f"the Hops server did not start: {out}")
            time.sleep(0.2)
    yield base
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
    log.close()


def _get(url):
    with urllib.request.urlopen(url, timeout=30) as r:
        return json.loads(r.read())


def _post(url, payload):
    req = urllib.request.Request(url, data=json.dumps(payload).encode(), method="POST",
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=60) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read() or b"{}")


def _item(type_, data):
    return {"type": type_, "data": data}


def _curve_item(curve):
    return _item("Rhino.Geometry." + type(curve).__name__, json.dumps(curve.Encode()))


def _number_items(values):
    return [_item("System.Double", json.dumps(float(v))) for v in values]


def _param(name, items, tree=None):
    return {"ParamName": name, "InnerTree": tree if tree is not None else {"{0}": items}}


def _decode(item):
    return rhino3dm.CommonObject.Decode(json.loads(item["data"]))


def _values(response):
    return {v["ParamName"]: [x for branch in v["InnerTree"].values() for x in branch]
            for v in response["values"]}


def _mesh_vertices(mesh):
    return np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices[k] for k in range(len(mesh.Vertices)))])


def test_components_are_listed_with_the_contracted_ports(server):
    listing = _get(server + "/")
    uris = {c["Uri"] for c in listing}
    assert {"/cnets_construct", "/cnets_construct_coplanar", "/cnets_graph_to_apex",
            "/cnets_support", "/arc-length"} <= uris, uris
    assert "/no-interface" not in uris
    meta = _get(server + "/cnets_construct")
    assert [p["Name"] for p in meta["Inputs"]] == ["Directrix", "Generatrix", "Apex", "Ratios", "Assistance"]
    assert [p["ParamType"] for p in meta["Inputs"]] == ["Curve", "Curve", "Number", "Number", "Number"]
    assert meta["Inputs"][2]["AtMost"] > 1, "Apex is a list"
    assert meta["Inputs"][3]["AtLeast"] == -1, "Ratios is a tree"
    assert meta["Inputs"][4]["AtMost"] == 1, "Assistance is one number"
    assert [p["Name"] for p in meta["Outputs"]] == ["Mesh", "Apex", "Quality"]
    lib = _get(server + "/arc-length")
    assert [p["Name"] for p in lib["Inputs"]] == ["radius"]
    assert [p["Name"] for p in lib["Outputs"]] == ["length"]


def _construct_payload(directrix, generatrix, apex, ratios_tree, assistance, pointer=None):
    payload = {
        "values": [
            _param("Directrix", [_curve_item(directrix)]),
            _param("Generatrix", [_curve_item(generatrix)]),
            _param("Apex", _number_items(apex)),
            _param("Ratios", None, tree={k: _number_items(v) for k, v in ratios_tree.items()}),
            _param("Assistance", _number_items([assistance])),
        ]
    }
    if pointer:
        payload["pointer"] = pointer
    return payload


def test_construct_with_a_nurbs_directrix_and_a_polyline_generatrix(server):
    control = [rhino3dm.Point3d(*p) for p in arc(6).tolist()]
    directrix = rhino3dm.NurbsCurve.Create(False, 3, control)
    generatrix = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in profile(5).tolist()])
    status, response = _post(server + "/cnets_construct",
                             _construct_payload(directrix, generatrix, [0.95], {"{0}": [0.5]}, -1.0))
    assert status == 200, response
    assert not response.get("errors"), response
    values = _values(response)
    mesh = _decode(values["Mesh"][0])
    assert isinstance(mesh, rhino3dm.Mesh)
    # The same construction in Python on the curve as the server samples it.
    from cnets.rhino import curve_points

    d = curve_points(directrix, 33)
    expected = cnets.construct(d, profile(5), apex=0.95)
    np.testing.assert_allclose(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3), atol=1e-6)
    assert mesh.Faces.Count == len(expected.faces())
    apex = [json.loads(a["data"]) for a in values["Apex"]]
    np.testing.assert_allclose(apex, expected.apex)
    quality = json.loads(values["Quality"][0]["data"])
    assert quality == pytest.approx(expected.quality["max_planarity"])


def test_ratio_trees_and_the_legacy_solve_route(server):
    d = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in arc(7).tolist()])
    g = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in profile(4).tolist()])
    rows = np.linspace(0.3, 0.7, 24).reshape(4, 6)
    tree = {"{%d}" % i: rows[i].tolist() for i in range(4)}
    status, response = _post(server + "/solve", _construct_payload(d, g, [0.9] * 6, tree, 0.5,
                                                                  pointer="/cnets_construct"))
    assert status == 200, response
    mesh = _decode(_values(response)["Mesh"][0])
    expected = cnets.construct(arc(7), profile(4), apex=[0.9] * 6, ratios=rows, assistance=0.5)
    np.testing.assert_allclose(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3), atol=1e-6)


def test_engine_errors_reach_grasshopper(server):
    d = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in arc(5).tolist()])
    g = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in profile(4).tolist()])
    status, response = _post(server + "/cnets_construct",
                             _construct_payload(d, g, [0.9, 0.9], {"{0}": [0.5]}, -1.0))
    assert status != 200
    assert any("apex" in e for e in response["errors"]), response


def test_coplanar_graph_to_apex_support_and_library(server):
    lifted = profile(4) + [0.0, 0.0, 0.5]  # off the directrix: support planes and axes defined
    d = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in arc(6).tolist()])
    g = rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in lifted.tolist()])
    status, response = _post(server + "/cnets_construct_coplanar", {"values": [
        _param("Directrix", [_curve_item(d)]), _param("Generatrix", [_curve_item(g)]),
        _param("Apex", _number_items([0.9])), _param("RulingRatios", _number_items([0.4])),
        _param("PlaneRatios", _number_items([0.6])), _param("Assistance", _number_items([-1])),
    ]})
    assert status == 200, response
    expected = cnets.construct_coplanar(arc(6), lifted, apex=0.9, ruling_ratios=0.4, plane_ratios=0.6)
    mesh = _decode(_values(response)["Mesh"][0])
    np.testing.assert_allclose(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3), atol=1e-6)

    widths = [1.0, 1.1, 1.3, 1.2, 1.0, 0.9]
    status, response = _post(server + "/cnets_graph_to_apex", {"values": [
        _param("Widths", _number_items(widths)),
        _param("Normalized", [_item("System.Boolean", "false")]),
        _param("Directrix", []), _param("Scale", _number_items([0])),
    ]})
    assert status == 200, response
    apex = [json.loads(a["data"]) for a in _values(response)["Apex"]]
    np.testing.assert_allclose(apex, np.array(widths[1:]) / np.array(widths[:-1]))

    net = cnets.construct(arc(6), lifted, apex=0.9)
    from cnets.rhino import quad_mesh_to_rhino

    status, response = _post(server + "/cnets_support", {"values": [
        _param("Directrix", [_curve_item(d)]),
        _param("Mesh", [_item("Rhino.Geometry.Mesh", json.dumps(quad_mesh_to_rhino(net).Encode()))]),
        _param("Apex", _number_items(net.apex)), _param("Factor", _number_items([0.8])),
    ]})
    assert status == 200, response
    values = _values(response)
    assert len(values["Axes"]) == 4 * 6
    support = cnets.eval("cnets.conical_support", directrix=arc(6), mesh=net, apex=net.apex, factor=0.8)["mesh"]
    np.testing.assert_allclose(_mesh_vertices(_decode(values["Support"][0])),
                               support.vertices.reshape(-1, 3), atol=1e-6)

    status, response = _post(server + "/arc-length", {"values": [_param("radius", _number_items([2.0]))]})
    assert status == 200, response
    length = json.loads(_values(response)["length"][0]["data"])
    assert length == pytest.approx(2 * np.pi, rel=1e-3)
