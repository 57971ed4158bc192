# SPDX-License-Identifier: Apache-2.0
"""Type aliases of the package's annotations (for type checkers and help(); no behaviour)."""
from __future__ import annotations

import os
from typing import Union

import numpy as np
import numpy.typing as npt

#: A file path: a str or an ``os.PathLike`` such as ``pathlib.Path``.
PathLike = Union[str, "os.PathLike[str]"]

#: Anything numpy converts to an array of real numbers (a list, a tuple, an array, ...).
ArrayLike = npt.ArrayLike

#: An RGB value: a number (grey) or three numbers.
ColorLike = npt.ArrayLike

#: A float64 numpy array (positions, hit distances, control points).
Float64Array = npt.NDArray[np.float64]

#: A float32 numpy array (images and their layers).
Float32Array = npt.NDArray[np.float32]

#: A uint32 numpy array (ids, triangle indices).
UInt32Array = npt.NDArray[np.uint32]

#: A bool numpy array (hit masks, occlusion).
BoolArray = npt.NDArray[np.bool_]
