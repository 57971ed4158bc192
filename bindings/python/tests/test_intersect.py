# SPDX-License-Identifier: Apache-2.0
"""Ray queries against closed-form answers (sphere, quad, triangle) and, on the teapot,
against an independent numpy model of the patches."""
import numpy as np
import pytest

import libppm

from conftest import TEAPOT, bezier

rng = np.random.default_rng(7)


def unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def rays_towards(targets, distance):
    """Origins `distance` away from `targets` in random directions, unit directions to them."""
    d = unit(rng.normal(size=targets.shape))
    return targets - distance * d, d


def test_sphere_against_closed_form(scene):
    center, radius = np.array([0.5, -1.0, 2.0]), 1.5
    scene.add_sphere(center, radius)
    scene.commit()
    targets = center + 0.9 * radius * unit(rng.normal(size=(2000, 3)))
    org, d = rays_towards(targets, 10.0)
    hits = scene.intersect(org, d)
    # |o + t d - c|^2 = R^2 with |d| = 1: the smaller root.
    oc = org - center
    b = np.einsum("ij,ij->i", oc, d)
    t = -b - np.sqrt(b * b - (np.einsum("ij,ij->i", oc, oc) - radius**2))
    assert hits.hit.all()
    np.testing.assert_allclose(hits.t, t, rtol=0, atol=1e-9)
    p = org + t[:, None] * d
    np.testing.assert_allclose(hits.p, p, atol=1e-9)
    n = (p - center) / radius
    np.testing.assert_allclose(hits.ng, n, atol=1e-9)  # outward, as stored
    phi = np.mod(np.arctan2(n[:, 1], n[:, 0]), 2 * np.pi)
    np.testing.assert_allclose(hits.u, phi / (2 * np.pi), atol=1e-9)
    np.testing.assert_allclose(hits.v, np.arccos(np.clip(n[:, 2], -1, 1)) / np.pi, atol=1e-7)
    assert (hits.geom_id == 0).all() and (hits.prim_id == 0).all()
    assert hits.t.dtype == np.float64 and hits.geom_id.dtype == np.uint32


def test_quad_against_closed_form(scene):
    origin, eu, ev = np.array([1.0, 2.0, 0.5]), np.array([2.0, 0.5, 0.0]), np.array([-0.3, 1.0, 1.0])
    scene.add_quad(origin, eu, ev)
    scene.commit()
    st = rng.uniform(0.02, 0.98, size=(1000, 2))
    targets = origin + st[:, :1] * eu + st[:, 1:] * ev
    org, d = rays_towards(targets, 7.0)
    hits = scene.intersect(org, d)
    np.testing.assert_allclose(hits.t, 7.0, atol=1e-9)
    np.testing.assert_allclose(np.stack([hits.u, hits.v], -1), st, atol=1e-9)
    normal = unit(np.cross(eu, ev))
    np.testing.assert_allclose(hits.ng, np.broadcast_to(normal, hits.ng.shape), atol=1e-12)
    # Outside the parallelogram: misses, marked as documented.
    miss = scene.intersect(origin - 0.5 * eu + normal, -normal)
    assert miss.t == np.inf and not miss.hit
    assert miss.geom_id == libppm.INVALID_ID == 0xFFFFFFFF and miss.prim_id == libppm.INVALID_ID


def test_triangle_mesh_barycentrics_and_shading_normals(scene):
    positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    normals = unit(np.array([[0, 0, 1], [1, 0, 1], [0, 1, 1]], dtype=float))
    scene.add_mesh(positions, [[0, 1, 2]], normals=normals, uvs=[[0, 0], [1, 0], [0, 1]])
    scene.commit()
    hits = scene.intersect((0.2, 0.3, 1.0), (0, 0, -1))
    assert hits.t == pytest.approx(1.0, abs=1e-12)
    assert (hits.u, hits.v) == (pytest.approx(0.2, abs=1e-12), pytest.approx(0.3, abs=1e-12))
    expected = unit(0.5 * normals[0] + 0.2 * normals[1] + 0.3 * normals[2])
    np.testing.assert_allclose(hits.ns, expected, atol=1e-9)
    assert abs(hits.ng[2]) == pytest.approx(1.0)


def test_transforms_and_materials(scene):
    sphere = scene.add_sphere((0, 0, 0), 1.0)
    quad = scene.add_quad((-1, -1, 0), (2, 0, 0), (0, 2, 0), material=None)
    scene.add_diffuse_material(0.5)
    glass = scene.add_dielectric_material()
    scene.set_material(sphere, glass)
    move = np.eye(4)
    move[:3, 3] = (0, 0, 5)
    scene.set_transform(sphere, move[:3])  # (3, 4) is completed with 0 0 0 1
    scene.set_transform(quad, 2 * np.eye(4) - np.diag([0, 0, 0, 1]))
    scene.commit()
    hits = scene.intersect([(0, 0, 10), (1.5, 1.5, -3)], [(0, 0, -1), (0, 0, 1)])
    np.testing.assert_allclose(hits.t, [4.0, 3.0], atol=1e-9)
    assert list(hits.geom_id) == [sphere, quad] and list(hits.material) == [glass, 0]
    lower, upper = scene.bounds
    np.testing.assert_allclose(lower, [-2, -2, 0], atol=1e-9)
    np.testing.assert_allclose(upper, [2, 2, 6], atol=1e-9)


def test_broadcasting_and_batch_shapes(scene):
    scene.add_sphere((0, 0, 0), 1.0)
    scene.commit()
    xs = np.linspace(-1.5, 1.5, 7)
    grid = np.stack(np.meshgrid(xs, xs, indexing="ij") + [np.full((7, 7), -5.0)], axis=-1)
    hits = scene.intersect(grid, (0, 0, 1))
    assert hits.t.shape == (7, 7) and hits.ng.shape == (7, 7, 3)
    r2 = grid[..., 0] ** 2 + grid[..., 1] ** 2
    clear = np.abs(r2 - 1) > 1e-6  # not the tangent rays
    assert (hits.hit == (r2 < 1))[clear].all()
    np.testing.assert_allclose(hits.t[r2 < 1], 5 - np.sqrt(1 - r2[r2 < 1]), atol=1e-9)
    one = scene.intersect((0, 0, -5), (0, 0, 2))
    assert one.t.shape == () and one.t == pytest.approx(2.0)  # t in units of |direction|
    near = scene.intersect((0, 0, -5), (0, 0, 1), tnear=[0.0, 4.5, 7.0], tfar=[3.0, 10.0, 10.0])
    np.testing.assert_allclose(near.t, [np.inf, 6.0, np.inf])


def test_occluded_agrees_with_intersect(scene, teapot_points):
    scene.add_bezier_patches(teapot_points)
    scene.commit()
    targets = rng.uniform(-3, 3, size=(3000, 3)) + (0, 0, 1.5)
    org, d = rays_towards(targets, 8.0)
    hits = scene.intersect(org, d)
    occluded = scene.occluded(org, d)
    assert occluded.dtype == bool and (occluded == hits.hit).all()
    assert 0.1 < occluded.mean() < 0.9
    # Limited to [0, t/2]: nothing in the way before the first hit.
    half = np.where(hits.hit, hits.t / 2, np.inf)
    assert not scene.occluded(org, d, tfar=half).any()


def test_teapot_hits_lie_on_the_patches(scene, teapot_points):
    """Every hit (t, u, v, p, ng) checked on the independent numpy model of the surface, and
    the hit distance against a Newton solve of S(u, v) = o + t d started at the hit."""
    scene.load_bpt(TEAPOT)
    scene.commit()
    lower, upper = scene.bounds
    diagonal = np.linalg.norm(upper - lower)
    targets = lower + rng.uniform(size=(4000, 3)) * (upper - lower)
    org, d = rays_towards(targets, diagonal)
    hits = scene.intersect(org, d)
    h = hits.hit
    assert h.sum() > 1000
    patches = teapot_points[hits.prim_id[h]]
    s, su, sv = bezier(patches, hits.u[h], hits.v[h])
    on_ray = org[h] + hits.t[h, None] * d[h]
    # ppm.h: hit point within tolerance (1e-9) * diagonal of the exact one, p = S(u, v).
    assert np.abs(s - on_ray).max() < 1e-9 * diagonal
    np.testing.assert_allclose(hits.p[h], s, atol=1e-12 * diagonal)
    n = np.cross(su, sv)
    norm = np.linalg.norm(n, axis=-1)
    regular = norm > 1e-6
    np.testing.assert_allclose(hits.ng[h][regular], n[regular] / norm[regular, None], atol=1e-9)
    # Newton on F(u, v, t) = S(u, v) - o - t d from the reported hit: it must not move.
    u, v, t = hits.u[h].copy(), hits.v[h].copy(), hits.t[h].copy()
    for _ in range(3):
        s, su, sv = bezier(patches, u, v)
        f = s - org[h] - t[:, None] * d[h]
        jac = np.stack([su, sv, -d[h]], axis=-1)
        step = np.linalg.solve(jac[regular], f[regular])
        u[regular] -= step[:, 0]
        v[regular] -= step[:, 1]
        t[regular] -= step[:, 2]
    assert np.abs(t - hits.t[h]).max() < 1e-9 * diagonal


def test_teapot_first_hits_at_known_surface_points(scene, teapot_points):
    """Rays aimed at points S(u0, v0) along the outward normal: the first hit is never
    beyond the point, and where the patch is the first surface it is that point."""
    scene.add_bezier_patches(teapot_points.reshape(-1, 4, 4, 3))
    scene.commit()
    patch = rng.integers(0, len(teapot_points), size=2000)
    uv = rng.uniform(0.05, 0.95, size=(2000, 2))
    x, su, sv = bezier(teapot_points[patch], uv[:, 0], uv[:, 1])
    n = unit(np.cross(su, sv))
    org = x + 20 * n
    hits = scene.intersect(org, -n)
    assert hits.hit.all()
    assert (hits.t <= 20 + 1e-8).all()
    same = (hits.prim_id == patch) & (np.abs(hits.t - 20) < 1e-6)
    assert same.mean() > 0.5
    np.testing.assert_allclose(hits.u[same], uv[same, 0], atol=1e-8)
    np.testing.assert_allclose(hits.v[same], uv[same, 1], atol=1e-8)


def test_bpt_file_and_array_give_the_same_hits(teapot_points):
    with libppm.Scene() as a, libppm.Scene() as b:
        a.load_bpt(TEAPOT)
        b.add_bezier_patches(teapot_points)
        a.commit()
        b.commit()
        targets = rng.uniform(-2, 2, size=(500, 3)) + (0, 0, 1.5)
        org, d = rays_towards(targets, 10.0)
        ha, hb = a.intersect(org, d), b.intersect(org, d)
        assert (ha.t == hb.t).all() and (ha.prim_id == hb.prim_id).all()
        assert a.primitive_count(0) == 32


def test_obj_file(scene, tmp_path):
    obj = tmp_path / "square.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n")
    geom = scene.load_obj(obj)
    assert scene.primitive_count(geom) == 2
    scene.commit()
    assert scene.intersect((0.3, 0.6, 2), (0, 0, -1)).t == pytest.approx(2.0)


def test_large_batch_on_worker_threads(teapot_points):
    with libppm.Context(threads=2) as ctx, libppm.Scene(ctx) as s:
        s.add_bezier_patches(teapot_points)
        s.commit()
        targets = rng.uniform(-2, 2, size=(100_000, 3)) + (0, 0, 1.5)
        org, d = rays_towards(targets, 10.0)
        hits = s.intersect(org, d)
        ctx.threads = 1
        again = s.intersect(org[:1000], d[:1000])
        assert (hits.t[:1000] == again.t).all()


def test_bezier_patches_come_back_in_world_space(scene, teapot_points):
    points = teapot_points.reshape(-1, 16, 3)
    sphere = scene.add_sphere((0, 0, 10), 1.0)
    pot = scene.add_bezier_patches(points)
    m = np.array([[0, -2, 0, 1], [2, 0, 0, -3], [0, 0, 2, 0.5], [0, 0, 0, 1]], dtype=float)
    scene.set_transform(pot, m)
    scene.commit()
    assert scene.geometry_count == 2
    world = scene.bezier_patches(pot)
    assert world.shape == (len(points), 16, 3) and world.dtype == np.float64
    expected = points @ m[:3, :3].T + m[:3, 3]
    np.testing.assert_allclose(world, expected, rtol=0, atol=1e-12)
    with pytest.raises(libppm.InvalidArgumentError, match="patch"):
        scene.bezier_patches(sphere)
