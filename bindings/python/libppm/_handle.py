# SPDX-License-Identifier: Apache-2.0
"""What every handle class shares: close(), the context manager, the closed check."""
from __future__ import annotations

from typing import Optional, Protocol, TypeVar

_H = TypeVar("_H", bound="Handle")


class _CoreHandle(Protocol):
    """What Handle needs of a libppm._core object."""

    def close(self) -> None: ...

    @property
    def closed(self) -> bool: ...


class Handle:
    """Base of the classes that own a libppm handle.

    ``close()`` drops this object's reference at once (also done when it is garbage
    collected); calling a method afterwards raises :class:`libppm.ClosedError`. Children keep
    what they need alive: a renderer works on after its scene and context are closed.
    """

    _core_object: Optional[_CoreHandle] = None

    def close(self) -> None:
        """Releases the handle; further calls raise :class:`libppm.ClosedError`. Idempotent."""
        if self._core_object is not None:
            self._core_object.close()

    @property
    def closed(self) -> bool:
        """True after :meth:`close`."""
        return self._core_object is None or self._core_object.closed

    def __enter__(self: _H) -> _H:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    def __repr__(self) -> str:
        state = "closed" if self.closed else "open"
        return f"<libppm.{type(self).__name__} ({state})>"
