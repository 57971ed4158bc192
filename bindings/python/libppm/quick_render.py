# SPDX-License-Identifier: Apache-2.0
"""One-call rendering, in the style of Mitsuba 3's ``mi.render``."""
from __future__ import annotations

from typing import Any, Optional, Union

from ._typing import Float32Array, PathLike
from .scene_file import SceneFile, load_file

#: Passes rendered when neither the call nor the scene file says how many.
DEFAULT_PASSES = 16


def render(scene: Union[SceneFile, PathLike], passes: Optional[int] = None,
           time: Optional[float] = None, seed: Optional[int] = None,
           **settings: Any) -> Float32Array:
    """Renders a scene file and returns its image: float32 ``(height, width, 3)``, linear
    radiance.

    ``scene``: a :class:`SceneFile` or the path of one. ``passes``: how many passes (default:
    the file's ``integrator.passes``, else 16). ``time``: a budget in seconds; the render
    stops after the pass that crosses it (with ``time`` alone, passes are unlimited).
    ``seed``: the random seed. Keyword ``settings`` override the file's integrator settings
    (``photons_per_pass=100_000``, ``mode="pppm"``, ...) and its camera's fields (``width=64,
    height=48``; ``crop=(x0, y0, x1, y1)`` renders only that window of the image).

    >>> image = libppm.render("examples/scenes/teapot-cornell.json", passes=8)
    >>> libppm.write_image("teapot.exr", image)
    """
    if seed is not None:
        settings["seed"] = seed
    if passes is not None and int(passes) < 1:
        raise ValueError(f"passes must be at least 1, not {passes}")
    if time is not None and not float(time) > 0:
        raise ValueError(f"time must be a number of seconds > 0, not {time}")
    owned = not isinstance(scene, SceneFile)
    scene_file = scene if isinstance(scene, SceneFile) else load_file(scene)
    try:
        if passes is None:
            file_passes = scene_file.passes
            if time is not None:
                passes = file_passes or 2**62
            else:
                passes = file_passes or DEFAULT_PASSES
        with scene_file.create_renderer(**settings) as renderer:
            return renderer.render(int(passes), time_limit=time)
    finally:
        if owned:
            scene_file.close()
