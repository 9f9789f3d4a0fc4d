"""Hull meshes: read (STL ASCII and binary, Wavefront OBJ, WAMIT GDF), check and repair, write
(STL), generate (box, sphere, barge), and the hydrostatics of the part below a waterline.

A ``Mesh`` holds vertices (nv, 3) [m] and triangles (nt, 3) (vertex numbers), wound
anticlockwise seen from outside. ``checked`` makes the winding consistent across shared edges
(a triangle whose neighbour runs their edge the same way is turned over), turns the whole mesh
over when its volume comes out negative, and refuses, with the reason, an edge shared by more
than two triangles, a one-sided surface, and a mesh not closed below the waterline: the
displaced volume measured three ways (int x n_x, int y n_y, int (z - level) n_z over the
wetted surface, by the divergence theorem on it closed by its waterplane) must agree.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from seacable import files
from seacable.kernels import hull

LARGEST_MESH = 200_000_000  # bytes of a mesh file
SMALLEST_HULL, LARGEST_HULL = 0.01, 10_000.0  # [m] a hull's largest extent
CLOSED_TOLERANCE = 1e-6  # relative disagreement of the three volumes beyond which a mesh is open


@dataclass(frozen=True)
class Mesh:
    vertices: np.ndarray  # (nv, 3) [m]
    triangles: np.ndarray  # (nt, 3) int

    def row(self) -> np.ndarray:
        """The kernels' flat row (kernels.hull.mesh_row)."""
        return hull.mesh_row(self.vertices, self.triangles)

    def moved(self, offset=(0.0, 0.0, 0.0), rotation=None, scale: float = 1.0) -> Mesh:
        """The mesh scaled, turned by ``rotation`` (3x3) and moved by ``offset``."""
        v = self.vertices * scale
        if rotation is not None:
            v = v @ np.asarray(rotation, dtype=float).T
        return Mesh(v + np.asarray(offset, dtype=float), self.triangles)

    def flipped(self) -> Mesh:
        return Mesh(self.vertices, self.triangles[:, ::-1].copy())


class MeshError(ValueError):
    """A mesh that cannot be read or used: the message says why and what to do."""


# ---- reading ------------------------------------------------------------------------------------
def read(path: str | Path, fmt: str | None = None) -> Mesh:
    """The mesh of a file: ``fmt`` stl, obj or gdf (by default, from the suffix)."""
    path = Path(path)
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in READERS:
        raise MeshError(
            f"mesh file '{path}': format '{fmt}' is not known; use one of {sorted(READERS)} "
            "(give 'format' when the suffix does not say it)"
        )
    raw = files.read_bytes(path, "mesh file", LARGEST_MESH, MeshError)
    try:
        vertices, triangles = READERS[fmt](raw)
    except (ValueError, IndexError, struct.error, UnicodeDecodeError) as exc:
        raise MeshError(f"mesh file '{path}' is not a readable {fmt.upper()} file: {exc}") from None
    if len(triangles) == 0:
        raise MeshError(f"mesh file '{path}' holds no triangles")
    if not np.all(np.isfinite(vertices)):
        raise MeshError(f"mesh file '{path}': NaN or infinite coordinates")
    size = float(np.ptp(vertices[triangles].reshape(-1, 3), axis=0).max())
    if not SMALLEST_HULL <= size <= LARGEST_HULL:
        raise MeshError(
            f"mesh file '{path}': the hull is {size:.3g} m across, not between "
            f"{SMALLEST_HULL:g} and {LARGEST_HULL:g} m; give its coordinates in metres (a mesh in "
            "millimetres is 1000 times too large)"
        )
    return _indexed(vertices, triangles)


def _stl(raw: bytes):
    if len(raw) >= 84:
        count = struct.unpack("<I", raw[80:84])[0]
        if len(raw) == 84 + 50 * count:
            return _stl_binary(raw, count)
    return _stl_ascii(raw.decode("utf-8", errors="strict"))


def _stl_binary(raw: bytes, count: int):
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.frombuffer(raw, dtype=record, count=count, offset=84)
    vertices = data["v"].reshape(-1, 3).astype(float)
    return vertices, np.arange(3 * count).reshape(-1, 3)


def _stl_ascii(text: str):
    words = text.split()
    if not words or words[0].lower() != "solid":
        raise ValueError("neither binary STL (84 + 50 n bytes) nor ASCII STL ('solid ...')")
    points = []
    for k, word in enumerate(words):
        if word.lower() == "vertex":
            points.append([float(words[k + 1]), float(words[k + 2]), float(words[k + 3])])
    if len(points) % 3:
        raise ValueError(f"{len(points)} vertices, not a multiple of 3")
    vertices = np.array(points, dtype=float).reshape(-1, 3)
    return vertices, np.arange(len(vertices)).reshape(-1, 3)


def _obj(raw: bytes):
    """Wavefront OBJ: ``v x y z`` vertices and ``f i j k ...`` faces (indices from 1, negative
    ones counted back from the last vertex read), fanned into triangles."""
    vertices, faces = [], []
    for number, line in enumerate(raw.decode("utf-8").splitlines(), start=1):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            if len(parts) < 4:
                raise ValueError(f"line {number}: a vertex needs x, y and z")
            vertices.append([float(p) for p in parts[1:4]])
        elif parts[0] == "f":
            try:
                ids = [int(p.split("/")[0]) for p in parts[1:]]
            except ValueError:
                raise ValueError(
                    f"line {number}: a face's vertices are whole numbers (from 1): "
                    f"{' '.join(parts[1:])!r}"
                ) from None
            if len(ids) < 3 or any(i == 0 or abs(i) > len(vertices) for i in ids):
                raise ValueError(
                    f"line {number}: face {ids} names a vertex the file has not given (it has "
                    f"{len(vertices)} so far, counted from 1), or has fewer than 3"
                )
            ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
            faces += [[ids[0], ids[k], ids[k + 1]] for k in range(1, len(ids) - 1)]
    return np.array(vertices, dtype=float).reshape(-1, 3), np.array(faces, dtype=np.int64)


def _gdf(raw: bytes):
    """WAMIT's GDF: a title line, ULEN GRAV, ISX ISY (planes of symmetry x = 0, y = 0 when 1),
    NPAN, then four vertices per panel (a triangle repeats one). Mirrored copies are added for
    each plane of symmetry."""
    lines = raw.decode("utf-8").splitlines()
    isx, isy = (int(float(w)) for w in lines[2].split()[:2])
    count = int(float(lines[3].split()[0]))
    numbers = np.array(" ".join(lines[4:]).split()[: 12 * count], dtype=float)
    if count < 1 or len(numbers) < 12 * count:
        raise ValueError(f"{count} panels need {12 * count} coordinates (4 vertices of 3); the "
                         f"file holds {len(numbers)}")  # fmt: skip
    quads = numbers.reshape(count, 4, 3)
    for flag, axis in ((isx, 0), (isy, 1)):
        if flag:
            mirror = quads[:, ::-1].copy()
            mirror[:, :, axis] *= -1.0
            quads = np.concatenate([quads, mirror])
    vertices = quads.reshape(-1, 3)
    base = 4 * np.arange(len(quads))[:, None]
    triangles = np.concatenate([base + [0, 1, 2], base + [0, 2, 3]])
    return vertices, triangles


READERS = {"stl": _stl, "obj": _obj, "gdf": _gdf}


def _indexed(vertices: np.ndarray, triangles: np.ndarray) -> Mesh:
    """Shared vertices merged (equal coordinates), degenerate triangles dropped."""
    unique, inverse = np.unique(vertices, axis=0, return_inverse=True)
    tri = inverse.reshape(-1)[triangles]
    keep = (tri[:, 0] != tri[:, 1]) & (tri[:, 1] != tri[:, 2]) & (tri[:, 2] != tri[:, 0])
    tri = tri[keep]
    v = unique[tri]
    area = 0.5 * np.linalg.norm(np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), axis=1)
    scale = np.abs(unique).max() if len(unique) else 1.0
    tri = tri[area > 1e-14 * max(scale, 1e-300) ** 2]
    return Mesh(unique, np.ascontiguousarray(tri, dtype=np.int64))


# ---- writing ------------------------------------------------------------------------------------
def stl_text(mesh: Mesh, name: str = "hull") -> str:
    """ASCII STL, coordinates to 17 digits (read back exactly)."""
    out = [f"solid {name}"]
    for a, b, c in mesh.vertices[mesh.triangles]:
        n = np.cross(b - a, c - a)
        n = n / (np.linalg.norm(n) or 1.0)
        out.append(f"  facet normal {n[0]:.6e} {n[1]:.6e} {n[2]:.6e}\n    outer loop")
        out += [f"      vertex {p[0]:.17g} {p[1]:.17g} {p[2]:.17g}" for p in (a, b, c)]
        out.append("    endloop\n  endfacet")
    out.append(f"endsolid {name}")
    return "\n".join(out) + "\n"


def write_stl(mesh: Mesh, path: str | Path, binary: bool = True) -> None:
    """Write an STL file (binary stores float32)."""
    path = Path(path)
    if not binary:
        path.write_text(stl_text(mesh))
        return
    v = mesh.vertices[mesh.triangles]
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]
    record = np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)), ("attr", "<u2")])
    data = np.zeros(len(v), dtype=record)
    data["normal"], data["v"] = n, v
    path.write_bytes(b"seacable mesh".ljust(80) + struct.pack("<I", len(v)) + data.tobytes())


# ---- checking -----------------------------------------------------------------------------------
def consistent(mesh: Mesh) -> Mesh:
    """The winding made consistent across shared edges, surface by surface (breadth first from
    each surface's first triangle). MeshError for an edge of more than two triangles or a
    one-sided surface (a Moebius strip)."""
    tri = mesh.triangles
    nt = len(tri)
    edges = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    owner = np.tile(np.arange(nt), 3)
    key = np.sort(edges, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, edges, owner = key[order], edges[order], owner[order]
    same = np.all(key[1:] == key[:-1], axis=1)
    if np.any(same[1:] & same[:-1]):
        k = int(np.argmax(same[1:] & same[:-1]))
        raise MeshError(
            f"mesh: the edge between vertices {key[k].tolist()} belongs to more than two "
            "triangles (a non-manifold mesh); remove the inner or duplicated faces"
        )
    pairs = np.nonzero(same)[0]
    a, b = owner[pairs], owner[pairs + 1]
    # equal orientation: both triangles run the edge the same way, one must turn over
    agree = np.all(edges[pairs] == edges[pairs + 1], axis=1)
    neighbours: list[list[tuple[int, bool]]] = [[] for _ in range(nt)]
    for i, j, flip in zip(a.tolist(), b.tolist(), agree.tolist(), strict=True):
        neighbours[i].append((j, flip))
        neighbours[j].append((i, flip))
    turn = np.full(nt, -1, dtype=np.int64)
    for start in range(nt):
        if turn[start] >= 0:
            continue
        turn[start] = 0
        queue = [start]
        while queue:
            i = queue.pop()
            for j, flip in neighbours[i]:
                want = turn[i] ^ int(flip)
                if turn[j] < 0:
                    turn[j] = want
                    queue.append(j)
                elif turn[j] != want:
                    raise MeshError(
                        f"mesh: triangles {i} and {j} cannot both face outwards (a one-sided "
                        "surface); the mesh is not a hull"
                    )
    out = tri.copy()
    out[turn == 1] = out[turn == 1][:, ::-1]
    return Mesh(mesh.vertices, out)


@dataclass(frozen=True)
class Hydrostatics:
    """The part of a hull below the waterline z = level, at a pose (earth axes, lengths from
    the reference point): displaced volume, centre of buoyancy, waterplane area, its centre
    (the centre of flotation) and its second moments about the reference point's vertical."""

    volume: float  # [m^3], from int (z - level) n_z
    volumes_xyz: tuple[float, float, float]  # from int x n_x, int y n_y, int (z - level) n_z
    centre_of_buoyancy: tuple[float, float, float]  # [m]
    waterplane_area: float  # [m^2]
    flotation_centre: tuple[float, float]  # [m]
    waterplane_moments: tuple[float, float, float]  # int x^2, y^2, xy dA [m^4]
    level: float  # height of the waterline above the reference point [m]

    def closed(self) -> bool:
        """True when the three volumes agree (the wetted surface and its waterplane close)."""
        v = np.array(self.volumes_xyz)
        scale = max(np.abs(v).max(), 1e-300)
        return bool(np.ptp(v) <= CLOSED_TOLERANCE * scale)


def hydrostatics(mesh: Mesh | np.ndarray, position=(0.0, 0.0, 0.0), rotation=None,
                 level: float = 0.0) -> Hydrostatics:  # fmt: skip
    """The hydrostatics of ``mesh`` (a Mesh or its row) with its reference point at
    ``position`` turned by ``rotation`` (3x3), cut by the plane z = ``level``."""
    row = mesh.row() if isinstance(mesh, Mesh) else np.asarray(mesh, dtype=float)
    rot = np.eye(3) if rotation is None else np.ascontiguousarray(rotation, dtype=float)
    out = np.zeros((10, 3))
    pos = np.asarray(position, dtype=float)
    hull.surface_integrals(row, float(level), pos, rot, out)
    k = {name: i for i, name in enumerate(hull.INTEGRANDS)}
    h = level - pos[2]  # the waterline's height above the reference point
    vz = out[k["z"], 2] - h * out[k["1"], 2]
    vx, vy = out[k["x"], 0], out[k["y"], 1]
    volume = vz
    safe = volume if volume != 0.0 else math.inf
    zz = out[k["zz"], 2] - 2.0 * h * out[k["z"], 2] + h * h * out[k["1"], 2]
    cob = (0.5 * out[k["xx"], 0] / safe, 0.5 * out[k["yy"], 1] / safe, h + 0.5 * zz / safe)
    area = -out[k["1"], 2]
    area_safe = area if area != 0.0 else math.inf
    centre = (-out[k["x"], 2] / area_safe, -out[k["y"], 2] / area_safe)
    moments = (-out[k["xx"], 2], -out[k["yy"], 2], -out[k["xy"], 2])
    return Hydrostatics(volume, (vx, vy, vz), cob, area, centre, moments, h)


def checked(mesh: Mesh, position=(0.0, 0.0, 0.0), rotation=None, level: float = 0.0,
            where: str = "mesh") -> Mesh:  # fmt: skip
    """The mesh with a consistent outward winding, or a MeshError naming ``where`` when it is
    not closed below the waterline at this pose."""
    try:
        mesh = consistent(mesh)
    except MeshError as exc:
        raise MeshError(f"{where}: {str(exc).removeprefix('mesh: ')}") from None
    stat = hydrostatics(mesh, position, rotation, level)
    if stat.volume < 0.0:
        mesh = mesh.flipped()
        stat = hydrostatics(mesh, position, rotation, level)
    if np.abs(stat.volumes_xyz).max() > 0.0 and not stat.closed():  # a face missing below
        vx, vy, vz = stat.volumes_xyz
        raise MeshError(
            f"{where}: the hull is not closed below the waterline (its displaced volume is "
            f"{vx:.6g}, {vy:.6g} and {vz:.6g} m^3 measured along x, y and z); close the mesh "
            "below the waterline (a hull may be open above it only)"
        )
    return mesh


# ---- generated hulls ----------------------------------------------------------------------------
def box(length: float, beam: float, height: float, n: int = 1) -> Mesh:
    """A closed box centred on the origin, each face cut in n x n squares of two triangles."""
    half = np.array([length, beam, height]) / 2.0
    grid = np.linspace(-1.0, 1.0, n + 1)
    faces = []
    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3
        for sign in (-1.0, 1.0):
            for i in range(n):
                for j in range(n):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis], p[u], p[w] = sign, grid[i + di], grid[j + dj]
                        quad.append(p * half)
                    if sign < 0:
                        quad = quad[::-1]
                    faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    v = np.array(faces).reshape(-1, 3)
    return _indexed(v, np.arange(len(v)).reshape(-1, 3))


def barge(length: float, beam: float, height: float, panel: float) -> Mesh:
    """A box barge centred on the origin (length along x, beam along y [m]), each face cut
    into nearly square panels of side at most ``panel`` [m], two triangles each."""
    half = np.array([length, beam, height]) / 2.0
    counts = [max(1, math.ceil(2.0 * h / panel)) for h in half]
    faces = []
    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3
        gu, gw = (np.linspace(-half[c], half[c], counts[c] + 1) for c in (u, w))
        for sign in (-1.0, 1.0):
            for i in range(counts[u]):
                for j in range(counts[w]):
                    quad = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = np.zeros(3)
                        p[axis], p[u], p[w] = sign * half[axis], gu[i + di], gw[j + dj]
                        quad.append(p)
                    if sign < 0:
                        quad = quad[::-1]
                    faces += [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]]
    v = np.array(faces).reshape(-1, 3)
    return _indexed(v, np.arange(len(v)).reshape(-1, 3))


def sphere(radius: float, n: int = 16) -> Mesh:
    """A sphere centred on the origin: n bands of latitude, 2n meridians (vertices on it)."""
    theta = np.linspace(0.0, math.pi, n + 1)
    phi = np.linspace(0.0, 2.0 * math.pi, 2 * n + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    pts = radius * np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], axis=-1)
    faces = []
    for i in range(n):
        for j in range(2 * n):
            a, b, c, d = pts[i, j], pts[i + 1, j], pts[i + 1, j + 1], pts[i, j + 1]
            faces += [[a, b, c], [a, c, d]]
    v = np.array(faces).reshape(-1, 3)
    return _indexed(np.round(v, 14), np.arange(len(v)).reshape(-1, 3))
