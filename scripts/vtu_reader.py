"""Reads the VTU series that Signorini writes (deal.II's binary VTU:
base64, zlib-compressed blocks or raw) without VTK, for the tests and
the figures.

read_series(directory, stem): the last step of STEM.pvd as a list of
pieces, one per rank; each piece a dict with "points" (list of (x, y, z)),
"cells" (list of node index lists) and "point_data" / "cell_data"
({name: list of values, a tuple per point for vector fields}).
"""
import base64
import math
import os
import struct
import xml.etree.ElementTree as ET
import zlib

_TYPES = {"Float32": "f", "Float64": "d", "Int32": "i", "Int64": "q",
          "UInt8": "B", "UInt32": "I", "UInt64": "Q"}


def _decode(array, header_type, compressed):
    """The values of one DataArray."""
    kind = _TYPES[array.get("type")]
    text = "".join((array.text or "").split())
    if array.get("format") != "binary":
        return [float(v) for v in text.split()]
    head = _TYPES[header_type]
    size = struct.calcsize(head)
    if not compressed:
        raw = base64.b64decode(text)
        n = struct.unpack("<" + head, raw[:size])[0]
        data = raw[size:size + n]
    else:
        # Header (encoded apart from the data): the number of blocks, the
        # block size, the last block's size, then each block's compressed
        # size. Its first three numbers: 3 * size bytes, 4 * size characters.
        n_blocks = struct.unpack("<" + head, base64.b64decode(text[:4 * size])[:size])[0]
        header_bytes = (3 + n_blocks) * size
        header_chars = 4 * math.ceil(header_bytes / 3)
        header = struct.unpack("<%d%s" % (3 + n_blocks, head),
                               base64.b64decode(text[:header_chars])[:header_bytes])
        raw = base64.b64decode(text[header_chars:])
        data, offset = b"", 0
        for b in range(n_blocks):
            data += zlib.decompress(raw[offset:offset + header[3 + b]])
            offset += header[3 + b]
    count = len(data) // struct.calcsize(kind)
    return list(struct.unpack("<%d%s" % (count, kind), data))


def _grouped(values, components):
    if components == 1:
        return values
    return [tuple(values[components * i:components * (i + 1)])
            for i in range(len(values) // components)]


def read_piece(path):
    """One .vtu file (see the module's documentation)."""
    root = ET.parse(path).getroot()
    header_type = root.get("header_type", "UInt32")
    compressed = root.get("compressor") is not None
    piece = root.find("UnstructuredGrid/Piece")

    def arrays(section):
        node = piece.find(section)
        result = {}
        for array in ([] if node is None else node.findall("DataArray")):
            result[array.get("Name")] = _grouped(
                _decode(array, header_type, compressed),
                int(array.get("NumberOfComponents", "1")))
        return result

    points = arrays("Points")
    cells = arrays("Cells")
    connectivity = [int(i) for i in cells.get("connectivity", [])]
    offsets = [int(i) for i in cells.get("offsets", [])]
    return {"points": next(iter(points.values()), []),
            "cells": [connectivity[a:b] for a, b in zip([0] + offsets, offsets)],
            "point_data": arrays("PointData"),
            "cell_data": arrays("CellData")}


def read_series(directory, stem):
    """The pieces of the last step of STEM.pvd and the .pvtu's name."""
    pvd = ET.parse(os.path.join(directory, stem + ".pvd")).getroot()
    pvtu_name = list(pvd.iter("DataSet"))[-1].get("file")
    pvtu = ET.parse(os.path.join(directory, pvtu_name)).getroot()
    return ([read_piece(os.path.join(directory, p.get("Source")))
             for p in pvtu.iter("Piece")], pvtu_name)
