# SPDX-License-Identifier: Apache-2.0
"""Scene files (docs/scene-format.md): libppm's JSON or Mitsuba 3 XML, ``ppm_scene_file_*``."""
from __future__ import annotations

import json
import os
from typing import Any, Mapping, Optional, Union

from . import _core
from ._errors import UnknownKeyError
from ._handle import Handle
from ._typing import PathLike
from .camera import Camera
from .context import Context, resolve
from .renderer import Renderer
from .scene import Scene

# The file's read-only values and their types (ppm_scene_file_get_int / _get_double).
_VALUES = {"passes": "int", "time": "double"}


class SceneFile(Handle):
    """A loaded scene file: its committed :attr:`scene`, :attr:`camera` and render settings.
    Relative paths in the file are relative to its folder.

    >>> with libppm.load_file("scene.xml", spp=64) as f:
    ...     image = libppm.render(f)

    ``format``: "json", "xml" or None (XML for a ``.xml`` name or a text starting with
    ``<``). ``defines``: parameters of an XML file, replacing its ``<default>`` values (as
    Mitsuba's ``-D name=value``). ``lenient``: what libppm cannot render in an XML file is
    substituted (a grey diffuse BSDF) or left out, with a warning each, instead of an error.
    ``text``: the scene's content instead of reading ``path`` (``path`` then only names it in
    messages), with file names inside relative to ``folder``.
    """

    _core_object: _core.SceneFile

    def __init__(self, path: PathLike, context: Optional[Context] = None, *,
                 format: Optional[str] = None, defines: Optional[Mapping[str, Any]] = None,
                 lenient: bool = False, text: Optional[str] = None,
                 folder: Optional[PathLike] = None) -> None:
        self.context = resolve(context)
        self.path = os.fspath(path)
        parameters = {str(k): _define_value(v) for k, v in (defines or {}).items()}
        self._core_object = _core.SceneFile(
            self.context._core_object, self.path, text,
            None if folder is None else os.fspath(folder), format, parameters, bool(lenient))
        self.scene = Scene._adopt(self._core_object.get_scene(), self.context)
        self.camera = Camera._from_tuple(self._core_object.get_camera())

    def create_renderer(self, camera: Optional[Camera] = None, **settings: Any) -> Renderer:
        """A :class:`Renderer` with the file's integrator settings, then ``settings``.

        It sees the scene through ``camera`` (default: the file's), whose fields may also be
        given as keywords that change the file's camera: ``create_renderer(width=64,
        height=48)`` renders at another size (radii given in pixels follow), ``crop=(x0, y0,
        x1, y1)`` only a window of the image.
        """
        fields = {k: settings.pop(k) for k in list(settings) if k in Camera.field_names()}
        if camera is not None and not isinstance(camera, Camera):
            raise TypeError(f"camera: expected libppm.Camera, got {type(camera).__name__}")
        if camera is None and not fields:
            core = self._core_object.create_renderer()
            view = self.camera
        else:
            view = (camera or self.camera).replace(**fields)
            core = self._core_object.create_renderer(view._as_tuple())
        renderer = Renderer._adopt(core, self.scene, view)
        try:
            renderer.set(**settings)
        except BaseException:
            renderer.close()
            raise
        return renderer

    @property
    def passes(self) -> int:
        """``integrator.passes`` of the file (an XML file's ``sample_count``), 0 when not given."""
        return int(self.get("passes"))

    @property
    def time(self) -> float:
        """``integrator.time`` of the file in seconds, 0 when not given."""
        return float(self.get("time"))

    def get(self, key: str) -> Union[int, float]:
        """A read-only value of the file: ``"passes"`` (int) or ``"time"`` (float)."""
        kind = _VALUES.get(key)
        if kind is None:
            raise UnknownKeyError(f"unknown scene file value {key!r} (known: passes, time)")
        if kind == "int":
            return int(self._core_object.get_int(key))
        return float(self._core_object.get_double(key))


def _define_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    return str(value)


def load(path: PathLike, context: Optional[Context] = None, **options: Any) -> SceneFile:
    """Loads a scene file (JSON or Mitsuba XML): returns a :class:`SceneFile`. ``options``
    as :class:`SceneFile` (``format``, ``defines``, ``lenient``)."""
    return SceneFile(path, context, **options)


def load_file(path: PathLike, context: Optional[Context] = None, *, lenient: bool = False,
              format: Optional[str] = None, **defines: Any) -> SceneFile:
    """Loads a scene file, Mitsuba 3 style: keyword arguments are the XML file's parameters
    (``libppm.load_file("scene.xml", spp=64, res=512)`` is ``-D spp=64 -D res=512``)."""
    return SceneFile(path, context, format=format, defines=defines, lenient=lenient)


def load_dict(scene: Mapping[str, Any], context: Optional[Context] = None, *,
              folder: Optional[PathLike] = None) -> SceneFile:
    """A scene from a dict with the structure of libppm's JSON scene files
    (docs/scene-format.md), e.g. ``{"shapes": [{"type": "sphere", "radius": 1}], ...}``.
    File names inside are relative to ``folder`` (default: the working directory). Errors
    name the key path (``shapes[0].radius: expected a number > 0``)."""
    try:
        text = json.dumps(scene, indent=1, allow_nan=False)
    except (TypeError, ValueError) as e:
        raise TypeError(f"load_dict: the scene is not JSON data: {e}") from None
    return SceneFile("<dict>", context, format="json", text=text,
                     folder=os.getcwd() if folder is None else folder)


def load_string(text: str, context: Optional[Context] = None, *, format: Optional[str] = None,
                folder: Optional[PathLike] = None, lenient: bool = False,
                **defines: Any) -> SceneFile:
    """A scene from the text of a scene file (JSON, or XML when it starts with ``<``); file
    names inside are relative to ``folder`` (default: the working directory); keyword
    arguments are XML parameters as in :func:`load_file`."""
    return SceneFile("<string>", context, format=format, defines=defines, lenient=lenient,
                     text=text, folder=os.getcwd() if folder is None else folder)
