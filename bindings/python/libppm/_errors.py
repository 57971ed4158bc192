# SPDX-License-Identifier: Apache-2.0
"""Exceptions raised for the status codes of libppm.

Every failed C call raises the subclass of :class:`Error` for its status, carrying the
library's message (``ppm_last_error_message()``), which names the argument, file, line or
index at fault. The classes also derive from the matching built-in exception where one fits
(``ValueError`` for invalid arguments, ``MemoryError``), so generic handlers catch them too.
"""
from __future__ import annotations

import builtins
import enum
import warnings
from typing import Dict, Optional, Type


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

    status: Optional[Status] = None

    def __init__(self, message: str, status: Optional[int] = None) -> None:
        super().__init__(message)
        self.message: str = message
        if status is not None:
            self.status = Status(status)


class InvalidArgumentError(Error, ValueError):
    """NULL, NaN/Inf, a bad size or an unknown key (``PPM_ERROR_INVALID_ARGUMENT``)."""

    status = Status.INVALID_ARGUMENT


class UnknownKeyError(InvalidArgumentError, TypeError):
    """An unknown setting name, e.g. a mistyped keyword argument: also a ``TypeError``, as
    Python raises for an unexpected keyword. The message lists the known names."""


class InvalidOperationError(Error):
    """A call not allowed in the object's state, e.g. a query before commit."""

    status = Status.INVALID_OPERATION


class ClosedError(InvalidOperationError, ValueError):
    """A method of an object called after its ``close()``."""


class OutOfMemoryError(Error, MemoryError):
    """libppm could not allocate memory (``PPM_ERROR_OUT_OF_MEMORY``)."""

    status = Status.OUT_OF_MEMORY


class FileError(Error, OSError):
    """A file could not be opened, read or written (``PPM_ERROR_IO``)."""

    status = Status.IO


class FileNotFoundError(FileError, builtins.FileNotFoundError):  # noqa: A001 - both meanings hold
    """A file that libppm was asked to read does not exist (``errno.ENOENT``)."""


class ParseError(Error):
    """A file's content is malformed; the message names file and line."""

    status = Status.PARSE


class UnsupportedError(Error):
    """A valid request this libppm cannot serve, e.g. on a CPU without SSE2 (``PPM_ERROR_UNSUPPORTED``)."""

    status = Status.UNSUPPORTED


class CancelledError(Error):
    """The operation was cancelled (``Renderer.cancel()``)."""

    status = Status.CANCELLED


class InternalError(Error):
    """A bug in libppm: please report the message."""

    status = Status.INTERNAL


_BY_STATUS: Dict[Optional[int], Type[Error]] = {
    cls.status: cls
    for cls in (InvalidArgumentError, InvalidOperationError, OutOfMemoryError, FileError,
                ParseError, UnsupportedError, CancelledError, InternalError)
}


def _class_for_status(status: int, message: str = "") -> Type[Error]:
    """The exception class of a C status and message (called by the extension module): the
    status's class, refined where the message says more (a missing file, an unknown key)."""
    if status == Status.IO and ("No such file or directory" in message or ": file not found: " in message):
        return FileNotFoundError
    if status == Status.INVALID_ARGUMENT and message.startswith("unknown "):
        return UnknownKeyError
    return _BY_STATUS.get(status, Error)


class Warning(UserWarning):  # noqa: A001 - libppm.Warning, as libppm.Error
    """What libppm skipped or substituted in an input (a vertex colour, an unsupported
    element read leniently), located as ``file:line:column: what``."""


def _warn(message: str) -> None:
    """Issues a libppm warning (called by the extension module)."""
    warnings.warn(message, Warning, stacklevel=2)
