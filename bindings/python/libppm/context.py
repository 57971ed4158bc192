# SPDX-License-Identifier: Apache-2.0
"""The root object: worker threads, Embree device."""
from __future__ import annotations

import numbers
from typing import Optional, Union

from . import _core
from ._handle import Handle

_default: Optional["Context"] = None


class Context(Handle):
    """A libppm context: owns the Embree device and the worker threads.

    Optional: scenes created without one share :func:`default_context`.

    >>> ctx = libppm.Context(threads=2)
    >>> scene = libppm.Scene(ctx)

    ``threads``: worker threads for batch queries, scene builds and rendering; 0 (default)
    means all hardware threads.
    """

    _core_object: _core.Context

    def __init__(self, threads: Optional[int] = None) -> None:
        self._core_object = _core.Context()
        if threads is not None:
            self.threads = threads

    @property
    def threads(self) -> int:
        """Worker threads (0 = all hardware threads); applies to calls that start later."""
        return self._core_object.get_int("threads")

    @threads.setter
    def threads(self, value: int) -> None:
        self._core_object.set_int("threads", int(value))

    def set(self, key: str, value: Union[int, float]) -> None:
        """Sets a setting by name: an int goes to ``ppm_context_set_int``, a float to
        ``ppm_context_set_double`` (a whole float for the integer ``threads``)."""
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"context setting {key!r}: expected int or float, got {type(value).__name__}")
        if isinstance(value, numbers.Integral):
            self._core_object.set_int(key, int(value))
        else:
            self._core_object.set_double(key, float(value))

    def get(self, key: str) -> int:
        """An integer setting by name (``threads``)."""
        return self._core_object.get_int(key)


def default_context() -> Context:
    """The context shared by scenes created without one (made on first use)."""
    global _default
    if _default is None or _default.closed:
        _default = Context()
    return _default


def resolve(context: Optional[Context]) -> Context:
    """`context` if given, else the default one."""
    if context is None:
        return default_context()
    if not isinstance(context, Context):
        raise TypeError(f"context: expected libppm.Context, got {type(context).__name__}")
    return context
