# SPDX-License-Identifier: Apache-2.0
"""The renderer (``ppm_renderer_*``): photon mapping and vertex connection and merging."""
from __future__ import annotations

import dataclasses
import numbers
import os
import time
from typing import TYPE_CHECKING, Any, Callable, Dict, Optional, Union

import numpy as np

from . import _core
from ._errors import CancelledError, InvalidArgumentError, UnknownKeyError
from ._handle import Handle
from ._typing import Float32Array, PathLike
from .camera import Camera

if TYPE_CHECKING:
    from .partial import Partial
    from .scene import Scene

#: A render setting's value: ``str``, ``int`` (and ``bool``) or ``float``.
SettingValue = Union[str, int, float]

#: ``progress(pass_index, stats)`` of :meth:`Renderer.render`; returning ``False`` stops.
ProgressCallback = Callable[[int, Dict[str, float]], Optional[bool]]

_LAYER_CHANNELS = {"radiance": 3, "radius": 1, "photons": 1}
_CAMERA_FIELDS = {f.name for f in dataclasses.fields(Camera)}


class Renderer(Handle):
    """A renderer of a committed scene seen through a camera, in one of the modes of ppm.h.

    >>> r = libppm.Renderer(scene, libppm.Camera(origin=(0, -5, 1), target=(0, 0, 1),
    ...                  up=(0, 0, 1), fov=40, width=320, height=240), photons_per_pass=100000)
    >>> rgb = r.render(16)                 # (240, 320, 3) float32, linear radiance

    The camera may also be given as keyword arguments (the fields of :class:`Camera`),
    alone or overriding fields of ``camera``:
    ``libppm.Renderer(scene, origin=(0, -5, 1), target=(0, 0, 1), up=(0, 0, 1), width=64,
    height=48, seed=3)``.

    Settings (keyword arguments here, or :meth:`set` / :meth:`get`; see ppm.h):
    ``mode`` ("vcm", the default, | "sppm" | "ppm" | "pppm" | "bpt" | "vm"; all but sppm and ppm
    are pass-independent, see :class:`libppm.Partial`),
    ``photons_per_pass``, ``alpha``, ``initial_radius``,
    ``initial_radius_pixels``, ``max_depth``, ``seed``, ``hit_point_search``
    ("grid" | "kdtree"), ``direct_lighting`` (1: shadow rays, 0: photons only),
    ``glossy_gather_alpha``. mode, seed, direct_lighting, glossy_gather_alpha and the initial
    radius are fixed after the first pass.

    The scene's lights, materials and textures are read at creation; later scene changes
    do not reach the renderer. It keeps the scene alive (``renderer.scene``).
    """

    _core_object: _core.Renderer

    def __init__(self, scene: Scene, camera: Optional[Camera] = None,
                 **settings: Any) -> None:
        camera_fields = {k: settings.pop(k) for k in list(settings) if k in _CAMERA_FIELDS}
        if camera is None:
            camera = Camera(**camera_fields)
        elif not isinstance(camera, Camera):
            raise TypeError(f"camera: expected libppm.Camera, got {type(camera).__name__}")
        elif camera_fields:
            camera = dataclasses.replace(camera, **camera_fields)
        self.scene = scene
        self.camera = camera
        self._core_object = _core.Renderer(scene._core_object, camera._as_tuple())
        self.set(**settings)

    @classmethod
    def _adopt(cls, core_renderer: _core.Renderer, scene: Scene, camera: Camera) -> "Renderer":
        """A Renderer owning ``core_renderer`` (of a scene file), without a new handle."""
        renderer = cls.__new__(cls)
        renderer.scene = scene
        renderer.camera = camera
        renderer._core_object = core_renderer
        return renderer

    # -- settings -------------------------------------------------------------------------
    def set(self, key: Optional[str] = None, value: Optional[SettingValue] = None,
            **settings: SettingValue) -> None:
        """Sets settings: ``set("alpha", 0.7)`` or ``set(alpha=0.7, seed=3)``.

        Python str, int (and bool) and float values go to the string, integer and double
        setters of the C API; whole floats are accepted for integer settings.
        """
        if key is not None:
            if value is None:
                raise TypeError(f"set({key!r}): the value is missing")
            settings = {key: value, **settings}
        for name, v in settings.items():
            if isinstance(v, str):
                self._core_object.set_string(name, v)
            elif isinstance(v, numbers.Integral):
                self._core_object.set_int(name, int(v))
            elif isinstance(v, numbers.Real):
                self._core_object.set_double(name, float(v))
            else:
                raise TypeError(f"render setting {name!r}: expected str, int or float, "
                                f"got {type(v).__name__}")

    def get(self, key: str) -> SettingValue:
        """A setting or read-only value by name (int, float or str, as the C API has it):
        the settings above and ``passes``, ``photons_emitted``, ``width``, ``height``,
        ``last_eye_pass_seconds``, ``last_photon_pass_seconds``,
        ``last_search_build_seconds``."""
        # The C API has one getter per type and no "type of key" query: try each in turn.
        getters = (self._core_object.get_int, self._core_object.get_double,
                   self._core_object.get_string)
        for getter in getters:
            try:
                return getter(key)
            except InvalidArgumentError as e:
                last = e
        raise UnknownKeyError(f"unknown render setting {key!r} ({last.message})")

    @property
    def passes(self) -> int:
        """Completed passes."""
        return self._core_object.get_int("passes")

    @property
    def photons_emitted(self) -> int:
        """Photon paths emitted so far (all of them, also those that left the scene)."""
        return self._core_object.get_int("photons_emitted")

    @property
    def width(self) -> int:
        """Image width in pixels (of the camera)."""
        return self._core_object.get_int("width")

    @property
    def height(self) -> int:
        """Image height in pixels (of the camera)."""
        return self._core_object.get_int("height")

    # -- rendering ------------------------------------------------------------------------
    def render_pass(self) -> None:
        """Runs one pass without the GIL (``ppm_renderer_render_pass``).

        Raises :class:`libppm.CancelledError` if :meth:`cancel` was called before or during
        it (the pass is then discarded).
        """
        self._core_object.render_pass()

    def render(self, passes: int = 1, progress: Optional[ProgressCallback] = None,
               time_limit: Optional[float] = None) -> Float32Array:
        """Runs up to ``passes`` passes and returns :meth:`image`.

        ``progress(pass_index, stats)`` is called after each pass with the 0-based index
        of the pass within this call and a dict (``passes``, ``photons_emitted``,
        ``elapsed`` seconds since the call started, ``last_eye_pass_seconds`` and the
        ``last_search_build_seconds`` within it, ``last_photon_pass_seconds``); returning
        ``False`` (not None) stops early.
        ``time_limit`` (seconds) stops after the pass that crosses it. A :meth:`cancel`
        from another thread stops too: the image is then that of the last whole pass.
        """
        start = time.perf_counter()
        for index in range(int(passes)):
            try:
                self.render_pass()
            except CancelledError:
                break
            elapsed = time.perf_counter() - start
            if progress is not None and progress(index, self.stats(elapsed)) is False:
                break
            if time_limit is not None and elapsed >= time_limit:
                break
        return self.image()

    def stats(self, elapsed: Optional[float] = None) -> Dict[str, float]:
        """Progress figures: passes, photons emitted, last pass timings (a dict)."""
        core = self._core_object
        stats: Dict[str, float] = {
            "passes": core.get_int("passes"),
            "photons_emitted": core.get_int("photons_emitted"),
            "last_eye_pass_seconds": core.get_double("last_eye_pass_seconds"),
            "last_photon_pass_seconds": core.get_double("last_photon_pass_seconds"),
            "last_search_build_seconds": core.get_double("last_search_build_seconds"),
        }
        if elapsed is not None:
            stats["elapsed"] = elapsed
        return stats

    def render_pass_index(self, index: int) -> None:
        """Runs pass ``index`` of a pass-independent render (a pass-independent mode: pppm, vcm, bpt, vm), in any order;
        :meth:`render_pass` there runs the lowest index not yet rendered."""
        _core.render_pass_index(self._core_object, int(index))

    def partial(self) -> Partial:
        """The passes so far as a :class:`libppm.Partial` (a pass-independent mode: pppm, vcm, bpt, vm)."""
        from .partial import Partial
        return Partial(_core.renderer_partial(self._core_object))

    def merge_partial(self, partial: Partial) -> None:
        """Adds a :class:`libppm.Partial`'s passes to this renderer's (a pass-independent mode: pppm, vcm, bpt, vm)."""
        _core.renderer_merge_partial(self._core_object, partial._core_object)

    def cancel(self) -> None:
        """Stops the running pass as soon as possible, or the next one. Thread safe."""
        self._core_object.cancel()

    def layer(self, name: str = "radiance") -> Float32Array:
        """An image layer after the last completed pass, row-major from the top-left pixel:
        ``"radiance"`` float32 ``(H, W, 3)`` linear RGB (W/(m^2 sr)); ``"radius"`` float32
        ``(H, W)`` gather radius in scene units; ``"photons"`` ``(H, W)`` the alpha-reduced
        photon count N. Safe to call from another thread during a pass."""
        channels = _LAYER_CHANNELS.get(name, 1)
        shape = (self.height, self.width) + ((channels,) if channels > 1 else ())
        out = np.empty(shape, dtype=np.float32)
        self._core_object.get_layer(name, out)
        return out

    def image(self) -> Float32Array:
        """The radiance layer: float32 ``(H, W, 3)`` linear RGB."""
        return self.layer("radiance")

    # -- checkpoints ----------------------------------------------------------------------
    def save_checkpoint(self, path: PathLike) -> None:
        """Writes the progressive state after the last whole pass to ``path`` atomically."""
        self._core_object.save_checkpoint(os.fspath(path))

    def load_checkpoint(self, path: PathLike) -> None:
        """Replaces the state of a renderer that has not run a pass yet by a checkpoint of
        the same scene, camera and fixed settings; rendering on gives the same image, bit
        for bit, as an uninterrupted render."""
        self._core_object.load_checkpoint(os.fspath(path))

