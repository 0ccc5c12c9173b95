#!/usr/bin/env python3
"""Writes the hand-made glTF fixtures of this folder: a unit square (4 vertices, 2 triangles) as .gltf and
.glb, and broken variants of it, each broken in one way. Run from this folder: python3 make_fixtures.py"""
import base64
import json
import struct

POSITIONS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
INDICES = [0, 1, 2, 0, 2, 3]


def square(positions=POSITIONS, indices=INDICES, count=4, attribute="POSITION", uri=None, units="mm"):
    """The square's JSON and its buffer: positions (48 bytes) then u16 indices (12 bytes)."""
    data = b"".join(struct.pack("<3f", *p) for p in positions) + struct.pack("<6H", *indices)
    buffer = {"byteLength": len(data)}
    if uri is not None:
        buffer["uri"] = uri
    doc = {
        "asset": {"version": "2.0", "generator": "make_fixtures.py", "extras": {"units": units}},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"name": "square", "primitives": [{"attributes": {attribute: 0}, "indices": 1, "mode": 4}]}],
        "buffers": [buffer],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
            {"buffer": 0, "byteOffset": 48, "byteLength": 12, "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    return doc, data


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def gltf(name, doc, data, indent=2):
    doc["buffers"][0].setdefault("uri", data_uri(data))
    with open(name, "w") as f:
        f.write(json.dumps(doc, indent=indent) + "\n")


def glb_bytes(doc, data, version=2, magic=b"glTF", json_length=None, bin_length=None):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    chunks = struct.pack("<I4s", len(text) if json_length is None else json_length, b"JSON") + text
    chunks += struct.pack("<I4s", len(data) if bin_length is None else bin_length, b"BIN\0") + data
    return magic + struct.pack("<II", version, 12 + len(chunks)) + chunks


def glb(name, *args, **kwargs):
    with open(name, "wb") as f:
        f.write(glb_bytes(*args, **kwargs))


gltf("square.gltf", *square())
glb("square.glb", *square())

# Containers.
glb("bad_magic.glb", *square(), magic=b"GLTF")
glb("bad_version.glb", *square(), version=1)
glb("json_chunk_past_end.glb", *square(), json_length=100000)
glb("bin_chunk_past_end.glb", *square(), bin_length=64)  # 60 bytes of data, padded to 60
with open("truncated.glb", "wb") as f:
    f.write(glb_bytes(*square())[:-10])

# JSON: a missing comma after "scene": 0 on line 3 of the document.
with open("syntax_error.gltf", "w") as f:
    f.write('{\n  "asset": {"version": "2.0"},\n  "scene": 0\n  "scenes": [{"nodes": [0]}]\n}\n')

# Data.
gltf("external_buffer.gltf", *square(uri="square.bin"))
gltf("missing_position.gltf", *square(attribute="NORMAL"))
gltf("accessor_past_end.gltf", *square(count=5))  # 5 positions need 60 bytes; the view has 48
glb("index_out_of_range.glb", *square(indices=[0, 1, 2, 0, 2, 7]))
glb("nan_position.glb", *square(positions=[(0, 0, 0), (1, 0, 0), (1, float("nan"), 0), (0, 1, 0)]))
