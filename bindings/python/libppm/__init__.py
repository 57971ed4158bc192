# SPDX-License-Identifier: Apache-2.0
"""libppm for Python: exact ray tracing of bicubic Bezier patches and progressive photon
mapping, over the C API of ``<ppm/ppm.h>``.

Objects (:class:`Context`, :class:`Scene`, :class:`Renderer`, :class:`SceneFile`) own a
libppm handle: ``close()`` or a ``with`` block releases it, and a child keeps its parents
alive. Arrays are numpy; failures raise :class:`Error` subclasses carrying libppm's message.
"""
from typing import List

from ._errors import (CancelledError, ClosedError, Error, FileError, FileNotFoundError,
                      InternalError, InvalidArgumentError, InvalidOperationError,
                      OutOfMemoryError, ParseError, Status, UnknownKeyError, UnsupportedError,
                      Warning)
from . import _core
from ._rays import HIT_DTYPE, RAY_DTYPE, Hits
from .camera import Camera
from .context import Context, default_context
from .partial import Partial, check_image_path, write_image
from .renderer import Renderer
from .scene import MaterialId, Scene, TextureId
from .quick_render import render
from .scene_file import SceneFile, load, load_dict, load_file, load_string
from .tessellate import Mesh, tessellate

#: The version of the package, which is that of the libppm inside it.
__version__: str = _core.version_string()

#: geom_id (and prim_id) of a miss: 0xFFFFFFFF.
INVALID_ID = _core.INVALID_ID


def type_names(kind: str) -> List[str]:
    """The types libppm renders of a kind: ``"material"``, ``"texture"``, ``"light"``,
    ``"shape"`` (what :meth:`Scene.add_material` and the others and scene files accept) or
    ``"mode"`` (the renderer's ``mode`` setting), in a fixed order."""
    return list(_core.type_names(kind))


def version() -> str:
    """Version string of the libppm actually loaded, "major.minor.patch"."""
    return _core.version_string()


__all__ = [
    "CancelledError", "ClosedError", "Error", "FileError", "FileNotFoundError", "InternalError",
    "InvalidArgumentError", "InvalidOperationError", "OutOfMemoryError", "ParseError", "Status",
    "UnknownKeyError", "UnsupportedError", "Warning", "HIT_DTYPE", "RAY_DTYPE", "Hits", "Camera",
    "Context", "default_context", "Partial", "check_image_path", "write_image", "Renderer",
    "MaterialId", "Scene", "SceneFile", "TextureId", "load", "load_dict", "load_file", "load_string", "render", "Mesh",
    "tessellate", "INVALID_ID", "type_names", "version",
]
