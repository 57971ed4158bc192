# SPDX-License-Identifier: Apache-2.0
"""Conversion of user input to the arrays the C API reads, with errors naming the argument.

Anything numpy converts to real numbers is accepted (lists, integer arrays, float32 ...) and
converted to C-contiguous float64; complex, string and object input is a TypeError, a wrong
shape a ValueError. Values are not checked here: NaN and infinities go to libppm, which
rejects them with an InvalidArgumentError naming the element.
"""
from __future__ import annotations

from typing import Any, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

from ._typing import ArrayLike, ColorLike, Float64Array, UInt32Array

Shape = Sequence[Optional[int]]

_REAL_KINDS = "biuf"


def _describe(shape: Shape) -> str:
    return "(" + ", ".join("n" if d is None else str(d) for d in shape) + ")"


def _convert(value: ArrayLike, name: str, dtype: npt.DTypeLike) -> npt.NDArray[Any]:
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:  # ragged nested lists, for one
        raise TypeError(f"{name}: expected an array of numbers ({e})") from None
    if array.dtype.kind not in _REAL_KINDS:
        raise TypeError(f"{name}: expected real numbers, got an array of dtype {array.dtype}")
    # Not ascontiguousarray: that turns a 0-d array (a scalar tnear) into shape (1,).
    return np.asarray(array, dtype=dtype, order="C")


def real_array(value: ArrayLike, name: str, *shapes: Shape) -> Float64Array:
    """`value` as a C-contiguous float64 array of one of `shapes` (None = any length)."""
    array = _convert(value, name, np.float64)
    for shape in shapes:
        if array.ndim == len(shape) and all(
                want is None or want == got for want, got in zip(shape, array.shape)):
            return array
    expected = " or ".join(_describe(s) for s in shapes)
    raise ValueError(f"{name}: expected shape {expected}, got {array.shape}")


def vector(value: ArrayLike, name: str, size: int = 3) -> Tuple[float, ...]:
    """A tuple of `size` floats."""
    return tuple(float(x) for x in real_array(value, name, (size,)))


def color(value: ColorLike, name: str) -> Tuple[float, ...]:
    """An RGB triple; a single number means grey."""
    array = _convert(value, name, np.float64)
    if array.ndim == 0:
        array = np.repeat(array, 3)
    if array.shape != (3,):
        raise ValueError(f"{name}: expected a number or shape (3,), got {array.shape}")
    return tuple(float(x) for x in array)


def index_array(value: ArrayLike, name: str, shape: Shape) -> UInt32Array:
    """A C-contiguous uint32 array of `shape` from integer input (no floats: no rounding)."""
    try:
        array = np.asarray(value)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{name}: expected an array of integers ({e})") from None
    if array.size == 0 and array.dtype.kind == "f":
        array = array.astype(np.int64)  # np.asarray([]) is float64
    if array.dtype.kind not in "iu":
        raise TypeError(f"{name}: expected integers, got an array of dtype {array.dtype}")
    if array.ndim != len(shape) or any(w is not None and w != g for w, g in zip(shape, array.shape)):
        raise ValueError(f"{name}: expected shape {_describe(shape)}, got {array.shape}")
    if array.size and (array.min() < 0 or array.max() > 0xFFFFFFFF):
        raise ValueError(f"{name}: indices must lie in 0 .. 2^32 - 1")
    return np.ascontiguousarray(array, dtype=np.uint32)


def uint32(value: Any, name: str) -> int:
    """A non-negative integer that fits a uint32 (geometry and material ids)."""
    try:
        number = int(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name}: expected an integer, got {value!r}") from None
    if number != value or not 0 <= number <= 0xFFFFFFFF:
        raise ValueError(f"{name}: expected an integer in 0 .. 2^32 - 1, got {value!r}")
    return number


def batch_array(value: ArrayLike, name: str, trailing: Tuple[int, ...] = ()) -> Float64Array:
    """`value` as a float64 array of shape (..., *trailing): any batch shape in front."""
    array = _convert(value, name, np.float64)
    k = len(trailing)
    if array.ndim < k or tuple(array.shape[array.ndim - k:]) != tuple(trailing):
        expected = "(" + ", ".join(["..."] + [str(d) for d in trailing]) + ")"
        raise ValueError(f"{name}: expected shape {expected}, got {array.shape}")
    return array
