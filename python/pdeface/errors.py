"""Errors and notes of pdeface.

Every error a file or a scan causes is a :class:`Error` with the code, the message, the source and the
place (line and column of a text file, byte offset of a binary one) the command line reports, and
``str(error)`` is the command line's message (``"face.wrl:12:5: malformed: expected '}'"``). The
subclass says what kind of problem it is; a wrong *call* (an option out of range) is a ``ValueError``.
"""

from __future__ import annotations


class Error(Exception):
    """Bad data: a file that cannot be read or written, a scan without a face, a result that fails its
    self-check."""

    code: str  #: "malformed", "truncated", "no face", "self-check failed", ... (stable)
    message: str  #: what is wrong, without the source
    source: str  #: the file (or the name given to bytes in memory)
    line: int | None  #: 1-based line of a text file
    column: int | None  #: 1-based column
    byte: int | None  #: byte offset in a binary file

    def __init__(self, text: str, code: str = "", message: str = "", source: str = "",
                 line: int | None = None, column: int | None = None, byte: int | None = None) -> None:
        super().__init__(text)
        self.code = code
        self.message = message or text
        self.source = source
        self.line = line
        self.column = column
        self.byte = byte

    def __reduce__(self):  # picklable, so that an error crosses Dask workers intact
        return (type(self), (str(self), self.code, self.message, self.source, self.line, self.column, self.byte))


class FileError(Error, OSError):
    """A file cannot be opened, read or written."""


class FormatError(Error):
    """The bytes are not a valid file of their format: malformed, truncated, out of range, damaged."""


class UnsupportedError(FormatError):
    """A format or a version of one that pdeface does not read or write."""


class NoFaceError(Error):
    """No face can be found in the scan (or too little of it to slice)."""


class SelfCheckError(Error):
    """A result measured against its scan is off: refused rather than returned (``force=True`` returns
    it anyway)."""


class InvalidArgumentError(Error, ValueError):
    """A value in the data or a request outside what the method accepts."""


class Note(UserWarning):
    """Something that did not stop the work, e.g. an attribute the output format cannot hold."""


_CLASSES = {
    "i/o error": FileError,
    "empty": FormatError,
    "truncated": FormatError,
    "malformed": FormatError,
    "bad magic": FormatError,
    "unsupported version": UnsupportedError,
    "unsupported format": UnsupportedError,
    "index out of range": FormatError,
    "non-finite value": FormatError,
    "count too large": FormatError,
    "undefined name": FormatError,
    "invalid argument": InvalidArgumentError,
    "no face": NoFaceError,
    "checksum mismatch": FormatError,
    "self-check failed": SelfCheckError,
}


def _from_code(code: str, message: str, source: str, line, column, byte, text: str) -> Error:
    """The exception for a C++ ``pdeface::Error`` (called by the extension)."""
    return _CLASSES.get(code, Error)(text, code, message, source, line, column, byte)
