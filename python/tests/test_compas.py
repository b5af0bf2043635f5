"""The COMPAS bridge: ``QuadMesh.to_compas()`` / ``ConeNet.to_compas()`` /
``PolygonMesh.to_compas()`` give a ``compas.datastructures.Mesh``; ``cnets.from_compas(mesh)``
a ``PolygonMesh`` that ``measure.surface_distance`` takes as its reference. Against a real
``compas`` install (scripts/requirements-python.txt); vertices compared bit for bit."""

import sys

import numpy as np
import pytest

import cnets
from conftest import arc, lifted

from compas.datastructures import Mesh


def _far_net():
    """A facade in millimetres 250 m out: doubles that float32 would round."""
    t = np.radians(np.linspace(0.0, 60.0, 14))
    d = np.c_[20000 * np.cos(t), 20000 * np.sin(t), np.zeros(14)] + [250_000.0, 250_000.0, 0.0]
    s = np.linspace(0.0, 1.0, 7)
    g = np.c_[20000 + 3000 * s, 400 * np.sin(2 * s), 500 + 12000 * s] + [250_000.0, 250_000.0, 0.0]
    return cnets.construct(d, g, apex=0.97)


def test_cone_net_round_trip_is_bit_for_bit():
    net = _far_net()
    mesh = net.to_compas()
    assert isinstance(mesh, Mesh)
    n, m = net.shape
    assert mesh.number_of_vertices() == n * m
    assert mesh.number_of_faces() == (n - 1) * (m - 1)
    expected = net.vertices.reshape(-1, 3)
    # COMPAS' own view: vertex i * M + j is row i, column j, every double kept.
    for key in (0, 5, m, n * m - 1):
        assert mesh.vertex_coordinates(key) == expected[key].tolist()
    vertices, faces = mesh.to_vertices_and_faces()
    assert np.asarray(vertices).tobytes() == expected.tobytes()
    assert faces == net.faces().tolist()
    back = cnets.from_compas(mesh)
    assert isinstance(back, cnets.PolygonMesh)
    assert back.vertices.dtype == np.float64
    assert back.vertices.tobytes() == expected.tobytes()
    assert back.faces == net.faces().tolist()


def test_wrapped_and_polygon_meshes():
    net = cnets.construct(arc(6), cnets.Polyline(lifted(5), closed=True))
    assert net.wrap_rows or net.wrap_cols
    mesh = net.to_compas()
    assert mesh.number_of_faces() == len(net.faces()), "the seam's quads are kept"
    polygons = cnets.PolygonMesh(np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0.5, 1.5, 0.1],
                                           [0, 1, 0.3]]), [[0, 1, 2, 3, 4], [0, 1, 2]])
    back = cnets.from_compas(polygons.to_compas())
    assert back.vertices.tobytes() == polygons.vertices.tobytes()
    assert back.faces == polygons.faces


def test_from_compas_maps_keys_and_feeds_surface_distance():
    """A COMPAS mesh edited in COMPAS (a vertex deleted: keys no longer 0…V−1) as the
    reference of measure.surface_distance: the distance of a net to its own mesh is 0."""
    net = cnets.construct(arc(8), lifted(5), apex=0.9)
    mesh = net.to_compas()
    extra = mesh.add_vertex(x=100.0, y=0.0, z=0.0)
    mesh.add_face([extra, 0, 1])
    mesh.delete_vertex(2)  # and the faces around it
    reference = cnets.from_compas(mesh)
    keys = list(mesh.vertices())
    assert len(reference.vertices) == len(keys) and 2 not in keys
    for face, key in zip(reference.faces, mesh.faces()):
        assert [keys[i] for i in face] == mesh.face_vertices(key)
    out = cnets.eval("measure.surface_distance", mesh=net, reference=cnets.from_compas(net.to_compas()))
    assert out["max"] == 0.0 and out["value"] == 0.0
    out = cnets.eval("measure.surface_distance", mesh=net, reference=reference)
    assert out["from_reference_max"] > 50.0, "the far vertex's face is measured"


def test_from_compas_refuses_what_is_not_a_compas_mesh():
    for bad in [None, np.zeros((3, 3)), "mesh", cnets.PolygonMesh(np.eye(3), [[0, 1, 2]])]:
        with pytest.raises(cnets.CnetsError, match="mesh: expected a compas.datastructures.Mesh"):
            cnets.from_compas(bad)
    with pytest.raises(cnets.CnetsError, match="no vertices"):
        cnets.from_compas(Mesh())


def test_a_missing_compas_is_named(monkeypatch):
    """Without compas installed (simulated: None in sys.modules makes its import fail), every
    entry point says which package is missing and how to install it."""
    for name in [m for m in sys.modules if m == "compas" or m.startswith("compas.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "compas", None)
    monkeypatch.setitem(sys.modules, "compas.datastructures", None)
    net = cnets.construct(arc(5), lifted(4))
    for call in [net.to_compas, cnets.QuadMesh(net.vertices).to_compas,
                 cnets.PolygonMesh(np.eye(3), [[0, 1, 2]]).to_compas,
                 lambda: cnets.from_compas(object())]:
        with pytest.raises(ImportError) as e:
            call()
        message = str(e.value)
        assert "needs the compas package" in message, message
        assert 'pip install "cnets[compas]"' in message, message
