"""Guaranteed-error triangle-mesh simplification on exact predicates.

The output of :func:`simplify` is within epsilon of the input and the input within epsilon
of the output, it does not self-intersect, and it keeps the input's genus; every output
comes with a certificate proved by an independent verifier (Cohen et al. 1996,
*Simplification Envelopes*). :func:`genus` lowers the genus on request (El-Sana and
Varshney 1997).

Meshes are numpy arrays: ``vertices`` of shape ``(n, 3)`` (float64, or anything
``numpy.asarray(..., dtype=float64)`` converts) and ``faces`` of shape ``(m, 3)`` (any
integer dtype), counter-clockwise seen from outside.

An epsilon is an absolute length (a number) or a string in the command line's syntax:
``"0.01"`` (absolute), ``"1%"`` or ``"1/64%"`` (of the bounding-box diagonal).

>>> import envelope
>>> vertices, faces = envelope.demo()
>>> out = envelope.simplify(vertices, faces, "1%", threads=1)
>>> out.is_certified, len(out.faces) < len(faces)
(True, True)

This module is a thin layer over the Rust library of the same name; every default comes
from it (:data:`DEFAULTS`), and every error message is the library's.
"""

from __future__ import annotations

from os import PathLike
from typing import Any, Callable, Iterable, Optional, Union

from . import _envelope
from ._envelope import (
    DEFAULTS,
    Cancelled,
    Certificate,
    CertificateViolated,
    CheckReport,
    EnvelopeError,
    GenusResult,
    InputError,
    InvalidArgumentError,
    InvalidEpsilonError,
    InvalidMeshError,
    Level,
    NotAcceptableError,
    OneSided,
    ReadError,
    Simplified,
    SimplifyError,
    Witness,
    WriteError,
    __version__,
)

__all__ = [
    "DEFAULTS",
    "Cancelled",
    "Certificate",
    "CertificateViolated",
    "CheckReport",
    "EnvelopeError",
    "GenusResult",
    "InputError",
    "InvalidArgumentError",
    "InvalidEpsilonError",
    "InvalidMeshError",
    "Level",
    "NotAcceptableError",
    "OneSided",
    "ReadError",
    "Simplified",
    "SimplifyError",
    "Witness",
    "WriteError",
    "__version__",
    "check",
    "demo",
    "genus",
    "load",
    "lod",
    "repair",
    "save",
    "simplify",
    "simplify_trimesh",
    "verify",
]

Epsilon = Union[float, str]
Progress = Callable[[dict[str, Any]], Optional[bool]]


def simplify(
    vertices: Any,
    faces: Any,
    epsilon: Epsilon,
    *,
    placement: str = DEFAULTS["placement"],
    method: str = DEFAULTS["method"],
    envelope: str = DEFAULTS["envelope"],
    hole_filling: str = DEFAULTS["hole_filling"],
    tube_segments: Optional[int] = DEFAULTS["tube_segments"],
    target_faces: Optional[int] = None,
    certify: bool = DEFAULTS["certify"],
    tolerance_phase: bool = DEFAULTS["tolerance_phase"],
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> Simplified:
    """Simplify a mesh within ``epsilon`` of it, both ways, and certify the output.

    Args:
        vertices: ``(n, 3)`` positions.
        faces: ``(m, 3)`` vertex indices (any integer dtype).
        epsilon: an absolute length, or ``"1%"``, ``"1/64%"`` of the bounding-box diagonal.
        placement: where output vertices may lie: ``"subset"`` (input vertices), ``"slide"``
            (moved along their normals), ``"collapse"`` (anywhere between the envelopes), or
            ``"auto"`` (subset, then the moving phase: in full when few vertices are left,
            light otherwise).
        method: ``"local"`` (5.2), ``"global"`` (5.3) or ``"hybrid"`` (5.4).
        envelope: how the envelopes find their offsets: ``"analytical"`` (4.1),
            ``"numerical"`` (4.2) or ``"auto"`` (analytical, grown numerically where short).
        hole_filling: ``"greedy"`` (the paper's) or ``"exhaustive"`` (small holes).
        tube_segments: vertices per border-tube ring (6.2); ``None`` keeps every border
            vertex.
        target_faces: stop once at most this many faces remain.
        certify: certify the output against the input.
        tolerance_phase: after the simplification, go on where the envelopes stop (thin
            parts at large epsilons) with operations proved against the bound itself
            (uniform epsilon only).
        threads: worker threads; ``None`` is the library's default (one per core). The
            output is the same for any number.
        progress: called with a dict per event (``{"kind": "stage", "stage": "envelopes"}``,
            ``{"kind": "removed", "attempts": ..., "removed": ...}``); returning ``False``
            cancels (:class:`Cancelled`). Ctrl-C cancels too (``KeyboardInterrupt``).

    Returns:
        A :class:`Simplified` with ``vertices``, ``faces``, ``report`` (a dict),
        ``certificate`` and ``is_certified``.

    Raises:
        InvalidMeshError: arrays that make no mesh (the message names the row).
        NotAcceptableError: degeneracies the simplifier refuses (see :func:`check`).
        InvalidEpsilonError, InvalidArgumentError: before any work.
        CertificateViolated: the output failed its certificate (``err.result`` holds it).
        Cancelled: the progress callback returned ``False``.

    >>> import envelope
    >>> v, f = envelope.demo()
    >>> out = envelope.simplify(v, f, 0.05, placement="subset", threads=2)
    >>> out.vertices.shape[1], out.faces.dtype.name, out.certificate.verdict
    (3, 'int64', 'holds')
    """
    return _envelope.simplify(
        vertices,
        faces,
        epsilon,
        placement=placement,
        method=method,
        envelope=envelope,
        hole_filling=hole_filling,
        tube_segments=tube_segments,
        target_faces=target_faces,
        certify=certify,
        tolerance_phase=tolerance_phase,
        threads=threads,
        progress=progress,
    )


def verify(
    v0: Any, f0: Any, v1: Any, f1: Any, epsilon: Epsilon, *, map: bool = False
) -> Certificate:
    """Certify ``(v1, f1)`` against ``(v0, f0)``, whoever made it.

    Every point of each within ``epsilon`` of the other (exact branch and bound, both
    ways), no self-intersection of ``(v1, f1)``, the same genus, components and border
    loops. A relative epsilon is a part of the original's diagonal. With ``map=True`` the
    certificate's ``error_map`` gives certified per-face bounds both ways and a per-vertex
    bound of ``(v1, f1)`` (what ``envelope verify --map`` writes).

    >>> import envelope
    >>> v, f = envelope.demo()
    >>> envelope.verify(v, f, v, f, "0.1%").verdict
    'holds'
    >>> moved = v.copy(); moved[0] += 1.0
    >>> envelope.verify(v, f, moved, f, "0.1%").violations[0]
    'approx_to_orig'
    """
    return _envelope.verify(v0, f0, v1, f1, epsilon, map=map)


def check(vertices: Any, faces: Any) -> CheckReport:
    """Whether a mesh is acceptable input, with every degeneracy class of section 7.1.

    >>> import envelope
    >>> report = envelope.check(*envelope.demo())
    >>> report.acceptable, report.problems
    (True, {})
    """
    return _envelope.check(vertices, faces)


def lod(
    vertices: Any,
    faces: Any,
    epsilons: Union[str, Iterable[Epsilon]] = DEFAULTS["lod_epsilons"],
    *,
    rule: str = DEFAULTS["lod_rule"],
    envelope: str = DEFAULTS["envelope"],
    hole_filling: str = DEFAULTS["hole_filling"],
    certify: bool = DEFAULTS["certify"],
    pixels: float = DEFAULTS["pixels"],
    resolution: float = DEFAULTS["resolution"],
    fov_degrees: float = DEFAULTS["fov_degrees"],
    correspondences: Optional[bool] = None,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> list[Level]:
    """A chain of levels of detail with nested vertex sets (Cohen et al. 7.2).

    Each level is simplified from the one before; with ``rule="cumulative"`` each epsilon
    is the level's bound to the original (they must increase), with ``"sum"`` each is a
    step and the bound is their running sum. Switching distances are for a screen of
    ``resolution`` pixels and ``fov_degrees`` tolerating ``pixels`` of error.
    ``epsilons`` is a list or one comma-separated string. ``progress`` hears
    ``{"kind": "level", "index": i, "count": n}`` before each level's stages. With
    ``correspondences=True`` each level's ``correspondence`` says which faces of the level
    before each of its faces covers (Cohen et al. 8.1; ``covers[f]`` sorted face indices,
    every finer face covered), with a bound of each face's distance to that level
    (``error``).

    >>> import envelope
    >>> levels = envelope.lod(*envelope.demo(), ["0.5%", "1%"], threads=1)
    >>> [l.index for l in levels], all(l.is_certified for l in levels)
    ([1, 2], True)
    >>> len(levels[1].faces) <= len(levels[0].faces)
    True
    """
    return _envelope.lod(
        vertices,
        faces,
        epsilons,
        rule=rule,
        envelope=envelope,
        hole_filling=hole_filling,
        certify=certify,
        pixels=pixels,
        resolution=resolution,
        fov_degrees=fov_degrees,
        correspondences=correspondences,
        threads=threads,
        progress=progress,
    )


def genus(
    vertices: Any,
    faces: Any,
    alpha: Epsilon,
    *,
    beta_degrees: float = DEFAULTS["genus_beta_degrees"],
    source: str = DEFAULTS["genus_source"],
    threads: Optional[int] = None,
) -> GenusResult:
    """Fill the holes and tunnels an L-infinity cube of side ``2 alpha`` cannot pass.

    (El-Sana and Varshney 1997.) ``beta_degrees`` is the sharp-edge angle between face
    normals; ``source`` is ``"closing"`` (the default: the sharp-edge step, then the regions
    the cube's closing swallows, networks of tunnels whose junctions are not sharp),
    ``"sharp_edges"`` (the paper's sharp-edge step alone) or ``"prism_union"`` (where the
    rims of the filled regions come from).

    >>> import envelope
    >>> out = envelope.genus(*envelope.demo(), "1%")
    >>> out.report["genus_out"]
    0
    """
    return _envelope.genus(
        vertices, faces, alpha, beta_degrees=beta_degrees, source=source, threads=threads
    )


def load(path: Union[str, "PathLike[str]"]) -> tuple[Any, Any]:
    """Read a mesh file (OBJ, OFF, PLY, STL) into ``(vertices, faces)`` arrays.

    Polygons are triangulated; anything that could change the surface and cannot be read
    is refused (:class:`ReadError`, naming the file and the element).

    >>> import envelope, os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "cup.off")
    >>> envelope.save(path, *envelope.demo())
    >>> v, f = envelope.load(path)
    >>> v.shape[1], f.shape[1]
    (3, 3)
    """
    return _envelope.load(path)


def repair(vertices: Any, faces: Any) -> tuple[Any, Any, dict[str, Any]]:
    """Repair a mesh without moving its surface: weld vertices at bitwise-equal positions,
    drop exact duplicate faces, zero-area faces proved to lie on others and unreferenced
    vertices, split faces at T-junctions and non-manifold vertices and edges into manifold
    sheets, orient each component consistently. Returns ``(vertices, faces, report)``; the
    report lists every change by input index, ``acceptable`` (whether :func:`simplify`
    takes the result) and what is ``left`` (such as intersecting faces). What cannot be
    repaired without moving the surface raises :class:`NotAcceptableError` naming it.

    >>> import envelope, numpy as np
    >>> v, f = envelope.demo()
    >>> apart = v[f.reshape(-1)]                      # every face with corners of its own
    >>> v2, f2, report = envelope.repair(apart, np.arange(len(apart)).reshape(-1, 3))
    >>> report["acceptable"], len(f2) == len(f)
    (True, True)
    """
    return _envelope.repair(vertices, faces)


def save(path: Union[str, "PathLike[str]"], vertices: Any, faces: Any) -> None:
    """Write a mesh in the format its extension names (``.obj``, ``.off``, ``.ply``,
    ``.stl``), through a temporary file renamed into place only when complete.

    >>> import envelope, os, tempfile
    >>> envelope.save(os.path.join(tempfile.mkdtemp(), "cup.obj"), *envelope.demo())
    """
    return _envelope.save(path, vertices, faces)


def demo() -> tuple[Any, Any]:
    """The built-in model of ``envelope demo``: a cup with a fluted wall, a sharp bottom
    crease and an open rim, as ``(vertices, faces)``.

    >>> import envelope
    >>> v, f = envelope.demo()
    >>> v.dtype.name, f.shape
    ('float64', (4032, 3))
    """
    return _envelope.demo()


def simplify_trimesh(mesh: Any, epsilon: Epsilon, **kwargs: Any) -> Any:
    """:func:`simplify` on a ``trimesh.Trimesh``, returning a new ``trimesh.Trimesh``.

    Keyword arguments are :func:`simplify`'s. The result is made with ``process=False`` (no
    merging or reordering: its arrays are the simplifier's output). Raises
    :class:`CertificateViolated` as :func:`simplify` does.

    >>> import envelope, trimesh
    >>> cup = trimesh.Trimesh(*envelope.demo(), process=False)
    >>> out = envelope.simplify_trimesh(cup, "1%", threads=1)
    >>> len(out.faces) < len(cup.faces)
    True
    """
    import trimesh  # only for this function: the package does not depend on it

    out = simplify(mesh.vertices, mesh.faces, epsilon, **kwargs)
    return trimesh.Trimesh(vertices=out.vertices, faces=out.faces, process=False)
