# SPDX-License-Identifier: Apache-2.0
"""The look-at camera (``ppm_camera``)."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any, FrozenSet, Optional, Sequence, Tuple

from ._arrays import vector

Vec3 = Tuple[float, float, float]

#: A crop window ``(x0, y0, x1, y1)`` in pixels: columns x0 .. x1-1, rows y0 .. y1-1.
Crop = Tuple[int, int, int, int]

# The camera as libppm._core takes and returns it: origin, target, up, fov, width, height,
# aperture_radius, focus_distance, near_clip, crop ((0, 0, 0, 0): none), principal point offset,
# pixel filter (its index in _PIXEL_FILTERS) and its parameter.
_CoreCamera = Tuple[Sequence[float], Sequence[float], Sequence[float], float, int, int, float,
                    float, float, Sequence[int], Sequence[float], int, float]

#: The pixel filters, in the order of ppm.h's PPM_PIXEL_FILTER_* values.
_PIXEL_FILTERS = ("box", "tent", "gaussian")


@dataclass
class Camera:
    """A look-at camera with Mitsuba 3's conventions (``perspective`` / ``thinlens``).

    ``fov`` is the full angle in degrees along the image's x axis; image x grows to the
    right, y down; pixels are square. ``aperture_radius`` 0 is a pinhole; a thin lens
    (> 0) focuses at ``focus_distance`` along the view axis. Rays start ``near_clip``
    along the view axis (0 = at the lens). ``crop`` ``(x0, y0, x1, y1)`` renders only that
    window of the ``width`` x ``height`` image (columns x0 .. x1-1, rows y0 .. y1-1),
    projected as in the whole image: the image rendered is x1 - x0 by y1 - y0 pixels.
    ``principal_point_offset`` ``(x, y)`` (Mitsuba's ``principal_point_offset_x`` / ``_y``)
    is a shifted lens: pixel (px, py) sees what pixel (px + x width, py + y height) of the
    centred camera sees. ``pixel_filter`` is Mitsuba's reconstruction filter, ``"box"`` (the
    pixel), ``"tent"`` or ``"gaussian"`` (Mitsuba's default for its scenes), with
    ``pixel_filter_parameter`` the tent's radius or the gaussian's stddev in pixels (0:
    Mitsuba's defaults, 1 and 0.5).

    The defaults are those of a scene file without a ``sensor`` and of Mitsuba 3: at the
    origin looking along +z with +y up, the 39.6 degree field of view of a 50 mm lens on
    36 mm film, a 768 x 576 film and ``near_clip`` 0.01.
    """

    origin: Vec3 = (0.0, 0.0, 0.0)
    target: Vec3 = (0.0, 0.0, 1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fov: float = 39.597752709049864
    width: int = 768
    height: int = 576
    aperture_radius: float = 0.0
    focus_distance: float = 0.0
    near_clip: float = 0.01
    crop: Optional[Crop] = None
    principal_point_offset: Tuple[float, float] = (0.0, 0.0)
    pixel_filter: str = "box"
    pixel_filter_parameter: float = 0.0

    @staticmethod
    def field_names() -> FrozenSet[str]:
        """The names of the camera's fields."""
        return frozenset(f.name for f in dataclasses.fields(Camera))

    def replace(self, **fields: Any) -> "Camera":
        """A copy with ``fields`` changed."""
        return dataclasses.replace(self, **fields)

    def _as_tuple(self) -> _CoreCamera:
        """The tuple libppm._core takes, checked."""
        size = []
        for name in ("width", "height"):
            value = getattr(self, name)
            if int(value) != value or not 0 <= value <= 0xFFFFFFFF:
                raise ValueError(f"camera {name}: expected a positive integer, got {value!r}")
            size.append(int(value))
        crop = (0, 0, 0, 0)
        if self.crop is not None:
            values = tuple(self.crop)
            if len(values) != 4 or any(int(v) != v or not 0 <= v <= 0xFFFFFFFF for v in values):
                raise ValueError(f"camera crop: expected (x0, y0, x1, y1) in pixels, got {self.crop!r}")
            crop = (int(values[0]), int(values[1]), int(values[2]), int(values[3]))
        offset = tuple(self.principal_point_offset)
        if len(offset) != 2:
            raise ValueError("camera principal_point_offset: expected (x, y), got "
                             f"{self.principal_point_offset!r}")
        if self.pixel_filter not in _PIXEL_FILTERS:
            raise ValueError(f"camera pixel_filter: expected one of {', '.join(_PIXEL_FILTERS)}, "
                             f"got {self.pixel_filter!r}")
        return (vector(self.origin, "camera origin"), vector(self.target, "camera target"),
                vector(self.up, "camera up"), float(self.fov), size[0], size[1],
                float(self.aperture_radius), float(self.focus_distance), float(self.near_clip),
                crop, (float(offset[0]), float(offset[1])), _PIXEL_FILTERS.index(self.pixel_filter),
                float(self.pixel_filter_parameter))

    @classmethod
    def _from_tuple(cls, t: _CoreCamera) -> "Camera":
        """The camera of a tuple from libppm._core."""
        x0, y0, x1, y1 = (int(v) for v in t[9])
        return cls((t[0][0], t[0][1], t[0][2]), (t[1][0], t[1][1], t[1][2]),
                   (t[2][0], t[2][1], t[2][2]), t[3], t[4], t[5], t[6], t[7], t[8],
                   None if (x0, y0, x1, y1) == (0, 0, 0, 0) else (x0, y0, x1, y1),
                   (float(t[10][0]), float(t[10][1])),
                   _PIXEL_FILTERS[int(t[11])] if int(t[11]) < len(_PIXEL_FILTERS) else "box", float(t[12]))
