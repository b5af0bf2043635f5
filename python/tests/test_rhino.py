"""Rhino files: written with rhino3dm, read back with rhino3dm and compared exactly — every
coordinate is the double cnets computed, bit for bit."""

import numpy as np
import pytest

import cnets
from conftest import arc, lifted, profile

import rhino3dm


def _objects_by_layer(model):
    names = [model.Layers[k].Name for k in range(len(model.Layers))]
    by_layer = {}
    for obj in model.Objects:
        by_layer.setdefault(names[obj.Attributes.LayerIndex], []).append(obj.Geometry)
    return names, by_layer


def _mesh_arrays(mesh):
    """A Rhino mesh's vertices at the precision it stores them, and its faces."""
    v = np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()])
    f = np.array([list(mesh.Faces[k]) for k in range(mesh.Faces.Count)])
    return v, f


def _curve_points(curve):
    return np.array([[p.X, p.Y, p.Z] for p in (curve.Point(k) for k in range(curve.PointCount))])


def _planarity(vertices, faces):
    """The libigl planarity of every quad (distance of the diagonals over their mean length)."""
    q = vertices[faces]
    d1, d2 = q[:, 2] - q[:, 0], q[:, 3] - q[:, 1]
    n = np.cross(d1, d2)
    dist = np.abs(np.einsum("ij,ij->i", q[:, 1] - q[:, 0], n)) / np.linalg.norm(n, axis=1)
    return dist / ((np.linalg.norm(d1, axis=1) + np.linalg.norm(d2, axis=1)) / 2)


def test_cone_net_to_3dm_round_trip_is_exact(tmp_path):
    d, g = arc(11), lifted(6)  # off the directrix: every node axis defined
    net = cnets.construct(d, g, apex=0.9)
    path = tmp_path / "net.3dm"
    net.to_3dm(path, layers=True)
    model = rhino3dm.File3dm.Read(str(path))
    assert model is not None
    names, by_layer = _objects_by_layer(model)
    for layer in ["Cone-net", "Directrix", "Generatrix", "Axes", "Support"]:
        assert layer in names, names
        assert by_layer.get(layer), layer
    (mesh,) = by_layer["Cone-net"]
    assert mesh.Vertices.UseDoublePrecisionVertices
    v, f = _mesh_arrays(mesh)
    np.testing.assert_array_equal(v, net.vertices.reshape(-1, 3))
    np.testing.assert_array_equal(f, net.faces())
    (directrix,) = by_layer["Directrix"]
    np.testing.assert_array_equal(_curve_points(directrix), d)
    (generatrix,) = by_layer["Generatrix"]
    np.testing.assert_array_equal(_curve_points(generatrix), g)
    axes = cnets.eval("cnets.torsion_free_axes", directrix=d, mesh=net)["axes"]
    assert len(by_layer["Axes"]) == len(axes) == 6 * 11
    for line, expected in zip(by_layer["Axes"], axes):
        got = [[line.PointAtStart.X, line.PointAtStart.Y, line.PointAtStart.Z],
               [line.PointAtEnd.X, line.PointAtEnd.Y, line.PointAtEnd.Z]]
        np.testing.assert_array_equal(got, expected)
    support = cnets.eval("cnets.conical_support", directrix=d, mesh=net, apex=net.apex)["mesh"]
    sv, _ = _mesh_arrays(by_layer["Support"][0])
    np.testing.assert_array_equal(sv, support.vertices.reshape(-1, 3))


def test_a_facade_far_from_the_origin_keeps_its_planarity(tmp_path):
    """The issue's case: a facade in millimetres placed 250 m from the origin. Single-precision
    vertices would move vertex 0 by ~2e-7 relative (0.05 mm of planarity); the file keeps every
    double, so the faces read back are exactly as planar as computed."""
    t = np.radians(np.linspace(0.0, 60.0, 30))
    d = np.c_[20000 * np.cos(t), 20000 * np.sin(t), np.zeros(30)] + [250_000.0, 250_000.0, 0.0]
    s = np.linspace(0.0, 1.0, 12)
    g = np.c_[20000 + 3000 * s, 400 * np.sin(2 * s), 500 + 12000 * s] + [250_000.0, 250_000.0, 0.0]
    net = cnets.construct(d, g, apex=0.97, ratios=np.linspace(0.4, 0.6, 29))
    path = tmp_path / "facade.3dm"
    cnets.write_3dm(path, {"Facade": net.vertices})
    (mesh,) = _objects_by_layer(rhino3dm.File3dm.Read(str(path)))[1]["Facade"]
    v, f = _mesh_arrays(mesh)
    expected = net.vertices.reshape(-1, 3)
    assert np.max(np.abs(v - expected) / np.abs(expected).max()) <= 1e-15
    np.testing.assert_array_equal(v, expected)
    np.testing.assert_array_equal(_planarity(v, f), _planarity(expected, net.faces()))
    assert _planarity(v, f).max() < 1e-9
    # What single precision would have done (the old files): visible planarity defects.
    single = expected.astype(np.float32).astype(np.float64)
    assert _planarity(single, f).max() > 1e-7


def test_without_layers_everything_is_on_the_default_layer(tmp_path):
    net = cnets.construct(arc(5), profile(4))
    path = tmp_path / "flat.3dm"
    with pytest.warns(UserWarning) as record:  # G_00 = X_0: no axis, no support there
        net.to_3dm(path, layers=False)
    messages = " ".join(str(w.message) for w in record)
    assert "no Axes layer" in messages and "no Support layer" in messages
    model = rhino3dm.File3dm.Read(str(path))
    names, by_layer = _objects_by_layer(model)
    assert "Cone-net" not in names
    assert sum(len(v) for v in by_layer.values()) == len(model.Objects) >= 3
    assert len(by_layer) == 1


def test_write_3dm_mixed_objects(tmp_path):
    net = cnets.construct(arc(6), cnets.Polyline(profile(5), closed=True))
    lines = np.array([[[0, 0, 0], [1, 0, 0]], [[0, 1, 0], [1, 1, 2]]], dtype=float)
    polygons = cnets.PolygonMesh(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0.5, 1.5, 0.1],
                                           [0, 1, 0]], dtype=float), [[0, 1, 2, 3, 4], [0, 1, 2]])
    path = tmp_path / "mixed.3dm"
    with pytest.warns(cnets.CnetsWarning) as record:  # G_00 = X_0: no axes, no support
        cnets.write_3dm(path, {"Net": net.vertices, "Path": arc(4), "Beams": lines,
                               "Ring": cnets.Polyline(profile(5), closed=True), "Wrapped": net,
                               "Polygons": polygons})
    assert {str(w.message).split(":")[1].strip() for w in record} == {"no Axes layer",
                                                                       "no Support layer"}
    model = rhino3dm.File3dm.Read(str(path))
    names, by_layer = _objects_by_layer(model)
    assert {"Net", "Path", "Beams", "Ring", "Polygons", "Wrapped/Cone-net"} <= set(names)
    v, f = _mesh_arrays(by_layer["Net"][0])
    assert len(v) == 30 and len(f) == 20  # an (N, M, 3) array is an open quad grid
    np.testing.assert_array_equal(v, net.vertices.reshape(-1, 3))
    v, f = _mesh_arrays(by_layer["Wrapped/Cone-net"][0])
    assert len(f) == 25, "the wrapped net keeps its seam quads"
    np.testing.assert_array_equal(v, net.vertices.reshape(-1, 3))
    assert len(by_layer["Beams"]) == 2
    ring = by_layer["Ring"][0]
    assert ring.IsClosed and ring.PointCount == 6
    np.testing.assert_array_equal(_curve_points(ring)[:5], profile(5))
    v, f = _mesh_arrays(by_layer["Polygons"][0])
    np.testing.assert_array_equal(v, polygons.vertices)
    assert f.tolist() == [[0, 1, 2, 2], [0, 2, 3, 3], [0, 3, 4, 4], [0, 1, 2, 2]], "fanned"
    with pytest.raises(cnets.CnetsError, match=r"objects\['x'\]: cannot write an array of shape \(2, 2\)"):
        cnets.write_3dm(tmp_path / "bad.3dm", {"x": np.zeros((2, 2))})
    assert not (tmp_path / "bad.3dm").exists()
