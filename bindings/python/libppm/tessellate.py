# SPDX-License-Identifier: Apache-2.0
"""Triangle meshes from Bezier patches (``ppm_tessellate_patches``)."""
from __future__ import annotations

from typing import NamedTuple, Optional

import numpy as np

from . import _core
from ._arrays import real_array
from ._typing import ArrayLike, Float64Array, UInt32Array


class Mesh(NamedTuple):
    """A tessellation. The arrays are read-only views of libppm's mesh (copy to modify).

    ``vertices`` ``(V, 3)`` float64, on the surface; ``normals`` ``(V, 3)`` unit geometric
    normals; ``uvs`` ``(V, 2)`` each vertex's (u, v) in its patch; ``triangles`` ``(T, 3)``
    uint32, counter-clockwise in (u, v); ``triangle_patches`` ``(T,)`` the patch each
    triangle approximates; ``welded_ids`` ``(V,)`` one index per distinct position
    (``triangles`` mapped through it give the crack-free welded mesh), ``welded_count``
    their number; ``max_deviation`` the largest measured distance from a triangle to the
    surface; ``tolerance`` the requested one (0 for a uniform grid).
    """

    vertices: Float64Array
    normals: Float64Array
    uvs: Float64Array
    triangles: UInt32Array
    triangle_patches: UInt32Array
    welded_ids: UInt32Array
    welded_count: int
    max_deviation: float
    tolerance: float


def tessellate(control_points: ArrayLike, tolerance: Optional[float] = None,
               grid: Optional[int] = None) -> Mesh:
    """Tessellates bicubic Bezier patches into triangles; returns a :class:`Mesh`.

    ``control_points``: shape ``(n, 16, 3)`` or ``(n, 4, 4, 3)``, laid out as for
    :meth:`Scene.add_bezier_patches`. Give exactly one of

    - ``tolerance`` (absolute, > 0): adaptive; every point of every triangle lies within it
      of the surface as measured, crack-free across shared patch edges;
    - ``grid`` (1 .. 4096): uniform, ``grid x grid`` quads per patch, two triangles each.

    Runs without the GIL; large requests use all hardware threads.
    """
    if (tolerance is None) == (grid is None):
        raise TypeError("tessellate: give exactly one of tolerance (adaptive) or grid (uniform)")
    points = real_array(control_points, "control_points", (None, 16, 3), (None, 4, 4, 3))
    if grid is not None:
        if int(grid) != grid or grid <= 0:
            raise ValueError(f"grid: expected a positive integer, got {grid!r}")
        grid, tolerance = int(grid), 0.0
        if grid > 0xFFFFFFFF:
            raise ValueError(f"grid: {grid} is too large (at most 4096)")
    else:
        assert tolerance is not None  # exactly one of the two was given
        grid, tolerance = 0, float(tolerance)
    mesh = _core.tessellate(points, tolerance, grid)
    try:
        arrays = mesh.arrays()
        return Mesh(max_deviation=mesh.get_double("max_deviation"),
                    tolerance=mesh.get_double("tolerance"), **arrays)
    finally:
        # The arrays hold their own references to libppm's mesh.
        mesh.close()
