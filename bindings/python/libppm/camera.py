"""The look-at camera (``ppm_camera``)."""
from dataclasses import dataclass
from typing import Tuple

from ._arrays import vector

Vec3 = Tuple[float, float, float]


@dataclass
class Camera:
    """A look-at camera with Mitsuba 3's conventions (``perspective`` / ``thinlens``).

    ``fov`` is the full angle in degrees along the image's x axis; image x grows to the
    right, y down; pixels are square. ``aperture_radius`` 0 is a pinhole; a thin lens
    (> 0) focuses at ``focus_distance`` along the view axis. Rays start ``near_clip``
    along the view axis (0 = at the lens).
    """

    origin: Vec3 = (0.0, 0.0, 0.0)
    target: Vec3 = (0.0, 0.0, -1.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fov: float = 45.0
    width: int = 256
    height: int = 256
    aperture_radius: float = 0.0
    focus_distance: float = 0.0
    near_clip: float = 0.0

    def _as_tuple(self):
        """The tuple libppm._core takes, checked."""
        size = []
        for name in ("width", "height"):
            value = getattr(self, name)
            if int(value) != value or not 0 <= value <= 0xFFFFFFFF:
                raise ValueError(f"camera {name}: expected a positive integer, got {value!r}")
            size.append(int(value))
        return (vector(self.origin, "camera origin"), vector(self.target, "camera target"),
                vector(self.up, "camera up"), float(self.fov), size[0], size[1],
                float(self.aperture_radius), float(self.focus_distance), float(self.near_clip))

    @classmethod
    def _from_tuple(cls, t):
        return cls(tuple(t[0]), tuple(t[1]), tuple(t[2]), *t[3:])
