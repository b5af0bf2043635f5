"""Rhino meshes as Rhino's JSON encoding (``{"version", "archive3dm", "opennurbs", "data"}``, what
``rhino3dm.CommonObject.Encode()`` returns and Grasshopper's Hops decodes), written from numpy
arrays in bulk — no Python object per vertex — with double-precision vertices.

``data`` is a base64 openNURBS archive holding one ``ON_Mesh`` (class record, mesh chunk version
3.8 as openNURBS 8 writes it for 3dm version 60): vertex and face counts, the single-precision
vertex copy Rhino always keeps, the face array, and the double-precision vertex chunk that makes
Rhino use the exact coordinates. Buffers are stored uncompressed (openNURBS' method 0, which every
reader accepts; openNURBS itself chooses it for buffers of up to 128 bytes), so small meshes come
out byte for byte as rhino3dm writes them (``python/tests/test_opennurbs.py``) and large ones cost
no compression time. Everything is little-endian, as 3dm archives are.
"""

from __future__ import annotations

import base64
import struct
import zlib
from typing import Dict, List, Sequence, Union

import numpy as np

__all__ = ["encode_mesh", "encode_mesh_json", "ARCHIVE_3DM", "OPENNURBS_VERSION"]

#: The 3dm archive version of the encoding (openNURBS 8 writes meshes for version 60).
ARCHIVE_3DM = 60
#: The openNURBS version number written with it (rhino3dm 8's, as ``Encode()`` reports it).
OPENNURBS_VERSION = -1869833980

# Chunk type codes (opennurbs_3dm.h).
_TCODE_OPENNURBS_CLASS = 0x00027FFA
_TCODE_OPENNURBS_CLASS_UUID = 0x0002FFFB
_TCODE_OPENNURBS_CLASS_DATA = 0x0002FFFC
_TCODE_OPENNURBS_CLASS_END = 0x80027FFF
_TCODE_ANONYMOUS_CHUNK = 0x40008000
_TCODE_CRC = 0x8000
# ON_Mesh's class id {4ED7D4E4-E947-11d3-BFE5-0010830122F0}, as ON_BinaryArchive::WriteUuid
# stores it.
_MESH_CLASS_ID = bytes.fromhex("e4d4d74e47e9d311bfe50010830122f0")
_UNSET = struct.pack("<d", -1.23432101234321e308)  # ON_UNSET_VALUE
_IDENTITY = struct.pack("<16d", *np.eye(4).reshape(-1))


class _Chunk:
    """A long chunk being written: its content bytes (nested chunks included whole) and the
    bytes written directly into it, which its CRC covers when its type code asks for one."""

    def __init__(self, typecode: int, version: Union[tuple, None] = None) -> None:
        self.typecode = typecode
        self.parts: List[bytes] = []
        self.crc = 0
        if version is not None:
            self.write(struct.pack("<ii", *version))

    def write(self, data: bytes) -> None:
        self.parts.append(data)
        if self.typecode & _TCODE_CRC:
            self.crc = zlib.crc32(data, self.crc)

    def nest(self, chunk: "_Chunk") -> None:
        self.parts.append(chunk.bytes())

    def bytes(self) -> bytes:
        if self.typecode & _TCODE_CRC:
            self.parts.append(struct.pack("<I", self.crc))
        body = b"".join(self.parts)
        return struct.pack("<Iq", self.typecode, len(body)) + body


def _buffer(data: bytes) -> bytes:
    """ON_BinaryArchive::WriteCompressedBuffer, uncompressed: size, CRC, method 0, the bytes."""
    if not data:
        return struct.pack("<I", 0)
    return struct.pack("<IIB", len(data), zlib.crc32(data), 0) + data


def _faces(faces: np.ndarray, vertex_count: int) -> bytes:
    """The face array (ON_Mesh::WriteFaceArray): the index size, then 4 indices a face (a
    triangle repeats its third)."""
    if vertex_count < 256:
        size, dtype = 1, "<u1"
    elif vertex_count < 65536:
        size, dtype = 2, "<u2"
    else:
        size, dtype = 4, "<i4"
    return struct.pack("<i", size) + np.ascontiguousarray(faces, dtype=dtype).tobytes()


def _mapping_tag() -> _Chunk:
    """The default ON_MappingTag (ON_MappingTag::Write, chunk version 1.1)."""
    tag = _Chunk(_TCODE_ANONYMOUS_CHUNK, (1, 1))
    tag.write(bytes(16) + struct.pack("<I", 0) + _IDENTITY + struct.pack("<I", 0))
    return tag


def _mesh_data(vertices: np.ndarray, faces: np.ndarray) -> _Chunk:
    """ON_Mesh::Write (chunk version 3.8) of a mesh with double-precision vertices."""
    v_count, f_count = len(vertices), len(faces)
    data = _Chunk(_TCODE_OPENNURBS_CLASS_DATA)
    data.write(bytes([3 * 16 + 8]))  # Write3dmChunkVersion(3, 8)
    data.write(struct.pack("<ii", v_count, f_count))
    data.write(_UNSET * 8)  # packed texture domain, surface domain (ON_Interval unset ×4)
    data.write(struct.pack("<dd", 0.0, 0.0))  # m_srf_scale
    empty_box = struct.pack("<6f", 1, 1, 1, -1, -1, -1)
    data.write(empty_box)  # single-precision vertex box (unset: readers recompute it)
    data.write(empty_box)  # normal box
    data.write(struct.pack("<4f", 1, 1, -1, -1))  # texture box
    data.write(struct.pack("<i", -1))  # closed: unknown
    data.write(bytes(5))  # no mesh parameters, no curvature statistics
    data.write(_faces(faces, v_count))
    if v_count:
        singles = np.ascontiguousarray(vertices, dtype="<f4").tobytes()
        data.write(_buffer(singles))
        data.write(_buffer(b"") * 4)  # normals, texture coordinates, curvatures, colours
    data.write(struct.pack("<i", 0) + bytes(16))  # packed texture rotation, mapping id
    if v_count:
        data.write(_buffer(b""))  # surface parameters
    data.nest(_mapping_tag())
    data.write(bytes(3))  # manifold, oriented, solid: unknown
    data.write(b"\x00")  # no n-gons
    # Double-precision vertices (an empty mesh has none).
    data.write(b"\x01" if v_count else b"\x00")
    if v_count:
        doubles = _Chunk(_TCODE_ANONYMOUS_CHUNK, (1, 0))
        doubles.write(struct.pack("<I", v_count))
        doubles.write(_buffer(np.ascontiguousarray(vertices, dtype="<f8").tobytes()))
        data.nest(doubles)
    data.write(_UNSET * 6)  # double-precision vertex box: unset
    return data


def encode_mesh(vertices: np.ndarray, faces: Union[np.ndarray, Sequence[Sequence[int]]]) -> Dict[str, object]:
    """A mesh as Rhino's JSON encoding (``rhino3dm.CommonObject.Decode`` reads it back into a
    ``rhino3dm.Mesh``; Hops into a Grasshopper mesh). ``vertices``: (V, 3) float64, stored
    exactly; ``faces``: (F, 4) vertex indices, a triangle repeating its third index."""
    return {
        "version": 10000,
        "archive3dm": ARCHIVE_3DM,
        "opennurbs": OPENNURBS_VERSION,
        "data": _archive(vertices, faces),
    }


def encode_mesh_json(vertices: np.ndarray, faces: Union[np.ndarray, Sequence[Sequence[int]]]) -> str:
    """``json.dumps(encode_mesh(vertices, faces))``, written directly (base64 needs no escaping:
    a megabyte string is not scanned again)."""
    return (f'{{"version": 10000, "archive3dm": {ARCHIVE_3DM}, "opennurbs": {OPENNURBS_VERSION}, '
            f'"data": "{_archive(vertices, faces)}"}}')


def _archive(vertices: np.ndarray, faces: Union[np.ndarray, Sequence[Sequence[int]]]) -> str:
    """The base64 archive of the mesh."""
    v = np.asarray(vertices, dtype=np.float64).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 4)
    if f.size and (f.min() < 0 or f.max() >= len(v)):
        raise ValueError("face indices out of range")
    record = _Chunk(_TCODE_OPENNURBS_CLASS)
    uuid = _Chunk(_TCODE_OPENNURBS_CLASS_UUID)
    uuid.write(_MESH_CLASS_ID)
    record.nest(uuid)
    record.nest(_mesh_data(v, f))
    record.parts.append(struct.pack("<Iq", _TCODE_OPENNURBS_CLASS_END, 0))
    return base64.b64encode(record.bytes()).decode("ascii")
