# SPDX-License-Identifier: Apache-2.0
"""Scenes: geometry, materials, textures, lights; commit; ray queries."""
from __future__ import annotations

import numbers
import os
from typing import Dict, List, Optional, Tuple, Union

import numpy as np

from . import _core, _rays
from ._arrays import color, index_array, real_array, uint32, vector
from ._errors import InvalidArgumentError
from ._handle import Handle
from ._typing import ArrayLike, BoolArray, ColorLike, Float64Array, PathLike
from .context import Context, resolve

#: Mitsuba 3's default indices of refraction (glass and air).
DEFAULT_INT_IOR = 1.5046
DEFAULT_EXT_IOR = 1.000277


class MaterialId(int):
    """A material's id (an ``int``): given as a parameter it names a nested BSDF."""


class TextureId(int):
    """A texture's id (an ``int``) from :meth:`Scene.add_texture`, for colour parameters."""


#: A value of :meth:`Scene.add_material`, :meth:`Scene.add_texture`, :meth:`Scene.add_light`.
ParamValue = Union[bool, float, str, "os.PathLike[str]", ArrayLike, MaterialId, TextureId]

# The kinds of ppm_param (ppm.h, ppm_param_type).
_NUMBERS, _STRING, _MATERIAL, _TEXTURE = 0, 1, 2, 3


def _params(params: Dict[str, ParamValue]) -> List[Tuple[str, int, List[float], str, int]]:
    """Named parameters as the extension passes them to the C API."""
    out: List[Tuple[str, int, List[float], str, int]] = []
    for name, value in params.items():
        if isinstance(value, MaterialId):
            out.append((name, _MATERIAL, [], "", int(value)))
        elif isinstance(value, TextureId):
            out.append((name, _TEXTURE, [], "", int(value)))
        elif isinstance(value, (str, os.PathLike)):
            out.append((name, _STRING, [], os.fspath(value), 0))
        else:
            numbers = real_array(value, name, (), (None,), (4, 4))
            out.append((name, _NUMBERS, [float(x) for x in np.ravel(numbers)], "", 0))
    return out


class Scene(Handle):
    """Geometry to ray trace and render, built by ``add_*`` calls, then :meth:`commit`.

    Every ``add_*`` call copies its input and returns an id (geometries, materials and
    lights are each numbered 0, 1, 2, ... in the order of addition). Geometry adds take an
    optional ``material`` id. After any change, :meth:`commit` before querying or rendering.

    >>> scene = libppm.Scene()
    >>> scene.add_sphere((0, 0, 0), 1.0)
    0
    >>> scene.commit()
    >>> scene.intersect((0, 0, -5), (0, 0, 1)).t
    array(4.)

    ``context``: a :class:`libppm.Context`, default :func:`libppm.default_context`.
    ``tolerance``: accuracy of hits relative to the scene's bounding-box diagonal
    (default 1e-9, range [1e-14, 1e-2]).
    """

    _core_object: _core.Scene

    def __init__(self, context: Optional[Context] = None,
                 tolerance: Optional[float] = None) -> None:
        self.context = resolve(context)
        self._core_object = _core.Scene(self.context._core_object)
        if tolerance is not None:
            self.tolerance = tolerance

    @classmethod
    def _adopt(cls, core_scene: _core.Scene, context: Context) -> "Scene":
        """A Scene owning ``core_scene`` (of a scene file), without a new handle."""
        scene = cls.__new__(cls)
        scene.context = context
        scene._core_object = core_scene
        return scene

    # -- settings -------------------------------------------------------------------------
    @property
    def tolerance(self) -> float:
        """Hit accuracy relative to the bounding-box diagonal; takes effect at commit."""
        return self._core_object.get_double("tolerance")

    @tolerance.setter
    def tolerance(self, value: float) -> None:
        self._core_object.set_double("tolerance", float(value))

    @property
    def patch_presplit(self) -> int:
        """Sub-patches per patch edge (an int in [1, 32], default 12): memory against ray
        speed, see ppm.h; takes effect at commit."""
        return self._core_object.get_int("patch_presplit")

    @patch_presplit.setter
    def patch_presplit(self, value: int) -> None:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise TypeError(f"patch_presplit: expected an int, got {type(value).__name__}")
        self._core_object.set_int("patch_presplit", int(value))

    def set(self, key: str, value: Union[int, float]) -> None:
        """Sets a setting by name: an int goes to ``ppm_scene_set_int``, a float to
        ``ppm_scene_set_double`` (whole floats are accepted for integer settings)."""
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"scene setting {key!r}: expected int or float, got {type(value).__name__}")
        if isinstance(value, numbers.Integral):
            self._core_object.set_int(key, int(value))
        else:
            self._core_object.set_double(key, float(value))

    def get(self, key: str) -> Union[int, float]:
        """A setting by name, as the C API types it: ``patch_presplit`` an int,
        ``tolerance`` a float."""
        # One getter per type and no "type of key" query: get_int refuses a double key.
        try:
            return self._core_object.get_int(key)
        except InvalidArgumentError:
            return self._core_object.get_double(key)

    # -- geometry -------------------------------------------------------------------------
    def _with_material(self, geom_id: int, material: Optional[int]) -> int:
        if material is not None:
            self.set_material(geom_id, material)
        return geom_id

    def add_bezier_patches(self, control_points: ArrayLike, material: Optional[int] = None) -> int:
        """Adds bicubic Bezier patches as one geometry; returns its id.

        ``control_points``: shape ``(n, 16, 3)`` or ``(n, 4, 4, 3)``; patch p has control
        points ``P[i][j]`` at ``[p, i, j]`` (or ``[p, 4*i + j]``) and the surface
        ``S(u, v) = sum_ij B_i(v) B_j(u) P[i][j]``: u runs along a row, v across rows.
        Hits report the patch index as ``prim_id`` and (u, v) in that patch.
        """
        points = real_array(control_points, "control_points", (None, 16, 3), (None, 4, 4, 3))
        return self._with_material(self._core_object.add_bezier_patches(points), material)

    def load_bpt(self, path: PathLike, material: Optional[int] = None) -> int:
        """Adds the patches of a ``.bpt`` file as one geometry; returns its id."""
        return self._with_material(self._core_object.load_bpt(os.fspath(path)), material)

    def add_sphere(self, center: ArrayLike, radius: float, material: Optional[int] = None) -> int:
        """Adds a sphere; hit (u, v) = (phi / 2pi, theta / pi), theta from +z."""
        return self._with_material(
            self._core_object.add_sphere(vector(center, "center"), float(radius)), material)

    def add_quad(self, origin: ArrayLike, edge_u: ArrayLike, edge_v: ArrayLike,
                 material: Optional[int] = None) -> int:
        """Adds the parallelogram ``origin + s*edge_u + t*edge_v``, s, t in [0, 1].

        Hit (u, v) = (s, t); geometric normal ``edge_u x edge_v``.
        """
        return self._with_material(
            self._core_object.add_quad(vector(origin, "origin"), vector(edge_u, "edge_u"),
                                       vector(edge_v, "edge_v")), material)

    def add_disk(self, center: ArrayLike = (0, 0, 0), axis_u: ArrayLike = (1, 0, 0),
                 axis_v: ArrayLike = (0, 1, 0), material: Optional[int] = None) -> int:
        """Adds the disk ``center + x*axis_u + y*axis_v``, x^2 + y^2 <= 1 (Mitsuba's ``disk``).

        Geometric normal ``axis_u x axis_v``; hit (u, v) = (r, phi / 2pi).
        """
        return self._with_material(
            self._core_object.add_disk(vector(center, "center"), vector(axis_u, "axis_u"),
                                       vector(axis_v, "axis_v")), material)

    def add_cylinder(self, p0: ArrayLike = (0, 0, 0), p1: ArrayLike = (0, 0, 1), radius: float = 1.0,
                     material: Optional[int] = None) -> int:
        """Adds the open tube of ``radius`` around p0 -> p1 (Mitsuba's ``cylinder``, no caps).

        Normals point away from the axis; hit (u, v) = (phi / 2pi, height / length).
        """
        return self._with_material(
            self._core_object.add_cylinder(vector(p0, "p0"), vector(p1, "p1"), float(radius)), material)

    def set_flip_normals(self, geom_id: int, flip: bool = True) -> None:
        """Mitsuba's ``flip_normals``: hits report the opposite normal and an area light on the
        geometry emits on the other side (meshes, quads, disks, cylinders)."""
        self._core_object.set_geometry_flip_normals(uint32(geom_id, "geom_id"), bool(flip))

    def set_face_normals(self, geom_id: int, face_normals: bool = True) -> None:
        """Shades a triangle mesh with its flat face normals (Mitsuba's ``face_normals``),
        dropping its vertex normals for good; takes effect at the next :meth:`commit`."""
        self._core_object.set_mesh_face_normals(uint32(geom_id, "geom_id"), bool(face_normals))

    def add_mesh(self, positions: ArrayLike, indices: ArrayLike,
                 normals: Optional[ArrayLike] = None, uvs: Optional[ArrayLike] = None,
                 material: Optional[int] = None) -> int:
        """Adds a triangle mesh; returns its id.

        ``positions`` ``(V, 3)``, ``indices`` ``(T, 3)`` integers, optional per-vertex
        ``normals`` ``(V, 3)`` (interpolated as shading normals) and ``uvs`` ``(V, 2)``.
        Hit (u, v) are the barycentric coordinates of a triangle's vertices 1 and 2.
        """
        positions = real_array(positions, "positions", (None, 3))
        count = positions.shape[0]
        indices = index_array(indices, "indices", (None, 3))
        if normals is not None:
            normals = real_array(normals, "normals", (count, 3))
        if uvs is not None:
            uvs = real_array(uvs, "uvs", (count, 2))
        return self._with_material(
            self._core_object.add_triangle_mesh(positions, indices, normals, uvs), material)

    add_triangle_mesh = add_mesh

    def load_obj(self, path: PathLike, material: Optional[int] = None) -> int:
        """Adds a Wavefront OBJ file as one triangle mesh; returns its id."""
        return self._with_material(self._core_object.load_obj(os.fspath(path)), material)

    def set_transform(self, geom_id: int, matrix: ArrayLike) -> None:
        """Sets a geometry's affine transform: a ``(4, 4)`` (last row 0 0 0 1) or ``(3, 4)``
        matrix applied to points as ``M @ (x, y, z, 1)``. Spheres need uniform scale."""
        m = real_array(matrix, "matrix", (4, 4), (3, 4))
        if m.shape == (3, 4):
            m = np.vstack([m, [0.0, 0.0, 0.0, 1.0]])
        self._core_object.set_geometry_transform(uint32(geom_id, "geom_id"), np.ascontiguousarray(m))

    def set_material(self, geom_id: int, material_id: int) -> None:
        """Assigns a material id (reported in hits, used by the renderer) to a geometry."""
        self._core_object.set_geometry_material(uint32(geom_id, "geom_id"),
                                                uint32(material_id, "material_id"))

    def primitive_count(self, geom_id: int) -> int:
        """Patches or triangles of a geometry; 1 for a sphere or quad."""
        return self._core_object.get_primitive_count(uint32(geom_id, "geom_id"))

    @property
    def geometry_count(self) -> int:
        """Number of geometries; their ids are ``0 .. geometry_count - 1``."""
        return self._core_object.get_geometry_count()

    def bezier_patches(self, geom_id: int) -> Float64Array:
        """World-space control points of a committed patch geometry, its transform applied:
        float64 array ``(n, 16, 3)`` in the layout of :meth:`add_bezier_patches`.
        Raises :class:`libppm.InvalidArgumentError` for a geometry that is not made of patches."""
        count = self.primitive_count(geom_id)
        out = np.empty((count, 16, 3), dtype=np.float64)
        self._core_object.get_bezier_patches(uint32(geom_id, "geom_id"), out)
        return out

    def commit(self) -> None:
        """Builds the acceleration structure; needed after any change, before queries."""
        self._core_object.commit()

    @property
    def bounds(self) -> Tuple[Float64Array, Float64Array]:
        """``(lower, upper)`` corners of the committed scene's box, float64 arrays."""
        lower, upper = self._core_object.get_bounds()
        return np.array(lower), np.array(upper)

    # -- materials, textures, lights ------------------------------------------------------
    def add_material(self, type: str, **params: ParamValue) -> MaterialId:
        """A material of any type libppm renders, with Mitsuba 3's type and parameter names
        and defaults (``docs/scene-format.md`` lists them), as in Mitsuba's ``load_dict``::

            glass = scene.add_material("dielectric", int_ior=1.5)
            shell = scene.add_material("twosided", bsdf=glass)

        A value is a number or a bool, a sequence of numbers (a colour, a vector, a 4x4
        transform), a string or path, a :class:`MaterialId` (nested BSDFs) or a
        :class:`TextureId` (a colour from :meth:`add_texture`). An unknown parameter name is
        an error (with a suggestion), never ignored.
        """
        return MaterialId(self._core_object.add_material(type, _params(params)))

    def add_texture(self, type: str, **params: ParamValue) -> TextureId:
        """A texture (Mitsuba ``bitmap`` and the other types of ``docs/scene-format.md``) to
        give a material's colour parameter: ``add_material("diffuse", reflectance=tex)``."""
        return TextureId(self._core_object.add_texture(type, _params(params)))

    def add_light(self, type: str, **params: ParamValue) -> int:
        """A light that is not a shape (Mitsuba ``point``, ``spot`` and the other emitter types
        of ``docs/scene-format.md``); area lights are :meth:`set_emission`. Returns its id."""
        return int(self._core_object.add_light(type, _params(params)))

    def add_shape(self, type: str, **params: ParamValue) -> int:
        """A shape of any type libppm renders, with Mitsuba 3's type and parameter names and
        defaults (``docs/scene-format.md``): ``sphere``, ``rectangle``, ``disk``, ``cylinder``,
        ``cube``, ``obj``, ``ply``, ``serialized``, and libppm's ``quad`` and ``bezier``; every
        type takes ``to_world`` (a 4x4 transform) and ``bsdf`` (a :class:`MaterialId`)::

            floor = scene.add_shape("rectangle", to_world=np.diag([5, 5, 1, 1]), bsdf=grey)

        Arrays of points (``patches``: per patch 16 control points; ``uv_rects``) may have any
        shape: they are passed in row-major order. Returns the geometry's id.
        """
        flat = {name: (np.ravel(np.asarray(value, dtype=np.float64))
                       if name != "to_world" and not isinstance(value, (str, os.PathLike)) and np.ndim(value) >= 2
                       else value)
                for name, value in params.items()}
        return int(self._core_object.add_shape(type, _params(flat)))

    def add_diffuse_material(self, reflectance: ColorLike = 0.5) -> MaterialId:
        """Lambertian material (Mitsuba ``diffuse``); RGB or grey reflectance in [0, 1]."""
        return MaterialId(self._core_object.add_diffuse_material(color(reflectance, "reflectance")))

    def add_mirror_material(self, specular_reflectance: ColorLike = 1.0) -> MaterialId:
        """Perfect mirror with a tint (Mitsuba ``conductor``)."""
        return MaterialId(self._core_object.add_mirror_material(
            color(specular_reflectance, "specular_reflectance")))

    def add_dielectric_material(self, int_ior: float = DEFAULT_INT_IOR,
                                ext_ior: float = DEFAULT_EXT_IOR) -> MaterialId:
        """Smooth glass with exact Fresnel (Mitsuba ``dielectric``); normals point outwards."""
        return MaterialId(self._core_object.add_dielectric_material(float(int_ior), float(ext_ior)))

    def add_coated_material(self, diffuse_reflectance: ColorLike = 0.5,
                            int_ior: float = DEFAULT_INT_IOR,
                            ext_ior: float = DEFAULT_EXT_IOR) -> MaterialId:
        """Diffuse base under a smooth dielectric coat (Mitsuba ``plastic``)."""
        return MaterialId(self._core_object.add_coated_material(
            color(diffuse_reflectance, "diffuse_reflectance"), float(int_ior), float(ext_ior)))

    def set_texture(self, material_id: int, path: PathLike, scale: Optional[ArrayLike] = None,
                    offset: Optional[ArrayLike] = None) -> None:
        """Gives a diffuse, mirror or coated material an image texture (read now).

        Looked up at ``(s * scale[0] + offset[0], t * scale[1] + offset[1])`` for surface
        texture coordinates (s, t); 8/16-bit images are decoded from sRGB.
        """
        self._core_object.set_material_texture(
            uint32(material_id, "material_id"), os.fspath(path),
            None if scale is None else vector(scale, "scale", 2),
            None if offset is None else vector(offset, "offset", 2))

    def set_patch_uv_rects(self, geom_id: int, rects: ArrayLike) -> None:
        """Maps one texture across a patch set: ``rects`` ``(n_patches, 4)`` rows
        ``(s0, t0, s1, t1)``; patch i's (u, v) maps onto ``[s0, s1] x [t0, t1]``."""
        r = real_array(rects, "rects", (None, 4))
        self._core_object.set_patch_uv_rects(uint32(geom_id, "geom_id"), r)

    def add_point_light(self, position: ArrayLike, intensity: ColorLike) -> int:
        """Point light; ``intensity`` in W/sr (RGB or grey). Returns the light id."""
        return self._core_object.add_point_light(vector(position, "position"),
                                                 color(intensity, "intensity"))

    def add_spot_light(self, position: ArrayLike, target: ArrayLike, intensity: ColorLike,
                       cutoff_angle: float = 20.0, beam_width: float = 15.0) -> int:
        """Spot light (Mitsuba ``spot``): full ``intensity`` (W/sr) within ``beam_width``
        degrees of the axis, falling linearly to 0 at ``cutoff_angle``."""
        return self._core_object.add_spot_light(
            vector(position, "position"), vector(target, "target"), color(intensity, "intensity"),
            float(cutoff_angle), float(beam_width))

    def set_emission(self, geom_id: int, radiance: ColorLike) -> None:
        """Makes a quad, sphere, disk, cylinder or triangle mesh an area light of constant
        ``radiance`` (W/(m^2 sr)) on the side its normal points to (a mesh's shading normal);
        black turns it off. Bezier patches cannot be area lights."""
        self._core_object.set_geometry_emission(uint32(geom_id, "geom_id"),
                                                color(radiance, "radiance"))

    # -- ray queries ----------------------------------------------------------------------
    def intersect(self, origins: ArrayLike, directions: ArrayLike, tnear: ArrayLike = 0.0,
                  tfar: ArrayLike = np.inf) -> _rays.Hits:
        """Closest hits of rays ``origins + t * directions``, t in [tnear, tfar].

        ``origins`` and ``directions`` have shape ``(..., 3)`` and broadcast against each
        other and against ``tnear`` / ``tfar`` (scalars or batch-shaped); directions need
        not be unit length (t is in units of ``|direction|``). Returns :class:`libppm.Hits`
        whose arrays have the broadcast batch shape. A miss has ``t = inf`` and ``geom_id``
        = ``prim_id`` = :data:`libppm.INVALID_ID` (0xFFFFFFFF; the arrays are uint32). The
        scene must be committed. Runs without the GIL, on the context's worker threads.
        """
        rays, shape = _rays.make_rays(origins, directions, tnear, tfar)
        hits = np.empty(rays.shape, dtype=_rays.HIT_DTYPE)
        self._core_object.intersect(rays.view(np.uint8), hits.view(np.uint8))
        return _rays.Hits(hits, shape)

    def occluded(self, origins: ArrayLike, directions: ArrayLike, tnear: ArrayLike = 0.0,
                 tfar: ArrayLike = np.inf) -> BoolArray:
        """Whether each ray hits anything in [tnear, tfar]: a bool array of the batch shape.
        Arguments as for :meth:`intersect`."""
        rays, shape = _rays.make_rays(origins, directions, tnear, tfar)
        result = np.empty(rays.shape, dtype=np.uint8)
        self._core_object.occluded(rays.view(np.uint8), result)
        return result.astype(bool).reshape(shape)
