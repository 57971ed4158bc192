/* SPDX-License-Identifier: Apache-2.0 */
/*
 * libppm — exact ray tracing of bicubic Bezier patches, and rendering by photon mapping and
 * vertex connection and merging.
 *
 * This header is the specification of the C ABI. It is C99 and self-contained.
 *
 * Conventions that hold for every function unless its comment says otherwise:
 *  - Every fallible call returns a ppm_status; PPM_OK (0) is success. On failure no output
 *    parameter is written (the few exceptions say so: a handle output set to NULL, a count
 *    that tells the caller how much room to make) and ppm_last_error_message() on the same
 *    thread says what was wrong and where (argument name, file and line, index). The error
 *    callback of the context that the call's object belongs to, if set, receives the same
 *    message (meshes, partials, images and hits belong to no context).
 *  - No function aborts, exits, or lets a C++ exception escape.
 *  - Handles are opaque and reference counted: *_create returns a handle holding one
 *    reference, *_retain adds one, *_release drops one and frees the object at zero.
 *    *_release(NULL) is a no-op. A child holds a reference to its parent (a scene keeps its
 *    context alive), so handles may be released in any order.
 *  - Pointers passed in are only read during the call; the library copies what it keeps.
 *  - Threads: different handles may be used from different threads at once. A single scene
 *    may be queried (ppm_scene_intersect/occluded, getters) from many threads at once after
 *    ppm_scene_commit, but building it (add/set/commit) must not overlap any other call on it.
 *  - Doubles are IEEE binary64; all geometry is stored and intersected in double precision.
 *  - Typed settings: contexts, scenes and renderers take string keys through
 *    ppm_<object>_set_int / _set_double / _get_int / _get_double (renderers also
 *    _set_string / _get_string); scene files have read-only values (_get_int / _get_double),
 *    meshes read-only doubles (_get_double), partials integers (_get_int, and _set_int for
 *    their one writable key). The same rules hold for each of them:
 *    an unknown key is INVALID_ARGUMENT naming the key and listing the object's keys; an
 *    integer key also takes set_double with a whole number and answers get_double exactly;
 *    a floating-point key also takes set_int, but get_int refuses it (INVALID_ARGUMENT
 *    naming its type) rather than round; read-only keys refuse every setter. New keys are
 *    how objects gain settings without a new function.
 *  - Growth: functions are never changed once released; a changed signature or struct is a
 *    new function or struct named *_v2 beside the old one, which keeps working. Structs
 *    that may grow start with a `size` field (sizeof the struct as the caller compiled it):
 *    the library reads and writes only that many bytes, so callers built against an older
 *    header keep working, and a field appended later means "as before" when 0.
 *  - Names: functions are ppm_<object>_<verb> (ppm_scene_commit, ppm_renderer_render_pass).
 *    A function first exported under another name keeps that name as an alias: the same
 *    function, declared beside the new name and kept in the ABI, so programs built against
 *    it keep working.
 */
#ifndef PPM_PPM_H
#define PPM_PPM_H

#include <stddef.h>
#include <stdint.h>

#include <ppm/config.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------------------------------- */
/* Status codes and errors                                                                   */
/* ---------------------------------------------------------------------------------------- */

/* Values are part of the ABI and never renumbered. */
typedef enum ppm_status {
    PPM_OK = 0,
    PPM_ERROR_INVALID_ARGUMENT = 1,  /* NULL where a pointer is needed, NaN/Inf, bad size, unknown key */
    PPM_ERROR_INVALID_OPERATION = 2, /* call not allowed in the object's state (e.g. query before commit) */
    PPM_ERROR_OUT_OF_MEMORY = 3,
    PPM_ERROR_IO = 4,          /* a file could not be opened or read */
    PPM_ERROR_PARSE = 5,       /* a file's content is malformed; the message names file and line */
    PPM_ERROR_UNSUPPORTED = 6, /* valid request the library cannot serve (e.g. CPU without SSE2) */
    PPM_ERROR_CANCELLED = 7,
    PPM_ERROR_INTERNAL = 8 /* a bug in libppm: please report the message */
} ppm_status;

/* Version of the library actually loaded (compare with PPM_VERSION from ppm/config.h):
 * major * 10000 + minor * 100 + patch. Thread safe, never fails. */
PPM_API uint32_t ppm_version(void);
/* "major.minor.patch"; a static string. Thread safe, never fails. */
PPM_API const char *ppm_version_string(void);

/* Short constant English name of a status ("invalid argument"); never NULL. Thread safe. */
PPM_API const char *ppm_status_string(ppm_status status);

/* Message of the last ppm_* call on the calling thread that returns a ppm_status: what was
 * wrong if it failed, "" if it succeeded. Works without any handle, so it explains why a
 * *_create failed. The string belongs to the library and stays valid until the next ppm_*
 * call on the same thread. */
PPM_API const char *ppm_last_error_message(void);

/* ---------------------------------------------------------------------------------------- */
/* Context: the root object. Owns the Embree device, the worker threads and error reporting.  */
/* ---------------------------------------------------------------------------------------- */

typedef struct ppm_context_t *ppm_context;

/* Called on the failing thread after the per-thread message is set. Must not call back
 * into the same object. `message` is valid only during the call. */
typedef void (*ppm_error_callback)(void *user_data, ppm_status status, const char *message);

/* Called with a warning: something in an input was read but not used, or replaced by a
 * substitute (vertex colours in a mesh file, an element of a kind libppm does not render).
 * `message` names the file and what was skipped, and is valid only during the call. Called on
 * the thread that reads the input; must not call back into the same object. */
typedef void (*ppm_warning_callback)(void *user_data, const char *message);

/* Creates a context with default settings (all hardware threads). The caller owns the one
 * reference returned. Thread safe.
 * Errors: INVALID_ARGUMENT (out NULL), UNSUPPORTED (Embree device creation failed),
 * OUT_OF_MEMORY. */
PPM_API ppm_status ppm_context_create(ppm_context *out_context);
/* Adds / drops a reference (atomic: thread safe). The context is freed when the caller's and
 * all scenes' references are gone. Errors (retain): INVALID_ARGUMENT (context NULL). */
PPM_API ppm_status ppm_context_retain(ppm_context context);
PPM_API void ppm_context_release(ppm_context context);

/* Settings of a context (typed settings: see the top of this header). Keys:
 *   "threads"  int: worker threads for batch queries, scene builds and rendering; 0
 *              (default) = all hardware threads; 1..1024 otherwise. Takes effect for calls
 *              that start after it.
 * Errors: INVALID_ARGUMENT (NULL, unknown key, wrong type, value out of range).
 * Thread safety: setters not concurrently with other calls using the same context (its
 * scenes' and renderers' calls included); getters concurrently with other getters. */
PPM_API ppm_status ppm_context_set_int(ppm_context context, const char *key, int64_t value);
PPM_API ppm_status ppm_context_get_int(ppm_context context, const char *key, int64_t *out_value);
PPM_API ppm_status ppm_context_set_double(ppm_context context, const char *key, double value);
PPM_API ppm_status ppm_context_get_double(ppm_context context, const char *key, double *out_value);

/* Sets (or clears, with callback NULL) the error callback; user_data is passed back as it is
 * and never dereferenced by the library. Errors: INVALID_ARGUMENT (context NULL). Not
 * concurrently with other calls using the same context. */
PPM_API ppm_status ppm_context_set_error_callback(ppm_context context, ppm_error_callback callback, void *user_data);
/* Sets the warning callback; user_data is passed back as it is. NULL restores the default,
 * which writes "libppm: warning: <message>" and a newline to stderr; to silence warnings, pass
 * a callback that does nothing. Errors: INVALID_ARGUMENT (context NULL). Not concurrently with
 * other calls using the same context. */
PPM_API ppm_status ppm_context_set_warning_callback(ppm_context context, ppm_warning_callback callback,
                                                    void *user_data);

/* ---------------------------------------------------------------------------------------- */
/* Scene: geometry, built then committed, then queried.                                      */
/* ---------------------------------------------------------------------------------------- */

typedef struct ppm_scene_t *ppm_scene;

#define PPM_INVALID_ID 0xFFFFFFFFu

/* Creates an empty scene; the caller owns the one reference returned, the scene holds one on
 * the context. Thread safe with respect to other scenes of the same context.
 * Errors: INVALID_ARGUMENT (context or out_scene NULL). */
PPM_API ppm_status ppm_scene_create(ppm_context context, ppm_scene *out_scene);
/* Adds / drops a reference (atomic: thread safe). Releasing the last reference while another
 * thread still queries the scene is the caller's error. Errors (retain): INVALID_ARGUMENT
 * (scene NULL). */
PPM_API ppm_status ppm_scene_retain(ppm_scene scene);
PPM_API void ppm_scene_release(ppm_scene scene);

/* Settings of a scene (typed settings: see the top of this header). Keys:
 *   "tolerance"  double: accuracy of every reported hit, relative to the diagonal of the
 *                scene's bounding box: hit distance and point are within tolerance * diagonal
 *                of the exact ones. Default 1e-9; range [1e-14, 1e-2]. Looser is faster
 *                mainly where the surface is degenerate or the ray tangent; Newton converges
 *                anyway. Below about 1e-11 the bound cannot hold for rays grazing the surface
 *                at 1e-6 rad or flatter: such a hit moves by eps / sin(angle) when the ray is
 *                rounded to double, so no double-precision method can place it better.
 *   "patch_presplit"  int: Bezier patches only: each patch is cut into n x n sub-patches at
 *                commit, each with its own bounding box in the scene's BVH, so a ray tests
 *                only the few sub-patches near it. n in [1, 32], default 12. Memory against
 *                speed: memory grows with n^2 per patch (each sub-patch keeps its culling
 *                data and a share of the BVH), while a smaller n makes every ray test larger
 *                sub-patches and so costs time; docs/how-it-works.md ("Memory against
 *                speed") gives both on the teapot. Accuracy does not depend on it.
 * Setting either key marks the scene uncommitted (queries need ppm_scene_commit again); the
 * new value takes effect at that commit.
 * Errors: INVALID_ARGUMENT (NULL, unknown key, wrong type, value NaN, not whole for an int
 * key, or out of range). Thread safety: setters change the scene (see Geometry below);
 * getters may run concurrently with queries and other getters. */
PPM_API ppm_status ppm_scene_set_int(ppm_scene scene, const char *key, int64_t value);
PPM_API ppm_status ppm_scene_get_int(ppm_scene scene, const char *key, int64_t *out_value);
PPM_API ppm_status ppm_scene_set_double(ppm_scene scene, const char *key, double value);
PPM_API ppm_status ppm_scene_get_double(ppm_scene scene, const char *key, double *out_value);

/* Geometry. Each add call copies its input and returns a geometry id (0, 1, 2, ... in the
 * order of addition) in *out_geom_id, which may be NULL. Adding a geometry, and changing one
 * (its transform, material id, flip_normals or face_normals), marks the scene uncommitted:
 * queries and render passes then fail with INVALID_OPERATION until ppm_scene_commit.
 * Every call below that takes a geom_id fails with INVALID_ARGUMENT when it names no
 * geometry of the scene, and every call fails with INVALID_ARGUMENT for a NULL scene or a
 * NULL pointer argument that is not documented as optional.
 * Coordinates must be finite, and every coordinate, length and radius of the placed geometry
 * (its transform applied) must lie within +-1e12 scene units; degenerate input (zero radius,
 * zero-area quad, out-of-range index) and input beyond that limit are INVALID_ARGUMENT naming
 * the offending element. Zero-area triangles of a mesh are allowed and never hit. A failed
 * add leaves the scene unchanged.
 * Thread safety of all calls that change a scene (add, load, set, commit): they must not
 * overlap any other call on the same scene. */

/* Bicubic Bezier patches: `control_points` holds patch_count * 16 * 3 doubles; patch p has
 * control points P[i][j] at index p*16 + i*4 + j (x, y, z consecutive) and the surface
 *   S(u, v) = sum_i sum_j B_i(v) B_j(u) P[i][j],  u, v in [0, 1], B = cubic Bernstein,
 * i.e. u runs along a row of four points, v across rows (the .bpt and Embree convention).
 * Patches are two-sided. Collapsed edges (a row of equal points) are allowed. */
PPM_API ppm_status ppm_scene_add_bezier_patches(ppm_scene scene, const double *control_points, size_t patch_count,
                                                uint32_t *out_geom_id);

/* Reads a .bpt file (patch count, then per patch a "3 3" degree line and 16 "x y z" lines)
 * and adds its patches as one geometry. Errors: IO (cannot open, read error), PARSE (the
 * message names file and line: truncated, not a number, NaN/Inf, wrong degree, count that
 * does not match the content or exceeds 10 000 000). */
PPM_API ppm_status ppm_scene_load_bpt(ppm_scene scene, const char *path, uint32_t *out_geom_id);

/* Sphere with centre and radius > 0. Hit (u, v) = (phi / 2pi, theta / pi), with theta measured
 * from +z and phi from +x towards +y (Mitsuba 3's convention). */
PPM_API ppm_status ppm_scene_add_sphere(ppm_scene scene, const double center[3], double radius, uint32_t *out_geom_id);

/* Disk (Mitsuba 3's `disk`, an ellipse for non-orthogonal or unequal axes)
 * {center + x*axis_u + y*axis_v : x^2 + y^2 <= 1}; geometric normal axis_u x axis_v (unit);
 * hit (u, v) = (r, phi / 2pi) with r = sqrt(x^2 + y^2) and phi from axis_u towards axis_v,
 * as Mitsuba's. Mitsuba's default disk is center (0, 0, 0), axes (1, 0, 0) and (0, 1, 0).
 * Two-sided. Errors: INVALID_ARGUMENT (NaN, axes zero or parallel: no area). */
PPM_API ppm_status ppm_scene_add_disk(ppm_scene scene, const double center[3], const double axis_u[3],
                                      const double axis_v[3], uint32_t *out_geom_id);

/* Open cylinder (Mitsuba 3's `cylinder`: a tube without caps) of `radius` around the segment
 * p0 -> p1; normals point away from the axis. Hit (u, v) = (phi / 2pi, z / |p1 - p0|), z the
 * height above p0 and phi about the axis from the tangent s of Duff et al.'s orthonormal
 * basis of the unit axis towards t (Mitsuba's coordinate_system). Takes only rotations,
 * translations and uniform scaling as its transform. Two-sided. Errors: INVALID_ARGUMENT
 * (NaN, p0 == p1, radius not in (0, coordinate limit]). */
PPM_API ppm_status ppm_scene_add_cylinder(ppm_scene scene, const double p0[3], const double p1[3], double radius,
                                          uint32_t *out_geom_id);

/* Mitsuba's `flip_normals`: hits on the geometry report the opposite ng and ns, and an area
 * light on it emits on the other side. For triangle meshes, quads, disks and cylinders.
 * Errors: INVALID_ARGUMENT (a sphere or patch set: not supported). */
PPM_API ppm_status ppm_scene_set_geometry_flip_normals(ppm_scene scene, uint32_t geom_id, int flip);

/* Mitsuba's `face_normals` on a triangle mesh: shades it with its flat face normals, dropping
 * the vertex normals it was loaded or made with (for good: a later call with 0 does not bring
 * them back). Takes effect at the next commit. Errors: INVALID_ARGUMENT (not a mesh). */
PPM_API ppm_status ppm_scene_set_mesh_face_normals(ppm_scene scene, uint32_t geom_id, int face_normals);

/* Parallelogram (a rectangle when the edges are orthogonal) {origin + s*edge_u + t*edge_v :
 * s, t in [0, 1]}; hit (u, v) = (s, t); geometric normal edge_u x edge_v. Two-sided. */
PPM_API ppm_status ppm_scene_add_quad(ppm_scene scene, const double origin[3], const double edge_u[3],
                                      const double edge_v[3], uint32_t *out_geom_id);

/* Triangle mesh: vertex_count positions (3 doubles each), triangle_count index triples.
 * `normals` (3 doubles per vertex) and `uvs` (2 doubles per vertex) may be NULL. Hit (u, v)
 * are the barycentric coordinates of vertices 1 and 2 (Embree's); the shading normal
 * interpolates `normals` when given. Two-sided. */
PPM_API ppm_status ppm_scene_add_triangle_mesh(ppm_scene scene, const double *positions, size_t vertex_count,
                                               const uint32_t *indices, size_t triangle_count, const double *normals,
                                               const double *uvs, uint32_t *out_geom_id);

/* The three mesh files below: a mesh that comes without vertex normals shades smoothly with
 * the vertex normals Mitsuba 3 computes for it (each triangle's unit normal added to its
 * corners, weighted by the corner's angle, from the placed positions at every commit), as
 * Mitsuba's mesh plugins do; ppm_scene_set_mesh_face_normals makes it flat. */

/* Reads a Wavefront OBJ file (v, vn, vt and f statements; all objects become one triangle
 * mesh, polygons are fanned from their first corner, per-vertex normals and texture
 * coordinates are kept when every face has them; a `vt u v` becomes uv (u, 1 - v): OBJ's
 * v = 0 is the image's bottom row, libppm's and Mitsuba's the top). Words are separated by
 * spaces and tabs; lines end with "\n" or "\r\n". Errors: IO, PARSE naming file and line (a
 * number that is not one, not finite or beyond +-1e12; an index out of range; a face with
 * fewer than 3 corners or with no area; a control character), INVALID_ARGUMENT (the
 * placed mesh beyond the coordinate limit). */
PPM_API ppm_status ppm_scene_load_obj(ppm_scene scene, const char *path, uint32_t *out_geom_id);

/* Reads a PLY mesh (format 1.0: ascii, binary_little_endian or binary_big_endian). Vertex
 * x, y, z are required; nx, ny, nz become per-vertex normals and u, v (else texture_u,
 * texture_v, else s, t) texture coordinates, kept as they are (as Mitsuba 3 reads them);
 * faces come from the list vertex_indices (or vertex_index), polygons fanned from their first
 * corner. Data the mesh does not use (vertex colours, other properties and elements) is
 * skipped with one warning per kind (ppm_context_set_warning_callback). Errors: IO, PARSE
 * naming the file and the header line, body line (ascii) or byte offset (binary): counts the
 * file's size cannot hold, a truncated body, a value that is not a number or not finite, a
 * coordinate beyond +-1e12, an index out of range, a face with fewer than 3 corners or no
 * area; INVALID_ARGUMENT (the placed mesh beyond the coordinate limit). */
PPM_API ppm_status ppm_scene_load_ply(ppm_scene scene, const char *path, uint32_t *out_geom_id);

/* Reads mesh number `shape_index` (0: the first) of a Mitsuba `serialized` file (format
 * versions 3 and 4, zlib-compressed, single or double precision), with its normals and
 * texture coordinates. A mesh flagged for face normals is loaded without vertex normals;
 * vertex colours are skipped with a warning; triangles repeating a vertex are left out.
 * Errors: IO, PARSE naming the file, the mesh and its byte offset (not a serialized file, a
 * shape_index beyond the meshes the file holds, corrupt or truncated compressed data, counts
 * the file cannot hold, an index out of range, a coordinate not finite or beyond +-1e12),
 * INVALID_ARGUMENT (the placed mesh beyond the coordinate limit). */
PPM_API ppm_status ppm_scene_load_serialized(ppm_scene scene, const char *path, uint32_t shape_index,
                                             uint32_t *out_geom_id);

/* Affine transform of a geometry: 16 doubles, row-major 4x4 matrix M applied to points as
 * M * (x, y, z, 1); the last row must be (0, 0, 0, 1) and the upper 3x3 invertible. Patches,
 * meshes, quads and disks are transformed exactly (their control points, vertices, origin
 * and axes); spheres and cylinders take only similarity transforms (rotations, reflections,
 * translations and uniform scaling). Default identity. Applied at commit. Errors:
 * INVALID_ARGUMENT (a NaN or infinite element, a projective last row, a singular 3x3, a
 * non-similarity on a sphere or cylinder, the placed geometry beyond the coordinate limit;
 * the scene is unchanged). */
PPM_API ppm_status ppm_scene_set_geometry_transform(ppm_scene scene, uint32_t geom_id, const double matrix[16]);

/* User material id reported in every hit of this geometry (default 0). Any id is accepted
 * here; a renderer checks that it names a material of the scene (ppm_renderer_create). */
PPM_API ppm_status ppm_scene_set_geometry_material(ppm_scene scene, uint32_t geom_id, uint32_t material_id);

/* Number of primitives of a geometry: patches, triangles, or 1 for a sphere, quad, disk or
 * cylinder.
 * Getters (this one and the three below) may run concurrently with queries and other
 * getters on the same scene. */
PPM_API ppm_status ppm_scene_get_primitive_count(ppm_scene scene, uint32_t geom_id, size_t *out_count);

/* Number of geometries; their ids are 0 .. count - 1. */
PPM_API ppm_status ppm_scene_get_geometry_count(ppm_scene scene, size_t *out_count);

/* World-space control points of a patch geometry (its transform applied) in the layout of
 * ppm_scene_add_bezier_patches: 48 doubles per patch into `out`, which holds `capacity`
 * doubles. Errors: INVALID_ARGUMENT (not a patch geometry, capacity below 48 * patch
 * count), INVALID_OPERATION (scene not committed). */
PPM_API ppm_status ppm_scene_get_bezier_patches(ppm_scene scene, uint32_t geom_id, double *out, size_t capacity);

/* Builds the acceleration structure on the context's threads. Required after any change
 * and before queries. Errors: INVALID_OPERATION (empty scene), INVALID_ARGUMENT (every
 * geometry degenerate, so the scene's bounding box is a point). */
PPM_API ppm_status ppm_scene_commit(ppm_scene scene);

/* Axis-aligned bounds of the committed scene (control-point hulls for patches).
 * Errors: INVALID_ARGUMENT (NULL), INVALID_OPERATION (scene not committed). */
PPM_API ppm_status ppm_scene_get_bounds(ppm_scene scene, double out_lower[3], double out_upper[3]);

/* ---------------------------------------------------------------------------------------- */
/* Ray queries                                                                               */
/* ---------------------------------------------------------------------------------------- */

/* A ray org + t * dir for t in [tnear, tfar]. dir need not be unit length (t is in units of
 * |dir|) but |dir|^2 must be a normal finite double (about 1e-154 < |dir| < 1e154); tnear is
 * finite and >= 0, tnear <= tfar, tfar may be INFINITY. */
typedef struct ppm_ray {
    double org[3];
    double tnear;
    double dir[3];
    double tfar;
} ppm_ray;

/* The closest hit of a ray. On a miss t = INFINITY and geom_id = PPM_INVALID_ID, other
 * fields 0. */
typedef struct ppm_hit {
    double t;          /* ray parameter of the hit */
    double u, v;       /* surface parameters: (u, v) in the original patch, see each add call */
    double p[3];       /* hit point evaluated on the surface, S(u, v) */
    double p_error;    /* bound on the distance of p from the exact hit point: the scene
                          tolerance plus rounding; ppm_hit_spawn_ray steps over it */
    double ng[3];      /* unit geometric normal (dS/du x dS/dv; the limit normal where a
                          derivative vanishes); as stored, not flipped towards the ray */
    double ns[3];      /* unit shading normal (interpolated vertex normal on meshes) */
    uint32_t geom_id;  /* geometry id from the add call */
    uint32_t prim_id;  /* patch or triangle index within the geometry; 0 for the other shapes */
    uint32_t material; /* material id of the geometry */
    uint32_t reserved; /* 0 */
} ppm_hit;

/* Closest hit of each of `count` rays, written to hits[i]; count 0 does nothing and succeeds.
 * Every ray is checked before any hit is written. Large batches run on the context's worker
 * threads. Errors: INVALID_ARGUMENT (NULL, a ray with NaN/Inf origin, zero or non-finite
 * direction, tnear < 0 or tnear > tfar: the message names the first bad index),
 * INVALID_OPERATION (scene not committed). Thread safe on a committed scene. */
PPM_API ppm_status ppm_scene_intersect(ppm_scene scene, const ppm_ray *rays, size_t count, ppm_hit *hits);

/* Whether each ray hits anything in [tnear, tfar]: occluded[i] = 1 or 0. Same rules. */
PPM_API ppm_status ppm_scene_occluded(ppm_scene scene, const ppm_ray *rays, size_t count, uint8_t *occluded);

/* A ray leaving a hit point in direction `dir` (either side of the surface) that does not
 * hit the surface at its own origin: the origin is moved off the surface by twice p_error
 * along ng, on the side `dir` points to; tnear = 0, tfar = INFINITY.
 * Real surfaces closer than that bound (about tolerance * diagonal) are not seen.
 * Pure function of its arguments; thread safe. Errors: INVALID_ARGUMENT (NULL, dir zero or
 * not finite, a miss, a hit with a NaN or infinite point, normal or p_error). */
PPM_API ppm_status ppm_hit_spawn_ray(const ppm_hit *hit, const double dir[3], ppm_ray *out_ray);

/* ---------------------------------------------------------------------------------------- */
/* Tessellation: triangle meshes from Bezier patches (no context or scene needed)            */
/* ---------------------------------------------------------------------------------------- */

/* The result of a tessellation: immutable, reference counted like every handle. */
typedef struct ppm_mesh_t *ppm_mesh;

/* Tessellates bicubic Bezier patches (control points laid out as in
 * ppm_scene_add_bezier_patches) into triangles. The caller owns the one reference returned.
 *  - grid > 0: uniform, grid x grid quads per patch in (u, v), two triangles each (split
 *    along the diagonal whose midpoint lies closer to the surface): exactly
 *    2 * grid^2 * patch_count triangles. `tolerance` is ignored. At a collapsed edge half of
 *    the first row's triangles have zero area, as in any uniform grid.
 *  - grid == 0: adaptive. Every point of every triangle lies within `tolerance` (absolute,
 *    finite, > 0) of the surface, as measured: each triangle is sampled on a barycentric grid,
 *    each sample mapped to its patch's (u, v) by interpolating the vertex uvs, and its distance
 *    to the patch found by Newton steps for the nearest point; patches that exceed the
 *    tolerance are refined until none does. Triangles are spent where the surface bends: each
 *    patch gets its own grid density per direction, and each patch edge a segment count
 *    computed from that edge's curve alone, so patches that share an edge (the same four
 *    control points, in either direction) agree on its vertices and the mesh has no cracks
 *    there (an edge that meets parts of two other patches, a T-junction, is not stitched).
 *    A collapsed edge (four equal control points, e.g. an apex) becomes one point with a fan
 *    of triangles around it: no triangle has zero area. The result is deterministic.
 * Vertices: each vertex belongs to one patch and carries that patch's (u, v) and its unit
 * geometric normal (the limit normal on a collapsed edge), so a point on a seam is repeated
 * once per patch (and an apex once per fan triangle), always at a bit-identical position.
 * ppm_mesh_get_welded_vertices numbers the distinct positions; through it, every edge of the
 * mesh is shared by exactly two triangles except along the patches' free borders.
 * Triangles are counter-clockwise in (u, v): their winding normal agrees with dS/du x dS/dv.
 * Errors: INVALID_ARGUMENT (NULL, patch_count 0 or above 10 000 000, a NaN or infinite
 * coordinate naming the patch, tolerance not finite or <= 0 when grid == 0, grid > 4096, or
 * a request estimated to need more than 200 000 000 triangles: refused before allocating),
 * UNSUPPORTED (refinement could not reach the tolerance: it is below what double precision
 * resolves on these patches, or a patch folds so sharply that the nearest-point search stalls).
 * Thread safe; large requests use all hardware threads. */
PPM_API ppm_status ppm_tessellate_patches(const double *control_points, size_t patch_count, double tolerance,
                                          uint32_t grid, ppm_mesh *out_mesh);

/* Adds / drops a reference (atomic: thread safe). Pointers returned by the getters stay valid
 * until the last reference is released. Every mesh call fails with INVALID_ARGUMENT for a
 * NULL mesh (or a NULL output that is not documented as optional). */
PPM_API ppm_status ppm_mesh_retain(ppm_mesh mesh);
PPM_API void ppm_mesh_release(ppm_mesh mesh);

/* Vertex arrays owned by the mesh: positions and normals 3 doubles per vertex, uvs 2 (the
 * vertex's patch parameters). Any output pointer may be NULL if not wanted. Thread safe. */
PPM_API ppm_status ppm_mesh_get_vertices(ppm_mesh mesh, const double **out_positions, const double **out_normals,
                                         const double **out_uvs, size_t *out_vertex_count);

/* Triangles: 3 vertex indices each (into the arrays of ppm_mesh_get_vertices). Either output
 * may be NULL. Thread safe. */
PPM_API ppm_status ppm_mesh_get_triangles(ppm_mesh mesh, const uint32_t **out_indices, size_t *out_triangle_count);

/* For each triangle, the index of the patch it approximates. Thread safe. */
PPM_API ppm_status ppm_mesh_get_triangle_patches(ppm_mesh mesh, const uint32_t **out_patch_ids);

/* For each vertex, a welded index in 0 .. welded_count - 1 (numbered in order of first
 * appearance): vertices on patch borders at bit-identical positions share one, every other
 * vertex has its own. Replacing each triangle's vertex indices by these gives the welded,
 * crack-free mesh (as an OBJ file's v/vt/vn triples do). Either output may be NULL. Thread
 * safe. */
PPM_API ppm_status ppm_mesh_get_welded_vertices(ppm_mesh mesh, const uint32_t **out_welded_ids,
                                                size_t *out_welded_count);

/* Floating-point properties of a mesh. Keys:
 *   "max_deviation"  the largest distance from a triangle to the surface that the measurement
 *                    described at ppm_tessellate_patches found (uniform grids are measured too)
 *   "tolerance"      the requested tolerance; 0 for a uniform grid
 * Errors: INVALID_ARGUMENT (NULL, unknown key). Thread safe. */
PPM_API ppm_status ppm_mesh_get_double(ppm_mesh mesh, const char *key, double *out_value);

/* ---------------------------------------------------------------------------------------- */
/* Materials, textures and lights (Mitsuba 3 names and units)                               */
/* ---------------------------------------------------------------------------------------- */

/* Materials, textures and lights are made by type name and named parameters, as Mitsuba 3's
 * load_dict takes them (ppm_scene_add_material, ppm_scene_add_texture, ppm_scene_add_light);
 * the typed calls after them are shorthands for the most common types. Materials, textures
 * and lights are numbered apart, each from 0 in the order they are added, by the named calls
 * and the shorthands alike; each add call writes the new id to its last argument, which may
 * be NULL.
 * Materials: ppm_scene_set_geometry_material assigns one to a geometry. A scene without any
 * material renders everything as diffuse grey 0.5; once it has materials, every geometry's id
 * must name one (checked when a renderer is created). Colours are linear RGB; reflectances
 * lie in [0, 1] per channel, indices of refraction are finite and > 0. All opaque materials
 * are two-sided.
 * Lights: intensities, radiances and irradiances are finite, >= 0 and at most 1e20 per
 * channel; positions obey the coordinate limit. An area light is not added here: it is
 * emission on a geometry (ppm_scene_set_geometry_emission, at the end of this section).
 * A renderer copies the materials, textures and lights when it is created; later additions
 * do not reach it, and none of these calls marks the scene uncommitted. They change the
 * scene all the same: the thread rules of Geometry above apply.
 * Errors: INVALID_ARGUMENT naming the bad value (or the NULL scene or argument). */

/* Named parameters: `type` and every parameter name are Mitsuba 3's (docs/scene-format.md
 * lists the types and their parameters), and a parameter left out takes Mitsuba's default.
 * New types and parameters arrive without changing the ABI. A parameter is one of:
 *   PPM_PARAM_NUMBERS   `count` doubles at `numbers`: 1 for a float, an integer or a boolean
 *                       (0 or 1), 3 for an RGB colour, a point or a vector, 16 for a 4x4
 *                       transform in row-major order (`to_world`, `to_uv`); a colour may
 *                       also be given as 1 number (grey);
 *   PPM_PARAM_STRING    `string`: a name (`distribution`, `material`) or a file name;
 *   PPM_PARAM_MATERIAL  `id`: a material of this scene (the nested BSDFs of `blendbsdf`,
 *                       `mask`, `twosided`);
 *   PPM_PARAM_TEXTURE   `id`: a texture of this scene, for a colour or float parameter that
 *                       takes one (`reflectance`, `weight`, ...).
 * Zero-initialise unused fields. Every parameter given must be used by the type: an unknown
 * name, a repeated one, or one of the wrong kind is an error naming it (with a suggestion for
 * a likely misspelling), so that nothing is silently ignored. Ownership: nothing is kept of
 * `params` or its strings after the call.
 * Errors: INVALID_ARGUMENT (NULL scene or type, a parameter without a name; unknown type or
 * parameter; a value out of range, naming the parameter), IO (a file that cannot be read,
 * named). */
typedef enum ppm_param_type {
    PPM_PARAM_NUMBERS = 0,
    PPM_PARAM_STRING = 1,
    PPM_PARAM_MATERIAL = 2,
    PPM_PARAM_TEXTURE = 3
} ppm_param_type;

typedef struct ppm_param {
    const char *name; /* Mitsuba's parameter name, e.g. "alpha", "eta", "filename" */
    ppm_param_type type;
    const double *numbers; /* PPM_PARAM_NUMBERS */
    size_t count;
    const char *string; /* PPM_PARAM_STRING */
    uint32_t id;        /* PPM_PARAM_MATERIAL, PPM_PARAM_TEXTURE */
} ppm_param;

/* A material. Types: `diffuse`, `conductor` (a perfect mirror unless `material` or `eta`/`k`
 * is given), `roughconductor`, `dielectric`, `thindielectric`, `roughdielectric`, `plastic`,
 * `roughplastic`, `twosided` (a copy of its `bsdf`: opaque materials are two-sided already),
 * `blendbsdf` and `mask`. */
PPM_API ppm_status ppm_scene_add_material(ppm_scene scene, const char *type, const ppm_param *params,
                                          size_t param_count, uint32_t *out_material_id);
/* A texture for the colour parameters of materials (`reflectance`, `specular_reflectance`,
 * `diffuse_reflectance`) and their weights (`weight` of blendbsdf, `opacity` of mask: the
 * texture's luminance). Types: `bitmap` (an image file read now through OpenImageIO, any
 * format it reads; 8/16-bit images are decoded from sRGB to linear unless `raw`, float images
 * taken as linear) and `checkerboard`. A hit's texture coordinates (s, t) are the hit (u, v)
 * of spheres, quads, disks and cylinders (as their add calls define them) and of patches
 * (mapped into a patch set's rectangles by ppm_scene_set_patch_uv_rects), and the
 * interpolated vertex uvs of meshes (the hit's barycentric (u, v) on a mesh without uvs); the
 * texture is looked up at `to_uv` applied to (s, t), with v = 0 the image's top row (as in
 * Mitsuba 3). Errors also: INVALID_ARGUMENT for an image of more than 2^28 pixels or with a
 * NaN, infinite or negative texel, PARSE for a header that claims more pixels than the file's
 * bytes can hold. */
PPM_API ppm_status ppm_scene_add_texture(ppm_scene scene, const char *type, const ppm_param *params, size_t param_count,
                                         uint32_t *out_texture_id);
/* A light that is not a shape. Types: `point`, `spot` (shining along +z of `to_world`),
 * `constant` and `envmap` (environment lights: what rays leaving the scene see) and
 * `directional`. */
PPM_API ppm_status ppm_scene_add_light(ppm_scene scene, const char *type, const ppm_param *params, size_t param_count,
                                       uint32_t *out_light_id);
/* A shape with Mitsuba 3's names: `sphere` (center, radius), `rectangle`, `disk`, `cylinder`
 * (p0, p1, radius), `cube`, `obj`, `ply`, `serialized` (filename, shape_index), and libppm's
 * `quad` (origin, edge_u, edge_v) and `bezier` (filename of a .bpt file, or patches: 48
 * numbers per patch; uv_rects: 4 per patch). Every type takes `to_world` (16 numbers,
 * row-major; default the identity) and `bsdf` (PPM_PARAM_MATERIAL); all but sphere and
 * bezier take `flip_normals`; mesh files take `face_normals`. Parameters and their defaults
 * are listed in docs/scene-format.md. The shape becomes one geometry, whose id goes to
 * *out_geom_id (may be NULL); it is placed and oriented as Mitsuba places it (a mirroring
 * to_world keeps Mitsuba's normal). Every parameter is checked before the geometry is added,
 * except a `uv_rects` count that does not match the patches of a .bpt file, which is known
 * only once the file is read (the geometry is then left in the scene). The typed calls above
 * (ppm_scene_add_sphere, _quad, _disk, _cylinder, _triangle_mesh, ppm_scene_load_*) are the
 * same geometries with explicit arguments. Ownership: nothing is kept of `params` or its
 * strings after the call. Thread rules: as for the other calls that build a scene (not
 * during any other call on it). Errors: as ppm_scene_add_material (a material id that names
 * no material too), and IO and PARSE for files. */
PPM_API ppm_status ppm_scene_add_shape(ppm_scene scene, const char *type, const ppm_param *params, size_t param_count,
                                       uint32_t *out_geom_id);

/* The types a kind of plugin has, in a fixed order: kind "material", "texture", "light" and
 * "shape" (the types of ppm_scene_add_material, _texture, _light and _shape, which the scene
 * file readers accept too) or "mode" (the renderer's "mode" setting). *out_name is a static
 * string, valid for the life of the library. Thread rules: any thread, any time.
 * Errors: INVALID_ARGUMENT (NULL kind or output, unknown kind, index >= count). */
PPM_API ppm_status ppm_type_count(const char *kind, size_t *out_count);
PPM_API ppm_status ppm_type_name(const char *kind, size_t index, const char **out_name);

/* Shorthands. Each call below is ppm_scene_add_material or ppm_scene_add_light with the type
 * and parameters it names: it makes the same material or light, accepts and refuses the same
 * values (its messages name the C argument), and takes the next id of the same sequence. Its
 * arguments have no defaults; where Mitsuba has one, it is given for reference. */
/* Lambertian: "diffuse" with `reflectance` (3 numbers). */
PPM_API ppm_status ppm_scene_add_diffuse_material(ppm_scene scene, const double reflectance[3],
                                                  uint32_t *out_material_id);
/* Perfect mirror tinted by `specular_reflectance`: "conductor" with `specular_reflectance` (3
 * numbers) and nothing else (`material` "none", no eta or k). */
PPM_API ppm_status ppm_scene_add_mirror_material(ppm_scene scene, const double specular_reflectance[3],
                                                 uint32_t *out_material_id);
/* Smooth glass with exact Fresnel: "dielectric" with `int_ior` and `ext_ior` (Mitsuba's
 * defaults 1.5046 and 1.000277). The surface normal must point outwards (to ext_ior). */
PPM_API ppm_status ppm_scene_add_dielectric_material(ppm_scene scene, double int_ior, double ext_ior,
                                                     uint32_t *out_material_id);
/* Diffuse base under a smooth dielectric coat, like glazed porcelain: "plastic" with
 * `diffuse_reflectance` (3 numbers), `int_ior` and `ext_ior` (Mitsuba's defaults 1.49 and
 * 1.000277). The named-parameter form also takes `nonlinear` (Mitsuba's: false). */
PPM_API ppm_status ppm_scene_add_coated_material(ppm_scene scene, const double diffuse_reflectance[3], double int_ior,
                                                 double ext_ior, uint32_t *out_material_id);

/* Gives a material an image texture that replaces its colour: the effect of giving its colour
 * parameter (`reflectance` of diffuse, `specular_reflectance` of conductor and roughconductor,
 * `diffuse_reflectance` of plastic and roughplastic) the texture of ppm_scene_add_texture
 * "bitmap" with `filename` = path and a `to_uv` of u = s * scale[0] + offset[0],
 * v = t * scale[1] + offset[1] (the other bitmap parameters at their defaults: bilinear,
 * repeat, sRGB-decoded). Unlike that, it changes a material made already, in place (its id
 * and the geometries that use it stay), and takes no texture id. scale and offset may be NULL
 * for (1, 1) and (0, 0). Errors: INVALID_ARGUMENT (bad id; glass (dielectric,
 * thindielectric, roughdielectric), which has no colour; a blendbsdf or mask, whose parts
 * are textured instead; non-finite or zero scale, non-finite offset; an image as refused by
 * ppm_scene_add_texture), IO (unreadable or truncated file; the message names it), PARSE (as
 * ppm_scene_add_texture). */
PPM_API ppm_status ppm_scene_set_material_texture(ppm_scene scene, uint32_t material_id, const char *path,
                                                  const double scale[2], const double offset[2]);

/* Point light, `intensity` in W/sr per channel, power 4 pi intensity: "point" with `position`
 * and `intensity`. */
PPM_API ppm_status ppm_scene_add_point_light(ppm_scene scene, const double position[3], const double intensity[3],
                                             uint32_t *out_light_id);
/* Spot light: `intensity` in W/sr on the axis from position to target, full out to
 * beam_width degrees and falling linearly in angle to 0 at cutoff_angle degrees
 * (0 < beam_width <= cutoff_angle <= 180; Mitsuba's defaults: cutoff_angle 20, beam_width
 * 3/4 of it). It is
 * "spot" with `intensity`, `cutoff_angle`, `beam_width` and a `to_world` that takes the
 * origin to position and +z along target - position (such as look_at(position, target, up)
 * for any up: only the axis matters). The named call finds the axis as the difference of the
 * points to_world gives for (0, 0, 1) and the origin, so for the same position and target
 * the two axes may differ by the rounding of that difference. */
PPM_API ppm_status ppm_scene_add_spot_light(ppm_scene scene, const double position[3], const double target[3],
                                            const double intensity[3], double cutoff_angle, double beam_width,
                                            uint32_t *out_light_id);

/* Maps one texture across a whole patch set: patch i's (u, v) in [0, 1]^2 maps linearly onto
 * [rects[4i], rects[4i+2]] x [rects[4i+1], rects[4i+3]] in texture space (4 * patch count
 * finite doubles), the texture coordinates (s, t) of its hits. Errors: INVALID_ARGUMENT (not a
 * patch geometry, NULL, NaN). */
PPM_API ppm_status ppm_scene_set_patch_uv_rects(ppm_scene scene, uint32_t geom_id, const double *rects);

/* Makes a quad, sphere, disk, cylinder or triangle mesh an area light (Mitsuba `area`; it has
 * no named form and no light id): constant `radiance` (W/(m^2 sr) per channel) on the side
 * the normal points to (quad: edge_u x edge_v; sphere and cylinder: outside; disk:
 * axis_u x axis_v; mesh: the shading normal, i.e. the interpolated vertex normal where the
 * mesh has normals, else the face normal (p1 - p0) x (p2 - p0)), reversed by
 * ppm_scene_set_geometry_flip_normals. Power pi L A with A the exact area (a mesh's: the sum
 * of its triangles'). A mesh light samples points uniformly in area (a table over its
 * triangles, made when rendering starts) and shares the mesh's data without copying it.
 * Black turns it off. Errors: INVALID_ARGUMENT (a Bezier patch set: patches cannot be area
 * lights; negative, NaN or too large values). */
PPM_API ppm_status ppm_scene_set_geometry_emission(ppm_scene scene, uint32_t geom_id, const double radiance[3]);

/* ---------------------------------------------------------------------------------------- */
/* Rendering: photon mapping and vertex connection and merging                               */
/* ---------------------------------------------------------------------------------------- */

/* A renderer renders a committed scene through a camera, one pass at a time
 * (ppm_renderer_render_pass); the image is the estimate of all passes so far and converges as
 * they grow. Its "mode" setting chooses the method:
 *  - the photon modes: a pass is an eye pass (camera paths to their visible points, direct
 *    light there by shadow rays) and a photon pass (photon paths from the lights, gathered at
 *    the visible points within their radii):
 *      "sppm"  stochastic progressive photon mapping (Hachisuka and Jensen 2009): a new
 *              jittered camera path per pixel every pass; each pixel's radius shrinks with
 *              the photons its earlier passes found;
 *      "ppm"   progressive photon mapping (Hachisuka, Ogaki and Jensen 2008): the visible
 *              points of the first pass, split at glass and coats, stay for every pass,
 *              whose eye pass only estimates their direct light again;
 *      "pppm"  probabilistic progressive photon mapping (Knaus and Zwicker 2011): SPPM's eye
 *              pass, with a radius that depends on the pass index only;
 *  - the bidirectional modes: a pass traces light subpaths (paths_per_pass of them), stores
 *    their vertices and connects them to the camera (light tracing; not through a thin
 *    lens), then one camera subpath per pixel, which samples the lights, connects to a light
 *    subpath's vertices and merges with the light vertices within the pass's radius, every
 *    technique weighted by multiple importance sampling:
 *      "vcm"   vertex connection and merging (Georgiev et al. 2012): all of it; the default,
 *              which had the least error at equal time on the benchmark scenes
 *              (docs/bench/converge.md);
 *      "bpt"   its connections only: bidirectional path tracing;
 *      "vm"    its merging only, at the camera subpath's first non-specular vertex: photon
 *              mapping on light subpaths, direct light included.
 * pppm, vcm, bpt and vm are pass-independent: each pass stands alone, so passes may be
 * rendered apart and merged (partial renders, below). */

typedef struct ppm_renderer_t *ppm_renderer;

/* Look-at camera with Mitsuba 3's conventions (`perspective` / `thinlens` sensors with
 * to_world = look_at(origin, target, up)): `fov` is the full angle in degrees along the
 * image's x axis; image x grows to the right, y down; pixels are square. aperture_radius 0
 * is a pinhole; a thin lens (aperture_radius > 0) focuses on the plane at focus_distance
 * along the view axis.
 * This first camera struct has no size field and cannot grow: it stays for programs built
 * against it (ppm_renderer_create, ppm_scene_file_get_camera). New code uses ppm_camera_v2,
 * whose fields mean the same. */
typedef struct ppm_camera {
    double origin[3];
    double target[3];
    double up[3];
    double fov;             /* degrees, in (0, 180) */
    uint32_t width, height; /* pixels, each in 1 .. 2^28 */
    double aperture_radius; /* scene units, >= 0 */
    double focus_distance;  /* scene units, > 0 when aperture_radius > 0 */
    double near_clip;       /* scene units, >= 0: rays start on the plane this far along the
                               view axis (Mitsuba's near_clip, whose default is 0.01); 0 = at
                               the lens */
} ppm_camera;

/* The camera as a struct that can grow (see "Growth" at the top of this header). Fill it
 * with ppm_camera_v2_init, which sets `size` and the defaults, then set the fields wanted:
 *     ppm_camera_v2 camera;
 *     ppm_camera_v2_init(&camera);
 *     camera.width = 640; camera.height = 480; ...
 * The library reads (ppm_renderer_create_v2) or writes (ppm_scene_file_get_camera_v2,
 * ppm_renderer_get_camera_v2) only the first `size` bytes. A size below that of this first
 * version is INVALID_ARGUMENT; a larger size from a newer header is accepted when every
 * byte this library does not know is 0 (a newer field left at its "as before" value), and
 * is UNSUPPORTED otherwise, naming the first such byte's offset. `reserved` must be 0. */
/* ppm_camera_v2's pixel filters. */
#define PPM_PIXEL_FILTER_BOX 0u
#define PPM_PIXEL_FILTER_TENT 1u
#define PPM_PIXEL_FILTER_GAUSSIAN 2u

typedef struct ppm_camera_v2 {
    size_t size;            /* sizeof(ppm_camera_v2) as the caller compiled it */
    double origin[3];       /* default (0, 0, 0) */
    double target[3];       /* default (0, 0, 1) */
    double up[3];           /* default (0, 1, 0) */
    double fov;             /* degrees along x, in (0, 180); default 39.597752709049864 */
    uint32_t width, height; /* pixels, each in 1 .. 2^28; no default (0 is refused) */
    double aperture_radius; /* scene units, >= 0; default 0 (pinhole) */
    double focus_distance;  /* scene units, > 0 when aperture_radius > 0; default 0 */
    double near_clip;       /* scene units, >= 0; default 0.01 (0: rays start at the lens) */
    /* Crop window: only the pixels [crop_x0, crop_x1) x [crop_y0, crop_y1) of the width x
     * height image are rendered, projected as in the whole image; the renderer's image is
     * crop_x1 - crop_x0 by crop_y1 - crop_y0 pixels. 0 <= x0 < x1 <= width and
     * 0 <= y0 < y1 <= height; all four 0 (default): the whole image. */
    uint32_t crop_x0, crop_y0, crop_x1, crop_y1;
    /* Principal point offset (Mitsuba's perspective principal_point_offset_x / _y), a
     * shifted lens: pixel (x, y) sees what pixel (x + offset_x width, y + offset_y height)
     * of the centred camera sees (x to the right, y down the image); fractions of the film's
     * size, finite, default 0 (centred). */
    double principal_point_offset_x, principal_point_offset_y;
    /* Pixel reconstruction filter, Mitsuba's: PPM_PIXEL_FILTER_BOX (0, default: the pixel
     * itself), _TENT (1 - |x| / radius) or _GAUSSIAN (exp(-x^2 / (2 stddev^2)) minus its
     * value at 4 stddev, Mitsuba's default filter); pixel_filter_parameter is the tent's
     * radius or the gaussian's stddev in pixels, in (0, 16], 0 for Mitsuba's default (1 and
     * 0.5). A pixel is the filter-weighted mean of the image around its centre, within the
     * image; camera paths sample the filter and light tracing splats to every pixel it
     * reaches, in every mode. */
    uint32_t pixel_filter;
    uint32_t reserved_pad; /* 0 */
    double pixel_filter_parameter;
    uint64_t reserved[2]; /* room for fields to come without changing size; 0 */
} ppm_camera_v2;

/* Sets *camera to the defaults above, `size` to sizeof(ppm_camera_v2) and every other byte
 * to 0. Inline, so that `size` is the struct size of the header the caller compiles with. */
static inline void ppm_camera_v2_init(ppm_camera_v2 *camera) {
    unsigned char *bytes = (unsigned char *)camera;
    size_t i;
    for (i = 0; i < sizeof *camera; ++i) bytes[i] = 0;
    camera->size = sizeof *camera;
    camera->target[2] = 1;
    camera->up[1] = 1;
    /* Mitsuba 3's perspective sensor defaults, which scene files and Python share: the fov
     * of a 50 mm lens on 36 mm film, and its near clip. */
    camera->fov = 39.597752709049864;
    camera->near_clip = 0.01;
}

/* A renderer for a committed scene seen through `camera`. The caller owns the one reference
 * returned; the renderer holds one on the scene (and so on its context). Lights, materials,
 * textures and emission are read now; later changes to them do not reach it. The scene may
 * be queried while renderers of it exist. After a change to its geometry their passes fail
 * (INVALID_OPERATION) until it is committed again. A renderer knows only the geometries the
 * scene had when it was made: after adding one, make a new renderer, and run no pass on the
 * old one. Errors: INVALID_ARGUMENT (NULL, a bad camera field naming it, a geometry without
 * a valid material, emission on a kind that cannot emit), INVALID_OPERATION (scene not
 * committed). */
PPM_API ppm_status ppm_renderer_create(ppm_scene scene, const ppm_camera *camera, ppm_renderer *out_renderer);
/* The same from an extensible camera; errors also as described at ppm_camera_v2. */
PPM_API ppm_status ppm_renderer_create_v2(ppm_scene scene, const ppm_camera_v2 *camera, ppm_renderer *out_renderer);
/* The renderer's camera into *out_camera, whose `size` the caller sets (ppm_camera_v2_init);
 * the library writes that many bytes (0 beyond the fields it knows) and leaves `size`.
 * Errors: INVALID_ARGUMENT (NULL, size too small). Thread safe, also during a pass. */
PPM_API ppm_status ppm_renderer_get_camera_v2(ppm_renderer renderer, ppm_camera_v2 *out_camera);
/* Adds / drops a reference (atomic: thread safe). Releasing the last reference while a pass
 * runs, or while another thread still uses the renderer, is the caller's error. The scene is
 * released with the renderer's last reference. Errors (retain): INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_renderer_retain(ppm_renderer renderer);
PPM_API void ppm_renderer_release(ppm_renderer renderer);

/* Settings (defaults):
 *   "mode"                  string "sppm", "ppm", "pppm", "vcm", "bpt" or "vm": the method,
 *                           described at the top of this section              default "vcm"
 *   "photons_per_pass"      int    photon paths (photon modes) or light subpaths
 *                           (bidirectional modes) per pass, 1 .. 2^31; 0 = automatic:
 *                           6 photon paths per pixel within [10^4, 2^22], or one
 *                           light subpath per pixel up to 2^18 (read "paths_per_pass")
 *                                                                             default 0
 *   "alpha"                 double radius reduction in (0, 1]                 default 2/3
 *   "initial_radius"        double the first pass's gather or merge radius, in scene
 *                           units in [0, 1e12]; 0 = automatic                 default 0
 *   "initial_radius_pixels" double the automatic radius in pixel footprints, in (0, 1e6]:
 *                           at each pixel's first visible point (photon modes), at the
 *                           distance from the camera to the scene's centre
 *                           (bidirectional modes)                             default 1
 *   "max_depth"             int    scattering events per camera, photon or light path,
 *                           1 .. 1000                                         default 16
 *   "seed"                  int    random sequence                            default 0
 *   "hit_point_search"      string "grid" (hashed) or "kdtree" (nanoflann): how photons
 *                           find visible points; both find the same           default "grid"
 *   "direct_lighting"       int    1: light sources by shadow rays; 0: by photons too
 *                                                                             default 1
 *   "glossy_gather_alpha"   double rough lobes with alpha >= this are gathered at
 *                           visible points, narrower ones followed like mirrors, >= 0
 *                                                                             default 0.2
 * The last three are the photon modes' only: the bidirectional modes store no visible
 * points, and weigh next-event estimation against the other techniques themselves.
 * Typed settings as described at the top of this header. mode, seed, direct_lighting,
 * glossy_gather_alpha and the initial radius settings are fixed after the first pass
 * (INVALID_OPERATION), in the pass-independent modes photons_per_pass, alpha and max_depth
 * too; unknown keys, wrong types and values out of range are INVALID_ARGUMENT.
 * Read-only ints:
 *   "passes"            passes completed (in a pass-independent mode: held, merged ones too)
 *   "photons_emitted"   photon paths or light subpaths traced by those passes
 *   "paths_per_pass"    the paths a pass traces: photons_per_pass, or its automatic count
 *                       for this image and mode
 *   "width", "height"   the image rendered (the crop window's size, if the camera has one)
 *   "lights"            the light sources the renderer read from the scene: every light of
 *                       ppm_scene_add_light and its shorthands, black ones included, and
 *                       every geometry with non-black emission; 0 renders black
 * Read-only doubles, the wall-clock seconds of the last completed pass:
 *   "last_eye_pass_seconds"      photon modes: its eye pass, the search build included;
 *                                bidirectional modes: the whole pass
 *   "last_photon_pass_seconds"   photon modes: its photon pass; 0 in the bidirectional modes
 *   "last_search_build_seconds"  photon modes: the part of the eye pass spent building the
 *                                visible points' search; 0 in the bidirectional modes
 * Thread safety: setters not during a pass of the same renderer; getters concurrently with
 * other getters, and the read-only values also during a pass (the state after the last
 * completed pass, zeros before the first). */
PPM_API ppm_status ppm_renderer_set_int(ppm_renderer renderer, const char *key, int64_t value);
PPM_API ppm_status ppm_renderer_set_double(ppm_renderer renderer, const char *key, double value);
PPM_API ppm_status ppm_renderer_set_string(ppm_renderer renderer, const char *key, const char *value);
PPM_API ppm_status ppm_renderer_get_int(ppm_renderer renderer, const char *key, int64_t *out_value);
PPM_API ppm_status ppm_renderer_get_double(ppm_renderer renderer, const char *key, double *out_value);
/* Writes the string setting into out (NUL-terminated, truncated to capacity) and its full
 * length to *out_length when out_length is not NULL. `out` may be NULL when capacity is 0,
 * to ask for the length only. */
PPM_API ppm_status ppm_renderer_get_string(ppm_renderer renderer, const char *key, char *out, size_t capacity,
                                           size_t *out_length);

/* Runs one pass on the context's threads and adds it to the image. In the photon modes: an
 * eye pass, a photon pass of paths_per_pass photon paths, and the update of every pixel's
 * statistics (sppm, ppm) or of the pass sums (pppm); in the bidirectional modes:
 * paths_per_pass light subpaths, then one camera subpath per pixel. In a pass-independent
 * mode the pass rendered is the lowest index the renderer does not hold yet (merged
 * partials count). Deterministic: the image after n passes depends only on the scene,
 * camera and settings, not on the thread count. Errors: CANCELLED (ppm_renderer_cancel was
 * called before or during the pass; the pass is discarded and the image unchanged),
 * INVALID_OPERATION (another pass of this renderer is running, or the scene was changed and
 * not committed again), OUT_OF_MEMORY, INVALID_ARGUMENT (NULL). Different renderers may run
 * passes at once (they share the context's threads). */
PPM_API ppm_status ppm_renderer_render_pass(ppm_renderer renderer);
/* Alias of ppm_renderer_render_pass: the same function under its libppm 0.1 name. */
PPM_API ppm_status ppm_render_pass(ppm_renderer renderer);

/* Stops the running pass as soon as possible, or the next pass if none runs. Thread safe;
 * the only renderer call that may overlap a pass besides the readers below.
 * Errors: INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_renderer_cancel(ppm_renderer renderer);

/* Copies an image layer after the last completed pass into `out`, row-major from the
 * top-left pixel (zeros before the first pass):
 *   "radiance"  3 floats per pixel: linear RGB radiance, W/(m^2 sr);
 *   "radius"    1 float, scene units: sppm and ppm: the pixel's gather radius now (the
 *               largest of its visible points'); pppm: its gather radius, and the
 *               bidirectional modes: the merge radius, as the mean over the passes;
 *   "photons"   1 float: sppm and ppm: the pixel's alpha-reduced photon count N; pppm: the
 *               photons its passes gathered; vcm and vm: the light vertices its passes
 *               merged (0 in bpt, which does not merge).
 * `count` is the number of floats `out` holds; it must be at least width * height *
 * channels. Errors: INVALID_ARGUMENT (NULL, unknown layer, count too small). Thread safe,
 * also during a pass. */
PPM_API ppm_status ppm_renderer_get_layer(ppm_renderer renderer, const char *layer, float *out, size_t count);

/* Checkpoints: the renderer's whole progressive state (pass count, photons emitted, every
 * pixel's statistics; in a pass-independent mode, once a pass has run, its partial render,
 * below) in a versioned binary file, so that a long render can stop and go on later. A
 * render resumed from a checkpoint and run to n passes gives the same image, bit for bit, as
 * an uninterrupted render of n passes with the same scene, camera, settings and seed.
 *
 * save writes the state after the last completed pass atomically (a temporary file beside
 * `path`, then rename), so `path` holds either the old or the new checkpoint, never a torn
 * one; it may run during a pass. load replaces the state of a renderer that has not run a
 * pass yet; the checkpoint must come from the same scene, camera and fixed settings, which
 * it records (mode, seed, direct_lighting and the initial radius; a partial records the
 * render's whole identity, below).
 * Errors: IO (cannot write or read `path`), PARSE (not a libppm checkpoint, another version,
 * truncated or corrupt: the message says which), INVALID_ARGUMENT (a checkpoint of another
 * scene, camera or settings: the message names what differs), INVALID_OPERATION (load after
 * a pass has run), INVALID_ARGUMENT (NULL). Thread safety: save may overlap a pass and other
 * readers; load must not overlap any other call on the renderer. */
PPM_API ppm_status ppm_renderer_save_checkpoint(ppm_renderer renderer, const char *path);
PPM_API ppm_status ppm_renderer_load_checkpoint(ppm_renderer renderer, const char *path);

/* Partial renders: passes of one render in a pass-independent mode ("pppm", "vcm", "bpt",
 * "vm"), rendered by any number of processes in any order, and merged exactly. In "pppm"
 * mode pass i uses the gather radius r_i^2 = r_0^2 prod_{k=1..i} (k - 1 + alpha) / k (Knaus
 * and Zwicker 2011), in the others the merge radius r_i = r_0 (i + 1)^((alpha - 1) / 2), and
 * random numbers drawn from (seed, i) only; the image is the mean of the passes' estimates,
 * each rounded once to a multiple of 2^-40 and summed as 128-bit integers. So merging the
 * partials of passes 0..N-1 gives the same bits as one process rendering N passes, whatever
 * the split, the order and the thread counts. A partial records the render's identity
 * (image size, camera, scene, mode, seed, direct_lighting, initial radius, alpha,
 * paths_per_pass, max_depth, glossy_gather_alpha); partials of different renders or with a
 * pass in common do not merge. Checkpoints of a pass-independent render are partials, so
 * ppm_renderer_load_checkpoint takes them. */
typedef struct ppm_partial_t *ppm_partial;

/* Renders pass `pass_index` of a pass-independent render (ppm_renderer_render_pass renders
 * the lowest index not yet rendered). Errors as ppm_renderer_render_pass, and
 * INVALID_OPERATION (another mode, or the pass is rendered already), INVALID_ARGUMENT
 * (pass_index >= 2^32). */
PPM_API ppm_status ppm_renderer_render_pass_index(ppm_renderer renderer, uint64_t pass_index);
/* Alias of ppm_renderer_render_pass_index: the same function under its first name. */
PPM_API ppm_status ppm_render_pass_index(ppm_renderer renderer, uint64_t pass_index);
/* The renderer's passes so far as a new partial (the caller owns the one reference), or
 * saved to `path` atomically. On failure *out_partial is set to NULL. Errors:
 * INVALID_OPERATION (not pass-independent, or no pass completed), IO (save),
 * INVALID_ARGUMENT (NULL). Thread safe, also during a pass (the state after the last
 * completed pass). */
PPM_API ppm_status ppm_renderer_get_partial(ppm_renderer renderer, ppm_partial *out_partial);
PPM_API ppm_status ppm_renderer_save_partial(ppm_renderer renderer, const char *path);
/* Adds a partial's passes to the renderer's (e.g. to go on rendering other passes, or to read
 * the merged image through ppm_renderer_get_layer). Errors: INVALID_ARGUMENT (NULL, a partial
 * of another render: the message names what differs; a pass the renderer holds already: the
 * message names it), INVALID_OPERATION (not pass-independent, or during a pass). */
PPM_API ppm_status ppm_renderer_merge_partial(ppm_renderer renderer, ppm_partial partial);

/* A partial from a file written by ppm_renderer_save_partial / ppm_partial_save, or from
 * bytes of ppm_partial_serialize; the caller owns the one reference returned. On failure
 * *out_partial is set to NULL. Errors: IO (cannot read), PARSE (not a partial, another
 * version, truncated or corrupt: the message names the file and what is wrong),
 * OUT_OF_MEMORY, INVALID_ARGUMENT (NULL; data NULL with a nonzero size). */
PPM_API ppm_status ppm_partial_load(const char *path, ppm_partial *out_partial);
PPM_API ppm_status ppm_partial_load_memory(const void *data, size_t size, ppm_partial *out_partial);
/* Writes the partial to `path` atomically. Errors: IO, INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_partial_save(ppm_partial partial, const char *path);
/* The partial's file bytes in memory owned by the partial, valid until it changes (merge,
 * set) or is released. Errors: INVALID_ARGUMENT (NULL), OUT_OF_MEMORY. */
PPM_API ppm_status ppm_partial_serialize(ppm_partial partial, const void **out_data, size_t *out_size);
/* Adds the passes of `from` to `into` (from is unchanged). Errors: INVALID_ARGUMENT (NULL, the
 * same partial twice, another render's partial or overlapping passes: the message names both
 * partials' files and what differs or the first common passes; `into` is then unchanged). */
PPM_API ppm_status ppm_partial_merge(ppm_partial into, ppm_partial from);
/* Adds / drops a reference (atomic). Errors (retain): INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_partial_retain(ppm_partial partial);
PPM_API void ppm_partial_release(ppm_partial partial);
/* Read-only ints: "width", "height", "passes" (how many the partial holds), "photons_emitted",
 * "pass_ranges" (how many ranges ppm_partial_get_passes gives), "rejected" (pass estimates out
 * of the fixed-point range: NaN, negative, or 2^40 and more); read-write: "pass_total", the
 * render's planned pass count (0: not given; a merge keeps the larger), which tells which
 * passes are missing. Errors: INVALID_ARGUMENT (NULL, unknown key, pass_total not in
 * 0 .. 2^32). */
PPM_API ppm_status ppm_partial_get_int(ppm_partial partial, const char *key, int64_t *out_value);
PPM_API ppm_status ppm_partial_set_int(ppm_partial partial, const char *key, int64_t value);
/* The passes held, as sorted half-open ranges [first, end): out[2k], out[2k+1]. `capacity` is
 * the number of uint64_t that `out` holds (2 per range); *out_count gets the number of ranges,
 * also when the call fails for a capacity too small, so that `out` may be NULL with capacity
 * 0 to ask for the count. Errors: INVALID_ARGUMENT (NULL, capacity too small). */
PPM_API ppm_status ppm_partial_get_passes(ppm_partial partial, uint64_t *out, size_t capacity, size_t *out_count);
/* An image layer of the merged passes, as ppm_renderer_get_layer gives it: "radiance" (the
 * mean of the passes' estimates), "radius" (the mean gather or merge radius) or "photons"
 * (the photons gathered or light vertices merged in all passes). Errors: INVALID_ARGUMENT
 * (NULL, unknown layer, count too small). */
PPM_API ppm_status ppm_partial_get_layer(ppm_partial partial, const char *layer, float *out, size_t count);

/* ---------------------------------------------------------------------------------------- */
/* Images                                                                                    */
/* ---------------------------------------------------------------------------------------- */

/* An extra single-channel EXR layer: `name` is the channel name, `data` one float per pixel. */
typedef struct ppm_image_layer {
    const char *name;
    const float *data;
} ppm_image_layer;

/* Checks that ppm_image_write could write `path` before a long render finds out: a format it
 * writes (by the extension) in a folder that exists and may be written into. Errors:
 * INVALID_ARGUMENT (NULL, no or unknown extension), IO (no such folder, not a folder, no
 * permission: the message names the folder and the reason). */
PPM_API ppm_status ppm_image_check_path(const char *path);
/* Writes an image atomically (encoded in memory, written beside `path`, synced and renamed):
 * .exr and .hdr get linear float RGB radiance as given (EXR also the `layers`, zip
 * compressed); other formats (.png, .jpg, .tif, ...) 8-bit sRGB of the radiance scaled by
 * 2^exposure and clamped to [0, 1]. `radiance` is 3 floats per pixel, rows from the top.
 * Errors: INVALID_ARGUMENT (NULL, unknown format, size not in 1 .. 2^28 pixels, exposure not in
 * [-100, 100]), IO (cannot encode or write: the message names the path and the reason). */
PPM_API ppm_status ppm_image_write(const char *path, const float *radiance, uint32_t width, uint32_t height,
                                   const ppm_image_layer *layers, size_t layer_count, double exposure);

/* ---------------------------------------------------------------------------------------- */
/* Scene files (JSON or Mitsuba 3 XML; the formats: docs/scene-format.md)                    */
/* ---------------------------------------------------------------------------------------- */

typedef struct ppm_scene_file_t *ppm_scene_file;

/* Reads a scene file (JSON, or Mitsuba 3 XML by its extension ".xml" or content; see
 * ppm_scene_file_options): builds and commits its scene (shapes, materials, textures,
 * lights), and keeps its camera and render settings. Relative paths inside the file are
 * relative to the file's folder. Errors name the file, line, column and key
 * ("scene.json:14:9: bsdfs.glass.int_ior: expected a number > 0"): PARSE for JSON syntax,
 * wrong types, unknown keys and bad values; IO for a missing scene file or a missing file it
 * refers to (textures, OBJ, .bpt); INVALID_ARGUMENT for a NULL argument, and, still located,
 * for values the scene functions above refuse (degenerate geometry, coordinates or light
 * values beyond their limits, a scene whose every geometry is degenerate). The caller owns the
 * one reference returned; the file holds one on its scene, which holds one on the context.
 * Thread safe with respect to other objects of the same context. A loaded file is
 * immutable: every call below is thread safe. */
PPM_API ppm_status ppm_scene_file_load(ppm_context context, const char *path, ppm_scene_file *out_file);

/* How ppm_scene_file_load_v2 and ppm_scene_file_load_memory read a scene: a struct that can
 * grow (see "Growth"), filled by ppm_scene_file_options_init. ppm_scene_file_load reads
 * with these defaults. Besides libppm's JSON, the loaders read Mitsuba 3 XML scene files
 * (docs/scene-format.md lists what is supported), chosen by `format`. */
typedef struct ppm_scene_file_options {
    size_t size; /* sizeof(ppm_scene_file_options) as the caller compiled it */
    /* "json", "xml", or NULL (default): XML for a path ending in ".xml" or a text whose first
     * non-blank character is '<', JSON otherwise. */
    const char *format;
    /* Parameters of an XML file (Mitsuba's -D name=value): define_count names and values
     * that replace the file's <default name="..." value="..."/>. Giving any for a JSON file
     * is INVALID_ARGUMENT. Default none. */
    const char *const *define_names;
    const char *const *define_values;
    size_t define_count;
    /* Nonzero: what libppm cannot render in an XML file is substituted (an unknown BSDF by
     * a grey diffuse one, an unknown emitter or texture left out), each element with one
     * warning through the context's warning callback; 0 (default): that is a PARSE error
     * naming file, line and element. */
    int lenient;
    uint64_t reserved[4]; /* 0 */
} ppm_scene_file_options;

/* Sets *options to the defaults above, `size` to sizeof(ppm_scene_file_options) and every
 * other byte to 0. */
static inline void ppm_scene_file_options_init(ppm_scene_file_options *options) {
    unsigned char *bytes = (unsigned char *)options;
    size_t i;
    for (i = 0; i < sizeof *options; ++i) bytes[i] = 0;
    options->size = sizeof *options;
}

/* ppm_scene_file_load with options (NULL: the defaults). Errors: as ppm_scene_file_load, and
 * INVALID_ARGUMENT for bad options (a size out of range, an unknown format, a NULL or empty
 * parameter name, NULL arrays with a count, parameters for a JSON file), UNSUPPORTED for
 * nonzero bytes this library does not know. Warnings of lenient reading go to the context's
 * warning callback. */
PPM_API ppm_status ppm_scene_file_load_v2(ppm_context context, const char *path, const ppm_scene_file_options *options,
                                          ppm_scene_file *out_file);
/* A scene file from `size` bytes of text at `text` (JSON or XML as `options` says), as if it
 * were a file named `name` (messages say "name:line:column: ..."; NULL: "<scene text>")
 * in the folder `folder`, against which the relative file names inside are resolved (NULL:
 * the working directory). Errors: as ppm_scene_file_load_v2 (IO only for files the text
 * names), INVALID_ARGUMENT (NULL text with a nonzero size). */
PPM_API ppm_status ppm_scene_file_load_memory(ppm_context context, const char *text, size_t size, const char *name,
                                              const char *folder, const ppm_scene_file_options *options,
                                              ppm_scene_file *out_file);
/* Adds / drops a reference (atomic: thread safe). The scene, renderers and references taken
 * from the file stay valid after its last release. Errors (retain): INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_scene_file_retain(ppm_scene_file file);
PPM_API void ppm_scene_file_release(ppm_scene_file file);

/* The file's committed scene, retained for the caller (release it when done). Changing that
 * scene changes it for the file's later renderers too. Errors: INVALID_ARGUMENT (NULL). */
PPM_API ppm_status ppm_scene_file_get_scene(ppm_scene_file file, ppm_scene *out_scene);
/* The file's camera (`sensor`) with its film size, in the first camera struct, which holds
 * neither a principal point offset nor a pixel filter: the filter is left out (a renderer
 * made from this struct uses the box), and a camera with an offset is refused. New code uses
 * ppm_scene_file_get_camera_v2, which holds both. Errors: INVALID_ARGUMENT (NULL),
 * UNSUPPORTED (the file's camera has a principal point offset). */
PPM_API ppm_status ppm_scene_file_get_camera(ppm_scene_file file, ppm_camera *out_camera);
/* The same into an extensible camera: `size` set by the caller as described at
 * ppm_renderer_get_camera_v2. Errors: INVALID_ARGUMENT (NULL, size too small). */
PPM_API ppm_status ppm_scene_file_get_camera_v2(ppm_scene_file file, ppm_camera_v2 *out_camera);
/* A renderer for the file's scene and camera with the file's `integrator` settings applied;
 * the caller owns the one reference returned. Errors: as ppm_renderer_create (for example
 * INVALID_OPERATION when the file's scene was changed and not committed again). */
PPM_API ppm_status ppm_scene_file_create_renderer(ppm_scene_file file, ppm_renderer *out_renderer);
/* The same seen through `camera` instead of the file's (NULL: the file's): typically the
 * file's camera (ppm_scene_file_get_camera_v2) with another image size or a crop window.
 * Settings the file gives in pixels (initial_radius_pixels) follow the new pixel size. The
 * caller owns the one reference returned; thread safe like the other calls on a loaded file.
 * Errors: INVALID_ARGUMENT (NULL file or out_renderer), and those of ppm_renderer_create_v2
 * (a bad camera field or size, naming it). */
PPM_API ppm_status ppm_scene_file_create_renderer_v2(ppm_scene_file file, const ppm_camera_v2 *camera,
                                                     ppm_renderer *out_renderer);
/* Read-only values of the file (typed settings: see the top of this header): "passes" (int,
 * integrator.passes, 0 when not given) and "time" (double, integrator.time in seconds, 0
 * when not given). Errors: INVALID_ARGUMENT (NULL, unknown key, wrong type). */
PPM_API ppm_status ppm_scene_file_get_int(ppm_scene_file file, const char *key, int64_t *out_value);
PPM_API ppm_status ppm_scene_file_get_double(ppm_scene_file file, const char *key, double *out_value);

#ifdef __cplusplus
}
#endif

#endif /* PPM_PPM_H */
