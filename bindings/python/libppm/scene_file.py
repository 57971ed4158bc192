"""JSON scene files (docs/scene-format.md, ``ppm_scene_file_*``)."""
import os

from . import _core
from ._errors import Error
from ._handle import Handle
from .camera import Camera
from .context import resolve
from .renderer import Renderer
from .scene import Scene


class SceneFile(Handle):
    """A loaded JSON scene file: its committed :attr:`scene`, :attr:`camera` and render
    settings. Relative paths in the file are relative to its folder.

    >>> with libppm.load("scene.json") as f:
    ...     image = f.create_renderer().render(f.passes or 16)
    """

    def __init__(self, path, context=None):
        if not _core.has_scene_files:
            raise Error("scene files: the libppm this module was built against does not "
                        "implement them (rebuild against a newer libppm)")
        self.context = resolve(context)
        self.path = os.fspath(path)
        self._core_object = _core.SceneFile(self.context._core_object, self.path)
        self.scene = Scene._adopt(self._core_object.get_scene(), self.context)
        self.camera = Camera._from_tuple(self._core_object.get_camera())

    def create_renderer(self, **settings):
        """A :class:`Renderer` with the file's integrator settings, then ``settings``."""
        renderer = Renderer._adopt(self._core_object.create_renderer(), self.scene, self.camera)
        renderer.set(**settings)
        return renderer

    @property
    def passes(self):
        """``integrator.passes`` of the file, 0 when not given."""
        return self._core_object.get_int("passes")

    @property
    def time(self):
        """``integrator.time`` of the file in seconds, 0 when not given."""
        return self._core_object.get_double("time")

    def get_int(self, key):
        return self._core_object.get_int(key)

    def get_double(self, key):
        return self._core_object.get_double(key)


def load(path, context=None):
    """Loads a JSON scene file: returns a :class:`SceneFile`."""
    return SceneFile(path, context)
