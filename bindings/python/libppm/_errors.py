"""Exceptions raised for the status codes of libppm.

Every failed C call raises the subclass of :class:`Error` for its status, carrying the
library's message (``ppm_last_error_message()``), which names the argument, file, line or
index at fault. The classes also derive from the matching built-in exception where one fits
(``ValueError`` for invalid arguments, ``MemoryError``), so generic handlers catch them too.
"""
import enum


class Status(enum.IntEnum):
    """``ppm_status`` codes (values fixed by the C ABI)."""

    OK = 0
    INVALID_ARGUMENT = 1
    INVALID_OPERATION = 2
    OUT_OF_MEMORY = 3
    IO = 4
    PARSE = 5
    UNSUPPORTED = 6
    CANCELLED = 7
    INTERNAL = 8


class Error(Exception):
    """A libppm call failed. ``status`` is its :class:`Status`, ``message`` the C message."""

    status = None

    def __init__(self, message, status=None):
        super().__init__(message)
        self.message = message
        if status is not None:
            self.status = Status(status)


class InvalidArgumentError(Error, ValueError):
    """NULL, NaN/Inf, a bad size or an unknown key (``PPM_ERROR_INVALID_ARGUMENT``)."""

    status = Status.INVALID_ARGUMENT


class InvalidOperationError(Error):
    """A call not allowed in the object's state, e.g. a query before commit."""

    status = Status.INVALID_OPERATION


class ClosedError(InvalidOperationError, ValueError):
    """A method of an object called after its ``close()``."""


class OutOfMemoryError(Error, MemoryError):
    status = Status.OUT_OF_MEMORY


class FileError(Error, OSError):
    """A file could not be opened, read or written (``PPM_ERROR_IO``)."""

    status = Status.IO


class ParseError(Error):
    """A file's content is malformed; the message names file and line."""

    status = Status.PARSE


class UnsupportedError(Error):
    status = Status.UNSUPPORTED


class CancelledError(Error):
    """The operation was cancelled (``Renderer.cancel()``)."""

    status = Status.CANCELLED


class InternalError(Error):
    """A bug in libppm: please report the message."""

    status = Status.INTERNAL


_BY_STATUS = {
    cls.status: cls
    for cls in (InvalidArgumentError, InvalidOperationError, OutOfMemoryError, FileError,
                ParseError, UnsupportedError, CancelledError, InternalError)
}


def _class_for_status(status):
    """The exception class of a C status (called by the extension module)."""
    return _BY_STATUS.get(status, Error)
