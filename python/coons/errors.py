# SPDX-License-Identifier: GPL-3.0-or-later
"""The exceptions of the package: one per libcoons status (coons/types.h),
each carrying the library's message and status code."""


class Error(Exception):
    """A libcoons call failed; ``message`` is the library's text, ``code``
    its status (a negative ``COONS_E_*``; 0 for errors found in Python)."""

    def __init__(self, message, code=0):
        super().__init__(message)
        self.message = message
        self.code = code


class InvalidError(Error, ValueError):
    """An argument or model value is invalid (COONS_E_INVALID), also wrong
    array shapes, dtypes and non-finite numbers found before the call."""


class DomainError(Error, ValueError):
    """A parameter lies outside its domain (COONS_E_DOMAIN), e.g. u not in [0, 1]."""


class FileError(Error, OSError):
    """Reading or writing a file failed (COONS_E_IO)."""


class LimitError(Error):
    """A size limit was exceeded (COONS_E_LIMIT); the message names it."""


class GeometryError(Error):
    """A repair or Boolean operation failed (COONS_E_CSG), curves or patches
    that must meet do not (COONS_E_INCOMPATIBLE), or a volume mesh has
    inverted cells."""


class UnsupportedError(Error):
    """The feature is not built into this libcoons (COONS_E_UNSUPPORTED);
    :func:`coons.features` says which parts are."""


class ClosedError(Error, ValueError):
    """The object, or the model it belongs to, was closed."""


class LoadError(Error):
    """A model could not be loaded: ``file``, ``line``, ``column`` (1-based,
    0 when the error concerns the file as a whole) and ``path`` (a JSON
    pointer) locate the offending value."""

    def __init__(self, message, code=0, file="", line=0, column=0, path=""):
        super().__init__(message, code)
        self.file = file
        self.line = line
        self.column = column
        self.path = path


class LoadLimitError(LoadError, LimitError):
    """A loader limit was exceeded (the model is too big for the limits)."""


class LoadGeometryError(LoadError, GeometryError):
    """The model's curves or faces that must meet do not."""


_BY_CODE = {-2: InvalidError, -3: DomainError, -4: FileError, -5: InvalidError,
            -6: GeometryError, -8: LimitError, -9: UnsupportedError, -10: GeometryError}
_LOAD_BY_CODE = {-8: LoadLimitError, -10: LoadGeometryError}


def from_status(code, message):
    if code == -1:
        return MemoryError(message)
    return _BY_CODE.get(code, Error)(message, code)


def load_error(code, message, file, line, column, path):
    if code == -1:
        return MemoryError(message)
    return _LOAD_BY_CODE.get(code, LoadError)(message, code, file, line, column, path)
