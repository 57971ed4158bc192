# SPDX-License-Identifier: Apache-2.0
"""Rays and hits as numpy structured arrays laid out exactly as ppm_ray and ppm_hit."""
from __future__ import annotations

from typing import Any, Tuple, cast

import numpy as np
import numpy.typing as npt

from . import _core
from ._arrays import batch_array
from ._typing import ArrayLike, BoolArray, Float64Array, UInt32Array

# numpy's stubs type a dtype's dict argument as a TypedDict, which a plain dict is not.
RAY_DTYPE: np.dtype[np.void] = np.dtype(cast(Any, _core.ray_layout()))
HIT_DTYPE: np.dtype[np.void] = np.dtype(cast(Any, _core.hit_layout()))


def make_rays(origins: ArrayLike, directions: ArrayLike, tnear: ArrayLike,
              tfar: ArrayLike) -> Tuple[npt.NDArray[np.void], Tuple[int, ...]]:
    """A 1-D ppm_ray array of the broadcast rays, and the batch shape."""
    org = batch_array(origins, "origins", (3,))
    dirs = batch_array(directions, "directions", (3,))
    near = batch_array(tnear, "tnear")
    far = batch_array(tfar, "tfar")
    try:
        shape = np.broadcast_shapes(org.shape[:-1], dirs.shape[:-1], near.shape, far.shape)
    except ValueError:
        raise ValueError(
            f"origins {org.shape}, directions {dirs.shape}, tnear {near.shape} and tfar "
            f"{far.shape} do not broadcast to one batch of rays") from None
    rays = np.empty(int(np.prod(shape, dtype=np.int64)), dtype=RAY_DTYPE)
    rays["org"] = np.broadcast_to(org, shape + (3,)).reshape(-1, 3)
    rays["dir"] = np.broadcast_to(dirs, shape + (3,)).reshape(-1, 3)
    rays["tnear"] = np.broadcast_to(near, shape).reshape(-1)
    rays["tfar"] = np.broadcast_to(far, shape).reshape(-1)
    return rays, shape


class Hits:
    """Closest hits of a batch of rays; every array has the batch shape (plus 3 for vectors).

    ``t`` (inf on a miss), ``u``, ``v`` (surface parameters, see each ``add_*``), ``p``
    (hit point on the surface), ``p_error`` (bound on its distance from the exact point),
    ``ng`` (unit geometric normal as stored, not flipped towards the ray), ``ns`` (unit
    shading normal), ``geom_id``, ``prim_id``, ``material`` (uint32; ``geom_id`` and
    ``prim_id`` are :data:`libppm.INVALID_ID` = 0xFFFFFFFF on a miss, ``material`` 0),
    ``hit`` (bool mask).
    ``raw`` is the underlying ppm_hit structured array (1-D).
    """

    raw: npt.NDArray[np.void]
    shape: Tuple[int, ...]
    t: Float64Array
    u: Float64Array
    v: Float64Array
    p: Float64Array
    p_error: Float64Array
    ng: Float64Array
    ns: Float64Array
    geom_id: UInt32Array
    prim_id: UInt32Array
    material: UInt32Array
    hit: BoolArray

    def __init__(self, raw: npt.NDArray[np.void], shape: Tuple[int, ...]) -> None:
        """Wraps ``raw``, a 1-D :data:`libppm.HIT_DTYPE` array, as hits of batch ``shape``
        (done by :meth:`libppm.Scene.intersect`)."""
        self.raw = raw
        self.shape = tuple(shape)
        for name in ("t", "u", "v", "p_error", "geom_id", "prim_id", "material"):
            setattr(self, name, np.array(raw[name], order="C").reshape(self.shape))
        for name in ("p", "ng", "ns"):
            setattr(self, name, np.array(raw[name], order="C").reshape(self.shape + (3,)))
        self.hit = np.isfinite(self.t)
        # The C API leaves prim_id 0 on a miss; marking it like geom_id spares callers a
        # special case.
        self.prim_id[~self.hit] = _core.INVALID_ID

    def __len__(self) -> int:
        return self.shape[0] if self.shape else 1

    def __repr__(self) -> str:
        return f"<libppm.Hits shape={self.shape} hits={int(self.hit.sum())}>"
