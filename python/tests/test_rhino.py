"""Rhino files: written with rhino3dm, read back with rhino3dm and compared."""

import numpy as np
import pytest

import cnets
from conftest import arc, profile

import rhino3dm


def _objects_by_layer(model):
    names = [model.Layers[k].Name for k in range(len(model.Layers))]
    by_layer = {}
    for obj in model.Objects:
        by_layer.setdefault(names[obj.Attributes.LayerIndex], []).append(obj.Geometry)
    return names, by_layer


def _mesh_arrays(mesh):
    v = np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices[k] for k in range(len(mesh.Vertices)))])
    f = np.array([list(mesh.Faces[k]) for k in range(mesh.Faces.Count)])
    return v, f


def _curve_points(curve):
    return np.array([[p.X, p.Y, p.Z] for p in (curve.Point(k) for k in range(curve.PointCount))])


def test_cone_net_to_3dm_round_trip(tmp_path):
    d, g = arc(11), profile(6) + [0.0, 0.0, 0.5]  # off the directrix: every node axis defined
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
    v, f = _mesh_arrays(mesh)
    np.testing.assert_allclose(v, net.vertices.reshape(-1, 3), atol=1e-9)
    np.testing.assert_array_equal(f, net.faces())
    (directrix,) = by_layer["Directrix"]
    np.testing.assert_allclose(_curve_points(directrix), d, atol=1e-12)
    (generatrix,) = by_layer["Generatrix"]
    np.testing.assert_allclose(_curve_points(generatrix), g, atol=1e-12)
    axes = cnets.eval("cnets.torsion_free_axes", directrix=d, mesh=net)["axes"]
    assert len(by_layer["Axes"]) == len(axes) == 6 * 11
    a0 = by_layer["Axes"][0]
    np.testing.assert_allclose([[a0.PointAtStart.X, a0.PointAtStart.Y, a0.PointAtStart.Z],
                                [a0.PointAtEnd.X, a0.PointAtEnd.Y, a0.PointAtEnd.Z]], axes[0], atol=1e-12)
    support = cnets.eval("cnets.conical_support", directrix=d, mesh=net, apex=net.apex)["mesh"]
    sv, _ = _mesh_arrays(by_layer["Support"][0])
    np.testing.assert_allclose(sv, support.vertices.reshape(-1, 3), atol=1e-9)


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
    path = tmp_path / "mixed.3dm"
    cnets.write_3dm(path, {"Net": net.vertices, "Path": arc(4), "Beams": lines,
                           "Ring": cnets.Polyline(profile(5), closed=True)})
    model = rhino3dm.File3dm.Read(str(path))
    names, by_layer = _objects_by_layer(model)
    assert {"Net", "Path", "Beams", "Ring"} <= set(names)
    v, f = _mesh_arrays(by_layer["Net"][0])
    assert len(v) == 30 and len(f) == 20  # an (N, M, 3) array is an open quad grid
    assert len(by_layer["Beams"]) == 2
    ring = by_layer["Ring"][0]
    assert ring.IsClosed and ring.PointCount == 6
    with pytest.raises(cnets.CnetsError):
        cnets.write_3dm(tmp_path / "bad.3dm", {"x": np.zeros((2, 2))})
