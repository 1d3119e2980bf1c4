"""
Face scenes
===========

A face scene is a TOML file (``scenes/face/*.toml``): a head mesh in skin
under Planckian lights, a few props of other reflectances beside it, seen by
a perspective camera. Where a chart scene (:mod:`skinrender.rendering.scene`)
is built so that the analytic model holds exactly, a face scene is built to
find where it stops holding: curved, self-shadowing skin, light bounced from
the props and the face itself, a second light and a sky of other
temperatures (the level of physics, :mod:`skinrender.rendering.face.effects`,
chooses which).

-   :class:`FaceCamera`, :class:`Light`, :class:`Prop`, :class:`FaceScene`:
    a parsed scene (frozen, hashable).
-   :func:`load_face_scene`: a scene from a bundled name (``face``) or a
    path; a bad file is refused naming the file and the field.
-   :func:`list_face_scenes`: the bundled names; :func:`is_face_scene`:
    whether a scene spec names a face (else a chart).
-   :func:`skin_reflectance_of`: a skin spec on a grid.
-   :func:`prevailing_name`: which light the white balance calls prevailing.

Scene file fields
-----------------
``name``, ``description``, ``skin`` (a skin spec); ``[camera]``
``position``, ``target`` (m), ``up`` (default [0, 1, 0]), ``fov``
(horizontal, degrees), ``width``, ``height`` (pixels); ``[mesh]`` ``file``
(``head``: :func:`skinrender.datasets.head.mesh_head`; or an ``.obj`` or
``.ply`` path, relative to the scene file), ``translate`` (m), ``rotate``
(degrees about x, then y, then z), ``scale``, ``smooth`` (interpolated
shading normals, default true: no facets in the pictures; ``false``: flat,
each triangle's own normal, which conserves energy — shading normals lose
energy in the white furnace, measured in ``docs/face-verdicts.md``);
``[key]`` (required), ``[fill]`` and ``[environment]`` lights:
``temperature`` (K), ``illuminance`` (lx, at the camera target facing a
point light; on a surface open to the whole environment) and a point
light's ``position`` (m); the key light's ``ambient`` (default 0): the share
of its illuminance added, at its temperature, as a uniform sky (the base
level's fill light: no pure-black shadow, and still one spectrum, so the
base's limit holds); ``[[prop]]``: ``name``,
``reflectance``, ``shape`` (``rectangle``, the square [−1, 1]² facing +z, or
``cube``, [−1, 1]³), ``size`` (m: x, y and a cube's z), ``position`` (m, its
centre), ``rotate`` (degrees about x, y, z).

A skin spec is any reflectance spec of a chart scene (``SET:SAMPLE``,
``SET:#N``, ``perfect``, ``grey:F``) or the skin model's parameters,
``skin-model:melanin=0.05,blood=0.02`` (any fields of
:class:`~skinrender.datasets.skin_model.SkinParameters`, the others at
their defaults).
"""

from __future__ import annotations

import math
import copy
import dataclasses
import functools
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ...errors import SkinrenderError
from ...files import exists
from ...hints import NDArrayFloat
from ...spectra import GRID_DEFAULT, WavelengthGrid
from ...toml_tables import entry, from_table, read_toml
from ..scene import PIXELS_MAX, ROOT_SCENES, check_mesh_file, read_scene_toml, reflectance_of

__all__ = ["ROOT_FACE_SCENES", "MESH_HEAD", "PROP_SHAPES", "FaceCamera", "Light", "Prop", "FaceScene",
           "skin_reflectance_of", "load_face_scene", "list_face_scenes", "is_face_scene", "prevailing_name"]

ROOT_FACE_SCENES = ROOT_SCENES / "face"
"""Bundled face scene files."""

MESH_HEAD = "head"
"""The ``[mesh] file`` naming the bundled head scan."""

MESH_SUFFIXES = (".obj", ".ply")
"""Mesh files Mitsuba loads directly."""

PROP_SHAPES = {
    "rectangle": "the square [-1, 1]² in the xy plane, facing +z (a card, a board)",
    "cube": "the cube [-1, 1]³ (a box)",
}
"""Prop shapes, name → meaning."""

Vector = tuple[float, float, float]


@dataclass(frozen=True)
class FaceCamera:
    """A perspective camera: ``position`` and ``target`` (m), ``up``, horizontal ``fov`` (degrees), pixels."""

    position: Vector
    target: Vector
    up: Vector
    fov: float
    width: int
    height: int


@dataclass(frozen=True)
class Light:
    """
    A Planckian light: ``temperature`` (K), ``illuminance`` (lx) and, for a
    point light, ``position`` (m; ``None`` for the uniform environment).
    """

    temperature: float
    illuminance: float
    position: Vector | None = None


@dataclass(frozen=True)
class Prop:
    """A prop: its ``name``, ``reflectance``, ``shape``, ``size``, ``position`` (m) and ``rotate``."""

    name: str
    reflectance: str
    shape: str
    size: Vector
    position: Vector
    rotate: Vector = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class FaceScene:
    """
    A parsed face scene (see the module docstring for the fields).

    ``mesh`` is :data:`MESH_HEAD` or the absolute path of a mesh file.
    """

    name: str
    description: str
    camera: FaceCamera
    mesh: str
    mesh_translate: Vector
    mesh_rotate: Vector
    mesh_scale: float
    skin: str
    key: Light | None
    fill: Light | None = None
    environment: Light | None = None
    props: tuple[Prop, ...] = ()
    source: str = ""
    mesh_smooth: bool = True
    ambient: float = 0.0
    """The share of the key light's illuminance added at its temperature as a uniform sky (the base's fill)."""

    @property
    def ambient_light(self) -> Light | None:
        """The key light's ambient sky: a uniform environment at the key's temperature and ``ambient`` times its
        illuminance (``None`` without a key light or an ambient share)."""
        if self.key is None or not self.ambient > 0:
            return None
        return Light(self.key.temperature, self.key.illuminance * self.ambient)

    def resized(self, width: int, height: int | None = None) -> FaceScene:
        """The scene at another image size, pixels (the field of view kept)."""
        return replace(self, camera=replace(self.camera, width=int(width), height=int(height or width)))

    def translated(self, translate_mm) -> FaceScene:
        """
        The whole scene moved by ``translate_mm`` (x, y, z, mm): the camera (position and target), the mesh, the
        props and the point lights; the skies are uniform and stay as they are.
        """
        offset = np.asarray(translate_mm, dtype=np.float64) / 1000.0

        def moved(point):
            return None if point is None else tuple(float(v) for v in np.add(point, offset))

        def light(item: Light | None) -> Light | None:
            return None if item is None else replace(item, position=moved(item.position))

        return replace(self, camera=replace(self.camera, position=moved(self.camera.position),
                                            target=moved(self.camera.target)),
                       mesh_translate=moved(self.mesh_translate), key=light(self.key), fill=light(self.fill),
                       environment=light(self.environment),
                       props=tuple(replace(prop, position=moved(prop.position)) for prop in self.props))


def skin_reflectance_of(spec: str, grid: WavelengthGrid = GRID_DEFAULT, where: str = "skin") -> NDArrayFloat:
    """
    The reflectance of a skin spec on ``grid`` (fractions): a reflectance
    spec of a chart scene, or ``skin-model:NAME=VALUE,…`` (the skin model's
    parameters, :func:`~skinrender.rendering.scene.skin_parameters_of`).

    Examples
    --------
    >>> skin_reflectance_of("macbeth:light skin").shape
    (301,)
    """
    return reflectance_of(spec, grid, where)


def list_face_scenes() -> list[str]:
    """Names of the bundled face scenes."""
    return sorted(p.stem for p in ROOT_FACE_SCENES.glob("*.toml"))


def is_face_scene(spec) -> bool:
    """
    Whether a scene spec is a face scene: a :class:`FaceScene`, a bundled name, or a TOML with ``[camera]`` and
    ``[mesh]`` (anything else is left to the chart scenes, which word their own errors).

    >>> is_face_scene("face"), is_face_scene("macbeth")
    (True, False)
    """
    if isinstance(spec, FaceScene):
        return True
    text = str(spec).strip()
    if text in list_face_scenes():
        return True
    table = _face_toml(Path(text))  # anything but a readable TOML is left to the chart's loader, which words it
    return table is not None and "camera" in table and "mesh" in table


def _face_toml(path: Path) -> dict | None:
    """
    The table of a ``.toml`` file (a copy), or ``None`` where it is no readable TOML; parsed once per version of
    the file (its path, modification time and size): :func:`is_face_scene` asks, :func:`load_face_scene` loads.
    """
    import os

    try:
        if path.suffix != ".toml" or not exists(path) or not path.is_file():
            return None
        stat = os.stat(path)
        return copy.deepcopy(_parsed(str(path.resolve()), stat.st_mtime_ns, stat.st_size))
    except (SkinrenderError, OSError):
        return None


@functools.lru_cache(maxsize=16)
def _parsed(path: str, mtime_ns: int, size: int) -> dict:
    return read_toml(path, "a scene TOML")


def prevailing_name(scene: FaceScene) -> str:
    """The light the white balance calls prevailing: ``key``, or ``environment`` in a scene without a key light."""
    return "key" if scene.key is not None else "environment"


def _size(value, shape: str, where: str) -> Vector:
    count = 2 if shape == "rectangle" else 3
    ok = isinstance(value, list) and len(value) == count and all(
        isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) and v > 0 for v in value)
    if not ok:
        raise SkinrenderError(f"{where}: field 'size' of a {shape} must be {count} finite numbers > 0 (m), "
                              f"got {value!r}")
    return (*(float(v) for v in value), 0.0)[:3]


def _checked_camera(camera: FaceCamera, where: str) -> FaceCamera:
    """A camera's fields together: a field of view below 180°, a view direction, an up not along it, pixels."""
    if camera.fov == 180.0:
        raise SkinrenderError(f"{where}: field 'fov' must be below 180 degrees, got 180")
    view = np.subtract(camera.target, camera.position)
    if np.linalg.norm(view) == 0:
        raise SkinrenderError(f"{where}: fields 'position' and 'target' coincide: the camera looks nowhere")
    if np.linalg.norm(np.cross(view, camera.up)) <= 1e-9 * np.linalg.norm(view) * np.linalg.norm(camera.up):
        raise SkinrenderError(f"{where}: field 'up' {list(camera.up)} is parallel to the view direction "
                              "(or zero)")
    if camera.width * camera.height > PIXELS_MAX:
        raise SkinrenderError(f"{where}: fields 'width' × 'height' = {camera.width * camera.height} "
                              f"pixels, more than {PIXELS_MAX}")
    return camera


def _mesh(name: str, where: str, folder: Path) -> str:
    if name == MESH_HEAD:
        return MESH_HEAD
    path = Path(name) if Path(name).is_absolute() else folder / name
    if path.suffix.lower() not in MESH_SUFFIXES:
        raise SkinrenderError(f"{where}: field 'file' must be {MESH_HEAD!r} or an .obj or .ply path, got {name!r}")
    if not exists(path):  # anything else than a regular file: refused by check_mesh_file, saying what it is
        raise SkinrenderError(f"{where}: field 'file': mesh {path} does not exist")
    check_mesh_file(path, f"{where}: field 'file': mesh {path}")
    return str(path.resolve())


_XYZ = entry("vector")
_ZERO = (0.0, 0.0, 0.0)


@dataclass(frozen=True, kw_only=True)
class _CameraTable:
    """``[camera]`` (the module docstring)."""

    position: Vector = field(metadata=_XYZ)
    target: Vector = field(metadata=_XYZ)
    up: Vector = field(default=(0.0, 1.0, 0.0), metadata=_XYZ)
    fov: float = field(metadata=entry("number", low=0.0, high=180.0, open_low=True))
    width: int = field(metadata=entry("integer", low=1, high=1 << 16))
    height: int = field(metadata=entry("integer", low=1, high=1 << 16))


@dataclass(frozen=True, kw_only=True)
class _MeshTable:
    """``[mesh]``."""

    file: str = field(metadata=entry("text"))
    translate: Vector = field(default=_ZERO, metadata=_XYZ)
    rotate: Vector = field(default=_ZERO, metadata=_XYZ)
    scale: float = field(default=1.0, metadata=entry("number", low=0.0, high=1e6, open_low=True))
    smooth: bool = field(default=True, metadata=entry("boolean"))


_KELVIN = entry("number", low=0.0, high=1e12, open_low=True)
_LUX = entry("number", low=0.0, high=1e9, open_low=True)


@dataclass(frozen=True, kw_only=True)
class _SkyTable:
    """``[environment]``: a uniform sky."""

    temperature: float = field(metadata=_KELVIN)
    illuminance: float = field(metadata=_LUX)


@dataclass(frozen=True, kw_only=True)
class _PointTable(_SkyTable):
    """``[key]``, ``[fill]``: a point light."""

    position: Vector = field(metadata=_XYZ)


@dataclass(frozen=True, kw_only=True)
class _KeyTable(_PointTable):
    """``[key]``: the key light, and the share of its illuminance added at its temperature as a uniform sky."""

    ambient: float = field(default=0.0, metadata=entry("number", low=0.0, high=10.0))


@dataclass(frozen=True, kw_only=True)
class _PropTable:
    """A ``[[prop]]`` (its size is checked against its shape once both are read)."""

    reflectance: str = field(metadata=entry("text"))
    shape: str = field(default="rectangle", metadata=entry("text"))
    size: object = field(default=None, metadata=entry("any"))
    name: str | None = field(default=None, metadata=entry("text"))
    position: Vector = field(metadata=_XYZ)
    rotate: Vector = field(default=_ZERO, metadata=_XYZ)


@dataclass(frozen=True, kw_only=True)
class _FaceTable:
    """A face scene file's table, in the order its fields are checked."""

    camera: _CameraTable = field(metadata=entry("table", schema=_CameraTable))
    mesh: _MeshTable = field(metadata=entry("table", schema=_MeshTable))
    key: _KeyTable = field(metadata=entry("table", schema=_KeyTable))
    fill: _PointTable | None = field(default=None, metadata=entry("table", schema=_PointTable))
    environment: _SkyTable | None = field(default=None, metadata=entry("table", schema=_SkyTable))
    skin: str = field(metadata=entry("text"))
    prop: tuple[_PropTable, ...] = field(default=(), metadata=entry("tables", schema=_PropTable))
    name: str | None = field(default=None, metadata=entry("text"))
    description: str = field(default="", metadata=entry("text"))


def _light(table: _SkyTable | None) -> Light | None:
    return None if table is None else Light(table.temperature, table.illuminance, getattr(table, "position", None))


def _prop(table: _PropTable, where: str) -> Prop:
    reflectance_of(table.reflectance, GRID_DEFAULT, f"{where}: field 'reflectance'")
    if table.shape not in PROP_SHAPES:
        raise SkinrenderError(f"{where}: field 'shape' must be one of {', '.join(PROP_SHAPES)}, got {table.shape!r}")
    size = _size(table.size, table.shape, where)
    name = table.reflectance.split(":", 1)[-1] if table.name is None else table.name
    return Prop(name, table.reflectance, table.shape, size, table.position, table.rotate)


def _read(spec: str) -> tuple[Path, dict]:
    path = Path(str(spec).strip())
    table = _face_toml(path)  # a face TOML that is_face_scene read: parsed once
    if table is not None:
        return path, table
    return read_scene_toml(spec, ROOT_FACE_SCENES, "face scene", f"bundled: {', '.join(list_face_scenes())}")


def load_face_scene(spec: str | Path | FaceScene) -> FaceScene:
    """
    A face scene from a bundled name (``face``) or a TOML path.

    Raises
    ------
    SkinrenderError
        Unknown name, unreadable TOML, or a missing, unknown or bad field
        (the file and the field named), a mesh file that does not exist, a
        reflectance that does not resolve.

    Examples
    --------
    >>> scene = load_face_scene("face")
    >>> scene.mesh, scene.key.temperature, len(scene.props)
    ('head', 2856.0, 4)
    """

    if isinstance(spec, FaceScene):
        return spec
    path, table = _read(str(spec))
    where = str(path)
    face = from_table(_FaceTable, table, where)
    camera = _checked_camera(FaceCamera(**dataclasses.asdict(face.camera)), f"{where}: [camera]")
    mesh = face.mesh
    mesh_file = _mesh(mesh.file, f"{where}: [mesh]", path.parent)
    skin_reflectance_of(face.skin, GRID_DEFAULT, f"{where}: field 'skin'")
    props = [_prop(table, f"{where}: prop {number}") for number, table in enumerate(face.prop, start=1)]
    names = [p.name for p in props]
    duplicated = sorted({n for n in names if names.count(n) > 1} | ({"skin", "background"} & set(names)))
    if duplicated:
        names = ", ".join(repr(n) for n in duplicated)
        raise SkinrenderError(f"{where}: prop names must be unique and not 'skin' or 'background' (they "
                              f"name labels), got {names} more than once or reserved")
    return FaceScene(path.stem if face.name is None else face.name, face.description, camera, mesh_file,
                     mesh.translate, mesh.rotate, mesh.scale, face.skin, _light(face.key), _light(face.fill),
                     _light(face.environment), tuple(props), where, mesh.smooth, face.key.ambient)
