"""Small meshes made in code: the library's demo cup and a UV sphere."""

import math

import numpy as np
import pytest

import envelope


def uv_sphere(stacks: int = 12, slices: int = 24, radius: float = 1.0):
    """A closed genus-0 sphere, triangles counter-clockwise seen from outside."""
    vertices = [(0.0, 0.0, radius)]
    for i in range(1, stacks):
        theta = math.pi * i / stacks
        for j in range(slices):
            phi = 2.0 * math.pi * j / slices
            vertices.append(
                (
                    radius * math.sin(theta) * math.cos(phi),
                    radius * math.sin(theta) * math.sin(phi),
                    radius * math.cos(theta),
                )
            )
    vertices.append((0.0, 0.0, -radius))
    bottom = len(vertices) - 1

    def ring(i, j):
        return 1 + (i - 1) * slices + j % slices

    faces = [(0, ring(1, j), ring(1, j + 1)) for j in range(slices)]
    for i in range(1, stacks - 1):
        for j in range(slices):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            faces += [(a, c, d), (a, d, b)]
    faces += [(bottom, ring(stacks - 1, j + 1), ring(stacks - 1, j)) for j in range(slices)]
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)


@pytest.fixture(scope="session")
def cup():
    return envelope.demo()


@pytest.fixture(scope="session")
def sphere():
    return uv_sphere()


@pytest.fixture(scope="session")
def simplified_cup(cup):
    """The cup at 1%, certified (shared: the arrays are only read)."""
    return envelope.simplify(*cup, "1%", threads=1)
