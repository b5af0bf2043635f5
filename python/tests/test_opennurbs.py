"""Rhino meshes written by cnets itself (cnets._opennurbs): byte for byte what rhino3dm writes
where rhino3dm stores its buffers uncompressed (up to 5 double-precision vertices), and read back
by rhino3dm exactly — every double, every face — at any size."""

import base64

import numpy as np
import pytest

from cnets._opennurbs import encode_mesh

import rhino3dm


def _rhino3dm_encoding(vertices, faces):
    mesh = rhino3dm.Mesh()
    mesh.Vertices.UseDoublePrecisionVertices = True
    for p in vertices.tolist():
        mesh.Vertices.AddPoint3d(*p)
    for f in faces:
        mesh.Faces.AddFace(*f)
    return mesh.Encode()


@pytest.mark.parametrize("vertices,faces", [
    (np.zeros((0, 3)), []),
    (np.array([[1.0, 2.0, 3.0]]), []),
    (np.array([[0.1, 0.2, 0.3], [250_000.123456789, 1e-300, -7.5], [3.0, 4.0, 5.0]]), [(0, 1, 2)]),
    (np.random.default_rng(3).normal(size=(4, 3)) * 1e5, [(0, 1, 2, 3), (0, 1, 2)]),
    (np.random.default_rng(4).normal(size=(5, 3)), [(0, 1, 2, 3), (1, 2, 3, 4), (4, 0, 1)]),
])
def test_small_meshes_are_byte_for_byte_rhino3dms(vertices, faces):
    ours = encode_mesh(vertices, np.array([f if len(f) == 4 else f + (f[2],) for f in faces],
                                          dtype=np.int64).reshape(-1, 4))
    theirs = _rhino3dm_encoding(vertices, faces)
    assert {k: v for k, v in ours.items() if k != "data"} == \
        {k: v for k, v in theirs.items() if k != "data"}
    assert base64.b64decode(ours["data"]) == base64.b64decode(theirs["data"])


@pytest.mark.parametrize("rows,cols", [(2, 2), (20, 13), (300, 256)])
def test_meshes_of_any_size_read_back_exactly(rows, cols):
    """Face indices are written as bytes, shorts or ints by the vertex count (256 and 65 536 are
    the thresholds); every vertex comes back as the same double."""
    rng = np.random.default_rng(rows)
    v = rng.normal(size=(rows * cols, 3)) * 1e4 + 3e5
    idx = np.arange(rows * cols).reshape(rows, cols)
    faces = np.stack([idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]], -1).reshape(-1, 4)
    mesh = rhino3dm.CommonObject.Decode(encode_mesh(v, faces))
    assert isinstance(mesh, rhino3dm.Mesh) and mesh.IsValid
    assert mesh.Vertices.UseDoublePrecisionVertices
    back = np.array([[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()])
    np.testing.assert_array_equal(back, v)
    assert mesh.Faces.Count == len(faces) and mesh.Faces.QuadCount == len(faces)
    assert [list(mesh.Faces[k]) for k in (0, len(faces) - 1)] == [faces[0].tolist(), faces[-1].tolist()]
    # The single-precision copy Rhino keeps beside them is the rounding of the same numbers.
    single = np.array([[p.X, p.Y, p.Z] for p in (mesh.Vertices[k] for k in range(3))])
    np.testing.assert_array_equal(single, v[:3].astype(np.float32))


def test_bad_faces_are_refused():
    with pytest.raises(ValueError, match="out of range"):
        encode_mesh(np.zeros((3, 3)), np.array([[0, 1, 2, 3]]))


def test_the_json_text_is_json_dumps_of_the_encoding():
    import json

    from cnets._opennurbs import encode_mesh_json

    v = np.random.default_rng(5).normal(size=(7, 3))
    f = np.array([[0, 1, 2, 3], [3, 4, 5, 6]])
    assert encode_mesh_json(v, f) == json.dumps(encode_mesh(v, f))
