"""Rhino files: written with rhino3dm, read back with rhino3dm and compared exactly — every
coordinate is the double cnets computed, bit for bit."""

import numpy as np
import pytest

import cnets
from conftest import GRAPHS, arc, lifted, profile

import rhino3dm


def _objects_by_layer(model):
    """Layer full paths (``Parent::Child``) and the geometry on each."""
    names = [model.Layers[k].FullPath for k in range(len(model.Layers))]
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
    assert {"Net", "Path", "Beams", "Ring", "Polygons", "Wrapped::Cone-net"} <= set(names)
    v, f = _mesh_arrays(by_layer["Net"][0])
    assert len(v) == 30 and len(f) == 20  # an (N, M, 3) array is an open quad grid
    np.testing.assert_array_equal(v, net.vertices.reshape(-1, 3))
    v, f = _mesh_arrays(by_layer["Wrapped::Cone-net"][0])
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


def _layers(model):
    return {layer.FullPath: layer for layer in model.Layers}


def test_a_named_cone_net_gets_nested_coloured_layers(tmp_path):
    """``{"Facade far": net}``: a parent layer "Facade far" and its sublayers, each with its
    parent's id (Rhino shows "Facade far::Cone-net"), every layer with its colour."""
    d, g = arc(11), lifted(6)
    net = cnets.construct(d, g, apex=0.9)
    path = tmp_path / "nested.3dm"
    cnets.write_3dm(path, {"Facade far": net, "Site::Path": d, "Beams": np.zeros((2, 2, 3)) + [[0, 0, 0], [1, 1, 1]]},
                    colours={"Beams": (10, 20, 30), "Site": (1, 2, 3, 255)})
    model = rhino3dm.File3dm.Read(str(path))
    layers = _layers(model)
    parent = layers["Facade far"]
    assert parent.Name == "Facade far"
    assert str(parent.ParentLayerId) == "00000000-0000-0000-0000-000000000000"
    from cnets.rhino import KIND_COLOURS, LAYER_COLOURS
    assert parent.Color == LAYER_COLOURS["Cone-net"]
    for sub in ["Cone-net", "Directrix", "Generatrix", "Axes", "Support"]:
        layer = layers[f"Facade far::{sub}"]
        assert layer.Name == sub, "the name is the part, the full path has the parent"
        assert layer.ParentLayerId == parent.Id
        assert layer.Color == LAYER_COLOURS[sub], sub
    assert not any("/" in name for name in layers)
    assert layers["Site"].Color == (1, 2, 3, 255)
    assert layers["Site::Path"].ParentLayerId == layers["Site"].Id
    assert layers["Site::Path"].Color == KIND_COLOURS["curve"]
    assert layers["Beams"].Color == (10, 20, 30, 255)
    assert len(layers) == 9
    names, by_layer = _objects_by_layer(model)
    (mesh,) = by_layer["Facade far::Cone-net"]
    np.testing.assert_array_equal(_mesh_arrays(mesh)[0], net.vertices.reshape(-1, 3))
    with pytest.raises(cnets.CnetsError, match=r"objects: layer name 'a::' has an empty part"):
        cnets.write_3dm(tmp_path / "bad.3dm", {"a::": d})
    with pytest.raises(cnets.CnetsError, match=r"colours\['x'\]"):
        cnets.write_3dm(tmp_path / "bad.3dm", {"x": d}, colours={"x": (300, 0, 0)})


def _groups_of(model):
    """Group name → the geometry of its members."""
    return {model.Groups[k].Name: [o.Geometry for o in model.Groups.GroupMembers(k)]
            for k in range(len(model.Groups))}


def test_axes_are_one_family_and_lines_on_request(tmp_path):
    """The node axes (disjoint segments) as one group named after their layer; a line set whose
    segments follow each other as one polyline; ``axes_as="lines"`` the old loose lines."""
    d, g = arc(11), lifted(6)
    net = cnets.construct(d, g, apex=0.9)
    axes = cnets.eval("cnets.torsion_free_axes", directrix=d, mesh=net)["axes"]
    chain = np.stack([d[:-1], d[1:]], axis=1)          # the directrix's edges, end to start
    path = tmp_path / "family.3dm"
    cnets.write_3dm(path, {"Facade": net, "Edges": chain, "Beams": axes[:5]})
    model = rhino3dm.File3dm.Read(str(path))
    names, by_layer = _objects_by_layer(model)
    groups = _groups_of(model)
    assert set(groups) == {"Facade::Axes", "Beams"}
    members = groups["Facade::Axes"]
    assert len(members) == len(by_layer["Facade::Axes"]) == len(axes) == 66
    got = np.array([[[c.PointAtStart.X, c.PointAtStart.Y, c.PointAtStart.Z],
                     [c.PointAtEnd.X, c.PointAtEnd.Y, c.PointAtEnd.Z]] for c in members])
    np.testing.assert_array_equal(got, axes)
    (edges,) = by_layer["Edges"]
    assert isinstance(edges, rhino3dm.PolylineCurve) and edges.IsValid
    np.testing.assert_array_equal(_curve_points(edges), d)
    assert len(groups["Beams"]) == 5
    # The old files: one loose line per segment, no group.
    path = tmp_path / "lines.3dm"
    net.to_3dm(path, axes_as="lines")
    model = rhino3dm.File3dm.Read(str(path))
    names, by_layer = _objects_by_layer(model)
    assert len(model.Groups) == 0
    assert len(by_layer["Axes"]) == 66
    assert all(isinstance(c, rhino3dm.LineCurve) for c in by_layer["Axes"])
    cnets.write_3dm(path, {"Edges": chain}, axes_as="lines")
    assert len(_objects_by_layer(rhino3dm.File3dm.Read(str(path)))[1]["Edges"]) == 10
    for bad in ["polycurve", None, 1]:
        with pytest.raises(cnets.CnetsError, match="axes_as: expected one of 'family', 'lines'"):
            cnets.write_3dm(tmp_path / "bad.3dm", {"x": chain}, axes_as=bad)
        with pytest.raises(cnets.CnetsError, match="axes_as"):
            net.to_3dm(tmp_path / "bad.3dm", axes_as=bad)
    assert not (tmp_path / "bad.3dm").exists()


def test_a_list_under_one_name_is_one_group(tmp_path):
    """The support structure's beams (a list of strips) as one family: one mesh per beam, all in
    one group."""
    d, g = arc(11), lifted(6)
    net = cnets.construct(d, g, apex=0.9)
    out = cnets.eval(f"cluster:{GRAPHS / 'library' / 'support-structure.ron'}", directrix=d, mesh=net,
                     apex=net.apex, factor=0.85)
    strips = out["beams"]
    assert len(strips) == 11
    path = tmp_path / "beams.3dm"
    cnets.write_3dm(path, {"Structure::Beams": strips, "Structure::Layer": out["layer"],
                           "Structure::Axes": out["axes"]})
    model = rhino3dm.File3dm.Read(str(path))
    groups = _groups_of(model)
    assert set(groups) == {"Structure::Beams", "Structure::Axes"}
    assert len(groups["Structure::Beams"]) == 11
    assert len(groups["Structure::Axes"]) == 66
    for strip, mesh in zip(strips, groups["Structure::Beams"]):
        np.testing.assert_array_equal(_mesh_arrays(mesh)[0], strip.vertices.reshape(-1, 3))


def test_exact_doubles_read_back_250_m_out(tmp_path):
    """What docs/python.md shows: a mesh written 250 m (250 000 mm) from the origin read back
    bit for bit through rhino3dm's double-precision accessors — ``Vertices.Point3dAt(i)`` and
    ``Vertices.ToPoint3dArray()`` — while ``Vertices[i]`` is the single-precision ``Point3f``
    copy. And building a mesh by hand: ``Vertices.AddPoint3d`` keeps doubles, ``Vertices.Add``
    does not (even with ``UseDoublePrecisionVertices``)."""
    t = np.radians(np.linspace(0.0, 60.0, 30))
    d = np.c_[20000 * np.cos(t), 20000 * np.sin(t), np.zeros(30)] + [250_000.0, 250_000.0, 0.0]
    s = np.linspace(0.0, 1.0, 12)
    g = np.c_[20000 + 3000 * s, 400 * np.sin(2 * s), 500 + 12000 * s] + [250_000.0, 250_000.0, 0.0]
    net = cnets.construct(d, g, apex=0.97)
    path = tmp_path / "far.3dm"
    cnets.write_3dm(path, {"Facade": net.vertices})
    model = rhino3dm.File3dm.Read(str(path))
    mesh = model.Objects[0].Geometry
    assert mesh.Vertices.UseDoublePrecisionVertices
    expected = net.vertices.reshape(-1, 3)
    # The docs' lines, as written there.
    v = np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()])
    assert v.tobytes() == expected.tobytes()
    at = np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices.Point3dAt(i)
                                              for i in range(len(mesh.Vertices)))])
    assert at.tobytes() == expected.tobytes()
    single = np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices[i] for i in range(len(mesh.Vertices)))])
    assert isinstance(mesh.Vertices[0], rhino3dm.Point3f)
    off = np.abs(single - expected).max()
    assert 1e-3 < off < 2e-2, off          # millimetres: 7.8e-3 mm at 250 m, the float32 step
    # Building a mesh by hand.
    x, y, z = expected[13].tolist()
    assert float(np.float32(x)) != x
    m = rhino3dm.Mesh()
    m.Vertices.UseDoublePrecisionVertices = True
    m.Vertices.AddPoint3d(x, y, z)
    m.Vertices.Add(x, y, z)
    kept, lost = m.Vertices.Point3dAt(0), m.Vertices.Point3dAt(1)
    assert (kept.X, kept.Y, kept.Z) == (x, y, z)
    assert (lost.X, lost.Y, lost.Z) != (x, y, z)
