# SPDX-License-Identifier: Apache-2.0
"""Partial renders of the pass-independent mode ("pppm"): passes rendered anywhere, merged
exactly (``ppm_partial_*``; see ppm.h, "Partial renders")."""
from __future__ import annotations

import os
from typing import List, Mapping, Optional, Tuple

import numpy as np

from . import _core
from ._handle import Handle
from ._typing import ArrayLike, Float32Array, PathLike

_LAYER_CHANNELS = {"radiance": 3, "radius": 1, "photons": 1}


class Partial(Handle):
    """The pass sums of some passes of one render, with that render's identity.

    Partials of the same render (scene, camera, settings) with disjoint passes merge into
    the same bits as one process rendering all of their passes, whatever the split and the
    order: ``a.merge(b)``. Make one with :meth:`Renderer.partial`, :meth:`load` or
    :meth:`from_bytes`; :meth:`to_bytes` and :meth:`save` give the file's bytes.
    """

    _core_object: _core.Partial

    #: Seconds the render took, set by :func:`libppm.distributed.render` on its result.
    elapsed: float

    def __init__(self, core_partial: _core.Partial) -> None:
        """Wraps a ``libppm._core.Partial``; use the constructors named above instead."""
        self._core_object = core_partial

    @classmethod
    def load(cls, path: PathLike) -> "Partial":
        """Reads a ``.ppmpart`` file (ppm-render --partial, :meth:`save`)."""
        return cls(_core.Partial.load(os.fspath(path)))

    @classmethod
    def from_bytes(cls, data: bytes) -> "Partial":
        """A partial from the bytes of :meth:`to_bytes`."""
        return cls(_core.Partial.from_bytes(bytes(data)))

    def to_bytes(self) -> bytes:
        """The partial's file content (versioned, checksummed), e.g. to send it elsewhere."""
        return self._core_object.to_bytes()

    def save(self, path: PathLike) -> None:
        """Writes the partial to ``path`` atomically."""
        self._core_object.save(os.fspath(path))

    def merge(self, other: "Partial") -> "Partial":
        """Adds ``other``'s passes. Raises :class:`libppm.InvalidArgumentError` naming both
        partials for another render's partial or a pass both hold (``self`` is then
        unchanged). Returns ``self``."""
        self._core_object.merge(other._core_object)
        return self

    @property
    def passes(self) -> List[Tuple[int, int]]:
        """The passes held, as sorted half-open ranges ``[(first, end), ...]``."""
        return [(int(first), int(end)) for first, end in self._core_object.passes()]

    @property
    def pass_count(self) -> int:
        """How many passes the partial holds."""
        return self._core_object.get_int("passes")

    @property
    def pass_total(self) -> int:
        """The render's planned pass count (0: not given)."""
        return self._core_object.get_int("pass_total")

    @pass_total.setter
    def pass_total(self, value: int) -> None:
        self._core_object.set_int("pass_total", int(value))

    def missing(self, total: Optional[int] = None) -> List[Tuple[int, int]]:
        """The ranges of ``[0, total)`` not held (``total`` defaults to :attr:`pass_total`)."""
        total = self.pass_total if total is None else int(total)
        gaps: List[Tuple[int, int]] = []
        next_pass = 0
        for first, end in self.passes:
            if first >= total:
                break
            if first > next_pass:
                gaps.append((next_pass, first))
            next_pass = end
        if next_pass < total:
            gaps.append((next_pass, total))
        return gaps

    @property
    def width(self) -> int:
        """Image width in pixels."""
        return self._core_object.get_int("width")

    @property
    def height(self) -> int:
        """Image height in pixels."""
        return self._core_object.get_int("height")

    @property
    def photons_emitted(self) -> int:
        """Photon paths emitted in the passes held."""
        return self._core_object.get_int("photons_emitted")

    def layer(self, name: str = "radiance") -> Float32Array:
        """An image layer of the merged passes: ``"radiance"`` float32 ``(H, W, 3)`` (the mean
        of the passes' estimates), ``"radius"`` ``(H, W)`` (the mean gather radius),
        ``"photons"`` ``(H, W)`` (photons found in all passes)."""
        channels = _LAYER_CHANNELS.get(name, 1)
        shape = (self.height, self.width) + ((channels,) if channels > 1 else ())
        out = np.empty(shape, dtype=np.float32)
        self._core_object.get_layer(name, out)
        return out

    def image(self) -> Float32Array:
        """The radiance layer: float32 ``(H, W, 3)`` linear RGB."""
        return self.layer("radiance")


def write_image(path: PathLike, image: ArrayLike,
                layers: Optional[Mapping[str, ArrayLike]] = None, exposure: float = 0.0) -> None:
    """Writes a float ``(H, W, 3)`` linear-radiance image atomically through libppm's writer
    (the one ppm-render uses): ``.exr`` and ``.hdr`` linear float (EXR also ``layers``, a
    dict of name to ``(H, W)`` arrays), other formats (``.png``, ``.jpg``, ...) 8-bit sRGB of
    the radiance scaled by ``2**exposure``."""
    rgb = np.ascontiguousarray(image, dtype=np.float32)
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise ValueError(f"image: expected shape (H, W, 3), got {rgb.shape}")
    height, width = rgb.shape[:2]
    names: List[str] = []
    arrays: List[Float32Array] = []
    for name, data in (layers or {}).items():
        array = np.ascontiguousarray(data, dtype=np.float32)
        if array.shape != (height, width):
            raise ValueError(f"layer {name!r}: expected shape {(height, width)}, got {array.shape}")
        names.append(str(name))
        arrays.append(array.reshape(-1))
    _core.image_write(os.fspath(path), rgb.reshape(-1), width, height, names, arrays, float(exposure))


def check_image_path(path: PathLike) -> None:
    """Checks that :func:`write_image` could write ``path``, before a long render finds out:
    :class:`libppm.InvalidArgumentError` for a format libppm does not write (by the
    extension), :class:`libppm.FileError` (an ``OSError``) for a folder that does not exist or
    may not be written into."""
    _core.image_check_path(os.fspath(path))
