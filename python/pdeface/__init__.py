"""pdeface: 3D face scans as compact PDE surfaces (.pdef) and back, mesh formats, and honest comparisons.

    >>> import pdeface
    >>> scan = pdeface.read("facefuns_f18.ply")            # any format: VRML, OBJ, PLY, glTF, Draco, ...
    >>> scan.vertices.shape, scan.faces.dtype              # numpy views, no copy
    ((30204, 3), dtype('int32'))
    >>> data = pdeface.encode(scan, ratio=0.10)            # the face as .pdef bytes (~0.9 KB)
    >>> face = pdeface.decode(data, resolution=200)        # its PDE surface, in the scan's frame and units

Errors are :class:`pdeface.Error` subclasses carrying the file and the line or byte the command line
reports; notes (an attribute a format cannot hold) are :class:`pdeface.Note` warnings. Every call that
takes time releases the GIL. The Dask batch: ``python3 -m pdeface.batch FOLDER --out DIR``
(:mod:`pdeface.batch`). docs/python.md has more.
"""

from __future__ import annotations

from typing import Tuple, Union

from ._pdeface import (Alignment, Mesh, ScanReport, __version__, align, compare, compare_file,
                       detect_landmarks, encode, expand_inputs, formats, from_bytes, profiles, read,
                       reconstruct, to_bytes, write, write_report)
from .errors import (Error, FileError, FormatError, InvalidArgumentError, NoFaceError, Note,
                     SelfCheckError, UnsupportedError)

Resolution = Union[None, int, Tuple[int, int]]


def decode(data: bytes, *, resolution: Resolution = None, source: str = "<bytes>.pdef") -> Mesh:
    """A .pdef file's bytes as its PDE surface: a mesh with normals in the scan's frame and units, at
    ``resolution`` (None: about 1 mm between vertices; V points along the face; or (U, V)) — what
    ``pdeface decode`` writes."""
    return from_bytes(data, source, format="pdef", resolution=resolution)


__all__ = [
    "Alignment", "Error", "FileError", "FormatError", "InvalidArgumentError", "Mesh", "NoFaceError", "Note",
    "ScanReport", "SelfCheckError", "UnsupportedError", "__version__", "align", "compare", "compare_file",
    "decode", "detect_landmarks", "encode", "expand_inputs", "formats", "from_bytes", "profiles", "read",
    "reconstruct", "to_bytes", "write", "write_report",
]
