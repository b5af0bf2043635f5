"""The Hops server: started as `python -m cnets.hops` on a free loopback port, sent what
Grasshopper's Hops component sends (JSON with rhino3dm-encoded curves) with a plain HTTP client:
solutions exact to the last bit, every failure a Hops response with one sentence, bodies over the
limit refused with 413, library graphs at safe URLs, concurrent requests all answered."""

import concurrent.futures
import json
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.parse
import urllib.request

import numpy as np
import pytest

import cnets
from conftest import CLUSTER, LIBRARY, HopsProcess, arc, lifted, profile

import rhino3dm


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    lib = tmp_path_factory.mktemp("library")
    (lib / "arc-length.ron").write_text(CLUSTER)
    (lib / "my tube.ron").write_text(CLUSTER)
    (lib / "...ron").write_text(CLUSTER)
    (lib / "cnets_construct.ron").write_text(CLUSTER)
    (lib / "Twice.ron").write_text(CLUSTER)
    (lib / "twice.ron").write_text(CLUSTER)
    (lib / "no-interface.ron").write_text('(version: 1, nodes: {"a": (type: "math.add")})')
    (lib / "broken.ron").write_text("(version: ")
    hops = HopsProcess(tmp_path_factory.mktemp("log") / "hops.log", "--library", str(lib))
    yield hops
    hops.stop()


@pytest.fixture(scope="module")
def small_server(tmp_path_factory):
    """A server with a 1 MB body limit and a 2 MB memory budget for solves."""
    hops = HopsProcess(tmp_path_factory.mktemp("log") / "hops.log", "--max-body", "1MB",
                       "--max-memory", "2MB")
    yield hops
    hops.stop()


def _get(url):
    try:
        with urllib.request.urlopen(url, timeout=60) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def _post(url, payload, raw=None):
    data = raw if raw is not None else json.dumps(payload).encode()
    req = urllib.request.Request(url, data=data, method="POST",
                                 headers={"Content-Type": "application/json"})
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            return r.status, json.loads(r.read())
    except urllib.error.HTTPError as e:
        return e.code, json.loads(e.read())


def _post_announced(url, length, prefix=b'{"values": ['):
    """POSTs the headers of a body of `length` bytes and only its first bytes, then reads the
    answer: the server refuses by Content-Length before it reads. (Sending all of an over-limit
    body races the server's close: once it has answered it drains what it is sent only while the
    client keeps up, and a client that falls behind on a busy machine gets a reset instead.)"""
    parts = urllib.parse.urlsplit(url)
    with socket.create_connection((parts.hostname, parts.port), timeout=120) as sock:
        sock.sendall((f"POST {parts.path} HTTP/1.1\r\nHost: {parts.netloc}\r\n"
                      f"Content-Type: application/json\r\nContent-Length: {length}\r\n"
                      "Connection: close\r\n\r\n").encode() + prefix)
        sock.shutdown(socket.SHUT_WR)
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    head, _, body = answer.partition(b"\r\n\r\n")
    status = int(head.split(b" ", 2)[1])
    return status, json.loads(body)


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
    assert mesh.Vertices.UseDoublePrecisionVertices
    return np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()])


def _polyline(points):
    return rhino3dm.PolylineCurve([rhino3dm.Point3d(*p) for p in np.asarray(points).tolist()])


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


def _one_error(status, response, expected_status, *words):
    """A Hops response carrying exactly one error: one sentence, no traceback, naming `words`."""
    assert status == expected_status, (status, response)
    assert response["values"] == [], response
    (error,) = response["errors"]
    assert "\n" not in error and "Traceback" not in error and 'File "' not in error, error
    assert error.endswith("."), error
    for w in words:
        assert w in error, (w, error)
    return error


def test_components_are_listed_with_the_contracted_ports(server):
    status, listing = _get(server.url + "/")
    assert status == 200
    uris = {c["Uri"] for c in listing}
    assert {"/cnets_construct", "/cnets_construct_coplanar", "/cnets_graph_to_apex",
            "/cnets_support", "/arc-length", "/my%20tube"} <= uris, uris
    assert "/no-interface" not in uris and "/broken" not in uris
    status, meta = _get(server.url + "/cnets_construct")
    assert status == 200
    assert [p["Name"] for p in meta["Inputs"]] == ["Directrix", "Generatrix", "Apex", "Ratios", "Assistance"]
    assert [p["ParamType"] for p in meta["Inputs"]] == ["Curve", "Curve", "Number", "Number", "Number"]
    assert meta["Inputs"][2]["AtMost"] > 1, "Apex is a list"
    assert meta["Inputs"][3]["AtLeast"] == -1, "Ratios is a tree"
    assert meta["Inputs"][4]["AtMost"] == 1, "Assistance is one number"
    assert [p["Name"] for p in meta["Outputs"]] == ["Mesh", "Apex", "Quality"]
    status, lib = _get(server.url + "/arc-length")
    assert [p["Name"] for p in lib["Inputs"]] == ["Radius"]
    assert [p["Name"] for p in lib["Outputs"]] == ["Length"]


def test_library_names_are_percent_decoded_and_unsafe_ones_refused_at_start_up(server):
    status, meta = _get(server.url + "/my%20tube")
    assert status == 200 and meta["Uri"] == "/my%20tube", meta
    status, response = _post(server.url + "/my%20tube", {"values": [_param("Radius", _number_items([2.0]))]})
    assert status == 200, response
    assert json.loads(_values(response)["Length"][0]["data"]) == pytest.approx(2 * np.pi, rel=1e-3)
    # The legacy route with the pointer as Hops sends it: the component's whole URL.
    status, response = _post(server.url + "/solve", {"pointer": server.url + "/my%20tube",
                                                      "values": [_param("radius", _number_items([1.0]))]})
    assert status == 200, response
    log = server.log()
    assert "...ron: skipped: its name '..' is made of dots only" in log, log
    assert "cnets_construct.ron: skipped: its URL /cnets_construct would be the same as /cnets_construct's" in log
    assert "twice.ron: skipped: its URL /twice would be the same as /Twice's" in log
    assert "broken.ron: skipped:" in log
    _one_error(*_get(server.url + "/.."), 404, "no component")
    _one_error(*_get(server.url + "/twice"), 404, "no component at /twice")
    assert _get(server.url + "/Twice")[0] == 200


def test_construct_is_exact_to_the_last_bit(server):
    """The mesh Grasshopper decodes holds the engine's doubles: vertex for vertex equal to
    cnets.construct on the curve as the server samples it."""
    control = [rhino3dm.Point3d(*p) for p in arc(6).tolist()]
    directrix = rhino3dm.NurbsCurve.Create(False, 3, control)
    generatrix = _polyline(lifted(5) + [250_000.0, 0.0, 0.0])
    status, response = _post(server.url + "/cnets_construct",
                             _construct_payload(directrix, generatrix, [0.95], {"{0}": [0.5]}, -1.0))
    assert status == 200, response
    assert response["errors"] == [], response
    values = _values(response)
    mesh = _decode(values["Mesh"][0])
    assert isinstance(mesh, rhino3dm.Mesh)
    from cnets.rhino import curve_points

    d = curve_points(directrix, 33)
    expected = cnets.construct(d, lifted(5) + [250_000.0, 0.0, 0.0], apex=0.95)
    np.testing.assert_array_equal(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3))
    assert [list(mesh.Faces[k]) for k in range(mesh.Faces.Count)] == expected.faces().tolist()
    apex = [float(a["data"]) for a in values["Apex"]]
    np.testing.assert_array_equal(apex, expected.apex)
    assert float(values["Quality"][0]["data"]) == expected.quality["max_planarity"]


def test_ratio_trees_and_the_legacy_solve_route(server):
    d, g = _polyline(arc(7)), _polyline(profile(4))
    rows = np.linspace(0.3, 0.7, 24).reshape(4, 6)
    tree = {"{%d}" % i: rows[i].tolist() for i in range(4)}
    expected = cnets.construct(arc(7), profile(4), apex=[0.9] * 6, ratios=rows, assistance=0.5)
    for pointer in ("/cnets_construct", "cnets_construct", server.url + "/cnets_construct"):
        status, response = _post(server.url + "/solve",
                                 _construct_payload(d, g, [0.9] * 6, tree, 0.5, pointer=pointer))
        assert status == 200, response
        mesh = _decode(_values(response)["Mesh"][0])
        np.testing.assert_array_equal(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3))


def test_malformed_requests_get_one_sentence(server):
    url = server.url
    good = _construct_payload(_polyline(arc(5)), _polyline(profile(4)), [0.9], {"{0}": [0.5]}, -1.0)
    _one_error(*_post(url + "/cnets_construct", None, raw=b"{not json"), 400, "not JSON")
    _one_error(*_post(url + "/cnets_construct", None, raw=b""), 400, "not JSON")
    _one_error(*_post(url + "/cnets_construct", None, raw=b"\xff\xfe"), 400, "not JSON")
    _one_error(*_post(url + "/cnets_construct", [1, 2]), 400, "JSON object")
    _one_error(*_post(url + "/cnets_construct", {"nothing": 1}), 400, "\"values\"")
    _one_error(*_post(url + "/solve", good), 400, "\"pointer\"")
    _one_error(*_post(url + "/solve", dict(good, pointer=5)), 400, "\"pointer\"")
    _one_error(*_post(url + "/solve", dict(good, pointer="/nope")), 404, "'/nope'")
    _one_error(*_post(url + "/nope", good), 404, "no component at /nope")
    _one_error(*_post(url + "/", good), 404, "no component at /")
    _one_error(*_get(url + "/nope"), 404, "no component at /nope")
    _one_error(*_get(url + "/solve"), 405, "POST")

    def with_input(name, items, tree=None):
        payload = json.loads(json.dumps(good))
        payload["values"] = [v for v in payload["values"] if v["ParamName"] != name]
        if items is not None or tree is not None:
            payload["values"].append(_param(name, items, tree))
        return payload

    construct = url + "/cnets_construct"
    _one_error(*_post(construct, with_input("Apex", [_item("System.String", '"abc"')])), 400,
               "Apex", "'\"abc\"'", "not a number")
    _one_error(*_post(construct, with_input("Apex", [_item("System.Double", "abc")])), 400,
               "Apex", "'abc'", "not a number")
    _one_error(*_post(construct, with_input("Assistance", _number_items([0.5, 0.2]))), 400,
               "Assistance", "expected one item, got 2")
    _one_error(*_post(construct, with_input("Directrix", _number_items([3.0]))), 400,
               "Directrix", "a number (System.Double)", "expected a curve")
    _one_error(*_post(construct, with_input("Directrix", None)), 400, "Directrix: no curve given")
    mesh = rhino3dm.Mesh()
    _one_error(*_post(construct, with_input("Generatrix", [_item("Rhino.Geometry.Mesh", json.dumps(mesh.Encode()))])),
               400, "Generatrix", "Mesh", "expected a curve")
    _one_error(*_post(construct, with_input("Generatrix", [_item("Rhino.Geometry.Curve", "{bad")])),
               400, "Generatrix", "could not be decoded")
    _one_error(*_post(construct, with_input("Ratios", None, tree=[1, 2])), 400, "Ratios", "InnerTree")
    _one_error(*_post(construct, with_input("Ratios", None, tree={"{a}": _number_items([1])})), 400,
               "Ratios", "tree path")
    _one_error(*_post(construct, with_input("Ratios", [{"type": "System.Double"}])), 400,
               "Ratios", "\"data\"")
    bogus = json.loads(json.dumps(good))
    bogus["values"].append(_param("Colour", _number_items([1])))
    _one_error(*_post(construct, bogus), 400, "no input 'Colour'", "Directrix, Generatrix")
    bogus["values"] = [{"InnerTree": {}}]
    _one_error(*_post(construct, bogus), 400, "\"ParamName\"")


def test_engine_errors_reach_grasshopper_as_one_sentence(server):
    d, g = _polyline(arc(5)), _polyline(profile(4))
    error = _one_error(*_post(server.url + "/cnets_construct",
                              _construct_payload(d, g, [0.9, 0.9], {"{0}": [0.5]}, -1.0)),
                       400, "CNets Construct", "apex has 2 entries, expected 4")
    assert "cnets.construct:" not in error


def test_bodies_over_the_limit_get_413(server, small_server):
    error = _one_error(*_post_announced(small_server.url + "/cnets_construct", 2_000_014), 413,
                       "2 MB", "limit of 1 MB", "--max-body")
    assert "request body" in error
    # The default limit is 64 MB: 65 MB is refused, the server stays up and answers.
    status, response = _post_announced(server.url + "/cnets_construct", 65_000_014)
    _one_error(status, response, 413, "65 MB", "limit of 64 MB")
    assert _get(server.url + "/")[0] == 200
    # A body just under the limit is read (and fails as the JSON it is).
    _one_error(*_post(small_server.url + "/cnets_construct", None, raw=b" " * 900_000 + b"{x"),
               400, "not JSON")


def test_solves_run_under_the_memory_budget(small_server):
    d, g = _polyline(arc(200)), _polyline(profile(200))
    _one_error(*_post(small_server.url + "/cnets_construct",
                      _construct_payload(d, g, [0.95], {"{0}": [0.5]}, -1.0)),
               400, "CNets Construct", "needs", "the limit is 2 MB")


def test_coplanar_graph_to_apex_support_and_library(server):
    d, g = _polyline(arc(6)), _polyline(lifted(4))
    status, response = _post(server.url + "/cnets_construct_coplanar", {"values": [
        _param("Directrix", [_curve_item(d)]), _param("Generatrix", [_curve_item(g)]),
        _param("Apex", _number_items([0.9])), _param("RulingRatios", _number_items([0.4])),
        _param("PlaneRatios", _number_items([0.6])), _param("Assistance", _number_items([-1])),
    ]})
    assert status == 200, response
    expected = cnets.construct_coplanar(arc(6), lifted(4), apex=0.9, ruling_ratios=0.4, plane_ratios=0.6)
    mesh = _decode(_values(response)["Mesh"][0])
    np.testing.assert_array_equal(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3))

    widths = [1.0, 1.1, 1.3, 1.2, 1.0, 0.9]
    status, response = _post(server.url + "/cnets_graph_to_apex", {"values": [
        _param("Widths", _number_items(widths)),
        _param("Normalized", [_item("System.Boolean", "false")]),
        _param("Directrix", []), _param("Scale", _number_items([0])),
    ]})
    assert status == 200, response
    apex = [float(a["data"]) for a in _values(response)["Apex"]]
    np.testing.assert_allclose(apex, np.array(widths[1:]) / np.array(widths[:-1]), rtol=1e-15)

    net = cnets.construct(arc(6), lifted(4), apex=0.9)
    from cnets.rhino import quad_mesh_to_rhino

    status, response = _post(server.url + "/cnets_support", {"values": [
        _param("Directrix", [_curve_item(d)]),
        _param("Mesh", [_item("Rhino.Geometry.Mesh", json.dumps(quad_mesh_to_rhino(net).Encode()))]),
        _param("Apex", _number_items(net.apex)), _param("Factor", _number_items([0.8])),
    ]})
    assert status == 200, response
    values = _values(response)
    axes = cnets.eval("cnets.torsion_free_axes", directrix=arc(6), mesh=net)["axes"]
    assert len(values["Axes"]) == 4 * 6
    first = _decode(values["Axes"][0])
    assert [first.PointAtStart.X, first.PointAtStart.Y, first.PointAtStart.Z] == axes[0, 0].tolist()
    support = cnets.eval("cnets.conical_support", directrix=arc(6), mesh=net, apex=net.apex, factor=0.8)["mesh"]
    np.testing.assert_array_equal(_mesh_vertices(_decode(values["Support"][0])),
                                  support.vertices.reshape(-1, 3))
    _one_error(*_post(server.url + "/cnets_support", {"values": [
        _param("Directrix", [_curve_item(d)]),
        _param("Mesh", [_item("Rhino.Geometry.Mesh", json.dumps(rhino3dm.Mesh().Encode()))]),
        _param("Apex", _number_items(net.apex)),
    ]}), 400, "Mesh", "not a quad grid")

    status, response = _post(server.url + "/arc-length", {"values": [_param("Radius", _number_items([2.0]))]})
    assert status == 200, response
    assert json.loads(_values(response)["Length"][0]["data"]) == pytest.approx(2 * np.pi, rel=1e-3)
    # A Hops component saved before the inputs were Capitalised sends the graph's port name.
    status, response = _post(server.url + "/arc-length", {"values": [_param("radius", _number_items([2.0]))]})
    assert status == 200, response
    assert json.loads(_values(response)["Length"][0]["data"]) == pytest.approx(2 * np.pi, rel=1e-3)


def test_concurrent_solves_are_all_answered_while_slow_clients_wait(server):
    """20 solves at once, each answered correctly, while 10 clients hold connections open with
    half-sent requests (a thread each: they delay no one)."""
    host, port = "127.0.0.1", server.port
    slow = []
    for _ in range(10):
        s = socket.create_connection((host, port), timeout=30)
        s.sendall(b"POST /cnets_construct HTTP/1.1\r\nHost: x\r\nContent-Length: 1000\r\n\r\n{")
        slow.append(s)
    try:
        def solve(k):
            n = 4 + k % 5
            d, g = _polyline(arc(5 + k)), _polyline(lifted(n))
            status, response = _post(server.url + "/cnets_construct",
                                     _construct_payload(d, g, [0.95], {"{0}": [0.5]}, -1.0))
            assert status == 200, response
            mesh = _decode(_values(response)["Mesh"][0])
            expected = cnets.construct(arc(5 + k), lifted(n), apex=0.95)
            np.testing.assert_array_equal(_mesh_vertices(mesh), expected.vertices.reshape(-1, 3))
            return k

        with concurrent.futures.ThreadPoolExecutor(20) as pool:
            assert sorted(pool.map(solve, range(20))) == list(range(20))
    finally:
        for s in slow:
            s.close()
    # Each half-sent request is answered as what it is (logged as one line), not as a crash.
    deadline = time.monotonic() + 30
    while server.log().count("the client disconnected") < 10 and time.monotonic() < deadline:
        time.sleep(0.05)
    assert server.log().count("the client disconnected") == 10, server.log()
    assert "Traceback" not in server.log()


def test_nothing_is_printed_per_request(server):
    # What earlier tests' requests still log lands first: the log unchanged for half a second.
    before, deadline = server.log(), time.monotonic() + 30
    while time.monotonic() < deadline:
        time.sleep(0.5)
        if server.log() == before:
            break
        before = server.log()
    d, g = _polyline(arc(5)), _polyline(profile(4))
    for _ in range(3):
        assert _post(server.url + "/cnets_construct",
                     _construct_payload(d, g, [0.9], {"{0}": [0.5]}, -1.0))[0] == 200
    time.sleep(0.2)
    assert server.log() == before, "a successful solve prints nothing"


def test_a_missing_package_is_named(tmp_path):
    """Without werkzeug the server says werkzeug is missing (not ghhops-server), and exits 2."""
    code = ("import sys, runpy; sys.modules['werkzeug'] = None; sys.argv = ['x', '--port', '0'];"
            " runpy.run_module('cnets.hops', run_name='__main__')")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60,
                            cwd=str(tmp_path))
    assert result.returncode == 2, result
    assert "needs the Python package 'werkzeug'" in result.stderr, result.stderr
    assert "pip install" in result.stderr and "Traceback" not in result.stderr
    assert "ghhops" not in result.stderr


def test_the_shipped_library_is_served(tmp_path):
    hops = HopsProcess(tmp_path / "hops.log", "--library", str(LIBRARY))
    try:
        status, listing = _get(hops.url + "/")
        uris = {c["Uri"] for c in listing}
        assert {"/strip-fabrication", "/support-structure", "/reference-fit", "/closed-tube"} <= uris
        assert "skipped" not in hops.log(), hops.log()
        status, meta = _get(hops.url + "/closed-tube")
        assert [p["Name"] for p in meta["Inputs"]] == ["Profile", "Path", "Apex", "Ratios"]
        assert [p["ParamType"] for p in meta["Inputs"]] == ["Curve", "Curve", "Number", "Number"]
        prof = cnets.eval("curve.circle", centre=(4, 0, 0), radius=0.8,
                          plane={"origin": (4, 0, 0), "normal": (0, 2, 1)}, count=8)["curve"]
        t = np.radians(np.linspace(0, 90, 12))
        path = np.c_[4 * np.cos(t), 4 * np.sin(t), np.zeros(12)]
        from cnets.rhino import polyline_to_rhino

        status, response = _post(hops.url + "/closed-tube", {"values": [
            _param("Profile", [_curve_item(polyline_to_rhino(prof))]),
            _param("Path", [_curve_item(_polyline(path))]),
        ]})
        assert status == 200, response
        values = _values(response)
        expected = cnets.eval(f"cluster:{LIBRARY / 'closed-tube.ron'}", profile=prof, path=path)
        mesh = _decode(values["Mesh"][0])
        np.testing.assert_array_equal(_mesh_vertices(mesh), expected["mesh"].vertices.reshape(-1, 3))
        assert mesh.Faces.Count == 8 * 11, "the tube wraps around its profile"
        assert float(values["ClosureGap"][0]["data"]) == expected["closure_gap"]
    finally:
        hops.stop()


def _tube_curves():
    """The closed-tube's test curves: a closed profile of 8 points (N = 8), a path of 12 (M − 1
    = 11)."""
    from cnets.rhino import polyline_to_rhino

    prof = cnets.eval("curve.circle", centre=(4, 0, 0), radius=0.8,
                      plane={"origin": (4, 0, 0), "normal": (0, 2, 1)}, count=8)["curve"]
    t = np.radians(np.linspace(0, 90, 12))
    path = np.c_[4 * np.cos(t), 4 * np.sin(t), np.zeros(12)]
    return prof, path, [_param("Profile", [_curve_item(polyline_to_rhino(prof))]),
                        _param("Path", [_curve_item(_polyline(path))])]


def test_library_components_broadcast_one_number_as_the_builtins_do(tmp_path):
    """/closed-tube's `ratios` is a table port: one number (a tree of one branch of one item,
    what a slider sends) broadcasts to every ratio, as /cnets_construct's Ratios does, and
    solves to the same mesh as the full table of N branches of M − 1; one branch of M − 1 is one
    row for every profile point; one number for the list port `apex` is that number for every
    edge."""
    hops = HopsProcess(tmp_path / "hops.log", "--library", str(LIBRARY))
    try:
        prof, path, curves = _tube_curves()

        def tube(*inputs):
            status, response = _post(hops.url + "/closed-tube", {"values": curves + list(inputs)})
            assert status == 200, response
            assert response["errors"] == [], response
            values = _values(response)
            return (_mesh_vertices(_decode(values["Mesh"][0])),
                    float(values["ClosureGap"][0]["data"]),
                    float(values["MaxPlanarity"][0]["data"]))

        one = tube(_param("Ratios", _number_items([0.4])), _param("Apex", _number_items([0.97])))
        table = tube(_param("Ratios", None, tree={"{%d}" % i: _number_items([0.4] * 11)
                                                  for i in range(8)}),
                     _param("Apex", _number_items([0.97] * 11)))
        row = tube(_param("Ratios", _number_items([0.4] * 11)),
                   _param("Apex", _number_items([0.97])))
        for got in (table, row):
            np.testing.assert_array_equal(got[0], one[0])
            assert got[1:] == one[1:]
        expected = cnets.eval(f"cluster:{LIBRARY / 'closed-tube.ron'}", profile=prof, path=path,
                              ratios=np.full((8, 11), 0.4), apex=[0.97] * 11)
        np.testing.assert_array_equal(one[0], expected["mesh"].vertices.reshape(-1, 3))
        assert one[1] == expected["closure_gap"]
        # The built-in reads one number the same way: the same net.
        status, response = _post(hops.url + "/cnets_construct", {"values": [
            _param("Directrix", curves[1]["InnerTree"]["{0}"]),
            _param("Generatrix", curves[0]["InnerTree"]["{0}"]),
            _param("Apex", _number_items([0.97])), _param("Ratios", _number_items([0.4])),
        ]})
        assert status == 200, response
        np.testing.assert_array_equal(_mesh_vertices(_decode(_values(response)["Mesh"][0])),
                                      one[0])
    finally:
        hops.stop()


def test_library_components_name_their_ports_as_the_builtins(tmp_path):
    """A library graph's ports are presented as the built-ins' are: each port name's words
    Capitalised and joined (`closure_gap` is `ClosureGap`), by the one function that names the
    built-ins' parameters after their engine ports (`ruling_ratios` is `RulingRatios`)."""
    from cnets.hops import _hops_name

    assert [_hops_name(p) for p in ("directrix", "ratios", "ruling_ratios", "plane_ratios")] == \
        ["Directrix", "Ratios", "RulingRatios", "PlaneRatios"]
    hops = HopsProcess(tmp_path / "hops.log", "--library", str(LIBRARY))
    try:
        status, listing = _get(hops.url + "/")
        assert status == 200
        style = __import__("re").compile(r"[A-Z][A-Za-z0-9]*")
        for component in listing:
            for p in component["Inputs"] + component["Outputs"]:
                assert style.fullmatch(p["Name"]), (component["Uri"], p["Name"])
        status, meta = _get(hops.url + "/closed-tube")
        assert [p["Name"] for p in meta["Inputs"]] == ["Profile", "Path", "Apex", "Ratios"]
        assert [p["Name"] for p in meta["Outputs"]] == ["Mesh", "ClosureGap", "MaxPlanarity"]
        assert [p["Nickname"] for p in meta["Inputs"]] == ["Profile", "Path", "Apex", "Ratios"]
        status, meta = _get(hops.url + "/strip-fabrication")
        interface = cnets._cnets.node_interface(f"cluster:{LIBRARY / 'strip-fabrication.ron'}",
                                                None)
        assert [p["Name"] for p in meta["Inputs"]] == \
            [_hops_name(p["name"]) for p in interface["inputs"]]
        assert "SheetWidth" in [p["Name"] for p in meta["Inputs"]]
        # The same input under its port name (what a component saved earlier sends) solves too;
        # an unknown name is refused with the component's input names.
        prof, path, curves = _tube_curves()
        status, response = _post(hops.url + "/closed-tube", {"values": curves + [
            _param("ratios", _number_items([0.4]))]})
        assert status == 200, response
        _one_error(*_post(hops.url + "/closed-tube", {"values": curves + [
            _param("Ratio", _number_items([0.4]))]}), 400, "'Ratio'", "Profile, Path, Apex, Ratios")
    finally:
        hops.stop()


def test_the_built_in_components_say_what_the_nodes_declare():
    """The built-in components' inputs take their descriptions and defaults from the nodes'
    declarations (``cnets.node_types()``), so a node's documentation reaches Hops unchanged."""
    import re

    from cnets import hops

    declared = {(n["id"], p["name"]): p for n in cnets.node_types() for p in n["inputs"]}
    node_of = {
        "/cnets_construct": "cnets.construct",
        "/cnets_construct_coplanar": "cnets.construct_coplanar",
        "/cnets_graph_to_apex": "cnets.graph_to_apex",
        "/cnets_support": "cnets.conical_support",
    }
    checked = 0
    for component in hops._builtin_components(object()):
        node = node_of[component.uri]
        for param in component.inputs:
            port = re.sub(r"(?<!^)([A-Z])", r"_\1", param.name).lower()
            d = declared[(node, port)]
            assert param.description.startswith(d["doc"]), (node, port, param.description)
            if (node, port) != ("cnets.graph_to_apex", "scale"):  # Hops: 0 stands for empty
                assert param.default == d["default"], (node, port, param.default)
            checked += 1
    assert checked == 19
