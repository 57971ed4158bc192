# SPDX-License-Identifier: Apache-2.0
"""Shared fixtures and an independent numpy model of bicubic Bezier patches."""
import pathlib

import numpy as np
import pytest

import libppm

REPO = pathlib.Path(__file__).resolve().parents[3]
TEAPOT = REPO / "tests" / "data" / "teapot.bpt"


def read_bpt(path):
    """The patches of a .bpt file as an (n, 16, 3) array, parsed here, not by libppm."""
    numbers = pathlib.Path(path).read_text().split()
    count, rest = int(numbers[0]), numbers[1:]
    patches = []
    for p in range(count):
        block = rest[p * 50:(p + 1) * 50]
        assert block[:2] == ["3", "3"]
        patches.append(np.array(block[2:], dtype=float).reshape(16, 3))
    return np.array(patches)


def bernstein(t):
    """Cubic Bernstein values and derivatives at t: two (..., 4) arrays."""
    t = np.asarray(t, dtype=float)[..., None]
    s = 1 - t
    b = np.concatenate([s**3, 3 * t * s**2, 3 * t**2 * s, t**3], axis=-1)
    db = np.concatenate([-3 * s**2, 3 * s**2 - 6 * t * s, 6 * t * s - 3 * t**2, 3 * t**2], axis=-1)
    return b, db


def bezier(points, u, v):
    """S, dS/du, dS/dv of patches `points` (..., 16, 3) at (u, v): u along a row, v across."""
    grid = np.asarray(points).reshape(np.shape(points)[:-2] + (4, 4, 3))
    bu, dbu = bernstein(u)
    bv, dbv = bernstein(v)
    s = np.einsum("...i,...j,...ijk->...k", bv, bu, grid)
    su = np.einsum("...i,...j,...ijk->...k", bv, dbu, grid)
    sv = np.einsum("...i,...j,...ijk->...k", dbv, bu, grid)
    return s, su, sv


@pytest.fixture(scope="session")
def teapot_points():
    return read_bpt(TEAPOT)


@pytest.fixture
def scene():
    with libppm.Scene() as s:
        yield s
