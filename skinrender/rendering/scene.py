"""
Chart scenes
============

A chart scene is a plain TOML file (``scenes/*.toml``): a grid of flat
Lambertian patches, each naming its reflectance, plus an ideal white
reference patch, seen straight on by an orthographic camera under one
directional emitter. The renderer models only that: direct lighting, no
interreflection (a flat chart has none), no polarisation, no depth of field.

-   :class:`Patch`, :class:`ChartScene`: a parsed scene.
-   :func:`load_chart_scene`: a chart scene from a name in ``scenes/`` or a
    path; a bad file gets an error naming the file and the field (charts and
    faces alike: :func:`skinrender.rendering.dispatch.load_scene`).
-   :func:`list_scenes`: the bundled scene names.
-   :func:`check_mesh_file`: a face scene's ``.obj``/``.ply`` mesh checked before any render.

Scene file fields
-----------------
``name`` (str), ``description`` (str), ``columns`` (int ≥ 1),
``patch_px`` (int ≥ 3, patch side in pixels), ``gap_px`` (int ≥ 0, black
gap), ``border_px`` (int ≥ 0, pixels left out at each patch edge when
averaging), ``white`` (reflectance of the white reference, default
``perfect``), and ``[[patch]]`` tables with ``reflectance`` and optional
``name`` and ``skin`` (bool, for detection).

A reflectance is ``SET:SAMPLE`` (a set name from ``skinrender datasets`` and
a sample name), ``SET:#N`` (the N-th sample, from 0), ``perfect`` (ρ = 1),
``grey:F`` (ρ = F for every wavelength) or the skin model's parameters,
``skin-model:melanin=0.05,blood=0.02`` (any fields of
:class:`~skinrender.datasets.skin_model.SkinParameters`, the others at their
defaults; :func:`skin_parameters_of`): its adding-doubling reflectance, and
under ``--physics subsurface`` or ``subsurface-volume`` its layers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..datasets import reflectances
from ..errors import SkinrenderError, flag_of
from ..files import MESH_BYTES_MAX, exists, read_input
from ..hints import NDArrayFloat
from ..spectra import GRID_DEFAULT, WavelengthGrid
from ..toml_tables import entry, from_table, read_toml

__all__ = ["ROOT_SCENES", "Patch", "ChartScene", "load_chart_scene", "list_scenes", "read_scene_toml", "reflectance_of",
           "skin_parameters_of", "check_mesh_file"]

ROOT_SCENES = Path(__file__).resolve().parent / "scenes"
"""Bundled scene files (installed with the package; ``scenes/`` in the repository links here)."""


@dataclass(frozen=True)
class Patch:
    """One chart patch: its ``name``, ``reflectance`` spec and whether it is ``skin``."""

    name: str
    reflectance: str
    skin: bool = False


@dataclass(frozen=True)
class ChartScene:
    """
    A parsed chart scene.

    Attributes
    ----------
    patches
        The patches in reading order (left to right, top to bottom); the
        white reference is the last one.
    """

    name: str
    description: str
    columns: int
    patch_px: int
    gap_px: int
    border_px: int
    patches: tuple[Patch, ...]
    source: str = ""

    @property
    def rows(self) -> int:
        """Rows of patches."""
        return -(-len(self.patches) // self.columns)

    @property
    def size(self) -> tuple[int, int]:
        """Image ``(width, height)`` in pixels."""
        step = self.patch_px + self.gap_px
        return self.columns * step + self.gap_px, self.rows * step + self.gap_px

    @property
    def white_index(self) -> int:
        """Index of the white reference patch (the last)."""
        return len(self.patches) - 1

    def patch_box(self, index: int) -> tuple[int, int, int, int]:
        """Pixel box ``(x0, y0, x1, y1)`` (end exclusive) of a patch, image rows from the top."""
        step = self.patch_px + self.gap_px
        row, column = divmod(index, self.columns)
        x0, y0 = self.gap_px + column * step, self.gap_px + row * step
        return x0, y0, x0 + self.patch_px, y0 + self.patch_px

    def patch_pixels(self, index: int) -> tuple[slice, slice]:
        """Row and column slices of the pixels averaged for a patch (its border left out)."""
        x0, y0, x1, y1 = self.patch_box(index)
        b = self.border_px
        return slice(y0 + b, y1 - b), slice(x0 + b, x1 - b)

    def reflectances(self, grid: WavelengthGrid) -> NDArrayFloat:
        """Patch reflectances on ``grid``, shape ``(len(patches), grid.size)``, fractions."""
        return np.array([reflectance_of(p.reflectance, grid, f"{self.source}: patch {p.name!r}") for p in self.patches])


TEXT_PARAMETERS = ("melanin_law",)
"""The :class:`~skinrender.datasets.skin_model.SkinParameters` fields a ``skin-model:`` spec gives as names, not
numbers (``melanin_law=exponential``)."""


def skin_parameters_of(spec: str, where: str = "reflectance"):
    """
    The :class:`~skinrender.datasets.skin_model.SkinParameters` of a ``skin-model:NAME=VALUE,…`` spec (the
    fields not named at their defaults), or ``None`` for any other spec (``skin-model:#3`` names a sample
    of the ``skin-model`` set). A bad name or value is refused with ``where`` and the parameter named.

    Examples
    --------
    >>> skin_parameters_of("skin-model:melanin=0.2").melanin, skin_parameters_of("skin:#0")
    (0.2, None)
    """
    text = str(spec).strip()
    if not (text.startswith("skin-model:") and "=" in text):
        return None
    from ..datasets.skin_model import SkinParameters, check_parameters

    known = {f.name for f in fields(SkinParameters)}
    values = {}
    for item in text[len("skin-model:"):].split(","):
        key, _, value = item.partition("=")
        key = key.strip()
        if key not in known:
            raise SkinrenderError(f"{where}: {text!r}: unknown skin-model parameter {key!r}; known: "
                                  f"{', '.join(sorted(known))}", flag=flag_of(where))
        if key in values:
            raise SkinrenderError(f"{where}: {text!r}: {key} is given twice; give each parameter once",
                                  flag=flag_of(where))
        if key in TEXT_PARAMETERS:  # a name, checked with the rest below
            values[key] = value.strip()
            continue
        try:
            values[key] = float(value)
        except ValueError:
            raise SkinrenderError(f"{where}: {text!r}: {key} must be a number, "
                                  f"got {value.strip()!r}", flag=flag_of(where)) from None
        if not math.isfinite(values[key]) or values[key] < 0:
            raise SkinrenderError(f"{where}: {text!r}: {key} must be a finite number ≥ 0, "
                                  f"got {value.strip()!r}", flag=flag_of(where))
    parameters = SkinParameters(**values)
    try:
        check_parameters(parameters)
    except SkinrenderError as error:
        raise SkinrenderError(f"{where}: {text!r}: {error}", flag=flag_of(where)) from None
    return parameters


def reflectance_of(spec: str, grid: WavelengthGrid, where: str = "reflectance") -> NDArrayFloat:
    """The reflectance named by a scene spec on ``grid`` (see the module docstring)."""
    text = str(spec).strip()
    parameters = skin_parameters_of(text, where)
    if parameters is not None:
        from ..datasets.skin_model import skin_reflectance

        with np.errstate(all="ignore"):  # a non-finite result is refused below, with no warning on stderr
            reflectance = skin_reflectance(grid.wavelengths, parameters)
        if not np.all(np.isfinite(reflectance)):
            raise SkinrenderError(f"{where}: {text!r} gives no finite reflectance", flag=flag_of(where))
        return reflectance
    if text == "perfect":
        return np.ones(grid.size)
    if text.startswith("grey:"):
        try:
            value = float(text[5:])
        except ValueError:
            value = np.nan
        if not 0 <= value <= 1:
            raise SkinrenderError(f"{where}: grey reflectance must be grey:F with F in [0, 1], got {text!r}",
                                  flag=flag_of(where))
        return np.full(grid.size, value)
    if ":" not in text:
        raise SkinrenderError(f"{where}: reflectance must be SET:SAMPLE, SET:#N, perfect, grey:F or "
                              f"skin-model:NAME=VALUE,…, got {text!r}", flag=flag_of(where))
    set_name, sample = text.split(":", 1)
    try:
        dataset = reflectances(set_name)
    except SkinrenderError as error:
        raise SkinrenderError(f"{where}: {error}", flag=flag_of(where)) from None
    if sample.startswith("#"):
        try:
            index = int(sample[1:])
        except ValueError:
            index = -1
        if not 0 <= index < dataset.count:
            raise SkinrenderError(f"{where}: {text!r}: index must be #0 … #{dataset.count - 1}",
                                  flag=flag_of(where))
    else:
        if sample not in dataset.names:
            raise SkinrenderError(f"{where}: {text!r}: no sample {sample!r} in set {set_name!r}",
                                  flag=flag_of(where))
        index = dataset.names.index(sample)
    return dataset.on(grid)[index]


def read_scene_toml(spec, root: Path, kind: str, bundled: str) -> tuple[Path, dict]:
    """
    The path and TOML table of a scene spec: a bundled name (``root/NAME.toml``; a bare name means the bundled
    scene even where a file or folder of that name stands in the working folder) or a path to a ``.toml``
    file. ``kind`` names the scene in errors (``scene``, ``face scene``); ``bundled`` lists the names.
    """
    text = str(spec).strip()
    if not text:
        raise SkinrenderError(f"expected a {kind} name ({bundled}) or a .toml path, got an empty one")
    path = Path(text)
    named = root / f"{text}.toml"
    if path.suffix != ".toml" and len(path.parts) == 1 and "\0" not in text and len(text) < 200 and named.is_file():
        path = named
    elif exists(path) and path.is_dir():
        raise SkinrenderError(f"{kind} {text} is a folder, expected a .toml file or a bundled name", role="scene")
    elif not (path.suffix == ".toml" or exists(path)):
        raise SkinrenderError(f"unknown {kind} {text!r}; {bundled}, or a .toml path")
    elif not exists(path):
        raise SkinrenderError(f"{kind} file {text} does not exist", role="scene")
    return path, read_toml(path, f"a {kind} TOML")  # a pipe, a device, a huge file: refused unread


def list_scenes() -> list[str]:
    """Names of the bundled scenes."""
    return sorted(p.stem for p in ROOT_SCENES.glob("*.toml"))


@dataclass(frozen=True, kw_only=True)
class _PatchTable:
    """A ``[[patch]]`` table of a chart scene file (the module docstring)."""

    reflectance: str = field(metadata=entry("string"))
    name: str | None = field(default=None, metadata=entry("string"))
    skin: bool = field(default=False, metadata=entry("boolean"))


@dataclass(frozen=True, kw_only=True)
class _ChartTable:
    """A chart scene file's table (the module docstring), in the order its fields are checked."""

    patch: tuple[_PatchTable, ...] = field(metadata=entry("tables", schema=_PatchTable, nonempty=True))
    white: str = field(default="perfect", metadata=entry("string"))
    name: str | None = field(default=None, metadata=entry("string"))
    description: str = field(default="", metadata=entry("string"))
    columns: int = field(metadata=entry("integer", low=1))
    patch_px: int = field(default=14, metadata=entry("integer", low=3))
    gap_px: int = field(default=2, metadata=entry("integer", low=0))
    border_px: int = field(default=0, metadata=entry("integer", low=0))


PIXELS_MAX = 4_000_000
"""Most pixels a chart may have (2000 × 2000)."""


_OBJ = "expected a Wavefront OBJ: text, 'v x y z' vertex and 'f i j k' face lines, indices from 1"
_PLY_BYTES = dict(zip("char uchar int8 uint8 short ushort int16 uint16 double float64 int uint int32 uint32 float "
                      "float32".split(), [1] * 4 + [2] * 4 + [8] * 2 + [4] * 6))


def _obj_line(words: list[str], counts: dict, top: dict) -> bool:
    """Whether a vertex (``v``, ``vt``, ``vn``) or face (``f``: ≥ 3 corners ``v[/vt][/vn]``) line is well formed."""
    try:
        if words[0] != "f":
            counts[words[0]] += 1
            return len(words) >= (3 if words[0] == "vt" else 4) and all(math.isfinite(float(w)) for w in words[1:])
        corners = [[int(i) if i or kind == "v" else None for kind, i in zip(top, w.split("/"))] for w in words[1:]]
    except ValueError:
        return False
    counts["f"] += 1
    given = {kind: [c[k] for c in corners if len(c) > k and c[k] is not None] for k, kind in enumerate(top)}
    top.update({kind: max([top[kind], *indices]) for kind, indices in given.items()})
    return len(corners) >= 3 and min(sum(given.values(), [])) >= 1


def _check_obj(data: bytes, where: str) -> None:
    """Refuse an OBJ Mitsuba cannot render: empty, binary, a bad line or index, no face."""
    if not data.strip() or b"\0" in data:
        raise SkinrenderError(f"{where} is {'binary' if data.strip() else 'empty'}; {_OBJ}")
    counts, top = {"v": 0, "vt": 0, "vn": 0, "f": 0}, {"v": 0, "vt": 0, "vn": 0}
    for number, line in enumerate(data.decode("utf-8", "replace").splitlines(), start=1):
        words = line.split("#", 1)[0].split()
        if words and words[0] in counts and not _obj_line(words, counts, top):
            raise SkinrenderError(f"{where}, line {number}: bad {words[0]!r} line {line.strip()[:40]!r}; {_OBJ}")
    beyond = [f"{kind} {top[kind]} of {counts[kind]}" for kind in top if top[kind] > counts[kind]]
    if beyond or not counts["f"]:
        raise SkinrenderError(f"{where} " + (f"has faces indexing {', '.join(beyond)}" if beyond else
                                             f"has {counts['v']} vertices but no face ('f' line)") + f"; {_OBJ}")


def _check_ply(data: bytes, where: str) -> None:
    """Refuse a PLY Mitsuba cannot render: a bad header, no vertex or face element, a body shorter than it says."""
    end = data.find(b"end_header", 0, 1 << 16)
    lines = [line.split() for line in data[:max(end, 0)].decode("ascii", "replace").splitlines()]
    kind = lines[1][1] if len(lines) > 1 and len(lines[1]) == 3 and lines[1][0] == "format" else ""
    if not data.startswith(b"ply") or end < 0 or kind not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise SkinrenderError(f"{where} has no valid PLY header; expected 'ply', 'format ascii|binary_little_endian|"
                              "binary_big_endian 1.0', 'element vertex N', 'element face M', … 'end_header'")
    elements: dict = {}  # name -> [count, least bytes per row]
    for words in lines[2:]:
        if words[:1] == ["element"] and len(words) == 3 and words[2].isdigit():
            last = elements.setdefault(words[1], [int(words[2]), 0])
        elif words[:1] == ["property"] and elements and words[-2] in _PLY_BYTES:
            last[1] += _PLY_BYTES[words[-2]] * (3 if words[1] == "list" else 1) + _PLY_BYTES.get(words[2], 0)
    (vertices, _), (faces, _) = elements.get("vertex", [0, 0]), elements.get("face", [0, 0])
    if vertices < 3 or not faces:
        raise SkinrenderError(f"{where} has {vertices} vertices and {faces} faces in its header ('element vertex N', "
                              "'element face M'); expected a mesh of ≥ 3 vertices and ≥ 1 face")
    body, unit = data[end + len("end_header\n"):], "lines" if kind == "ascii" else "bytes"
    least = vertices + faces if kind == "ascii" else sum(n * size for n, size in elements.values())
    if (have := len(body.splitlines()) if kind == "ascii" else len(body)) < least:
        raise SkinrenderError(f"{where} is cut short: its header promises {vertices} vertices and {faces} faces "
                              f"({least} {unit} at least), it holds {have}")


def check_mesh_file(path: str | Path, where: str = "mesh") -> None:
    """
    Refuse a mesh file Mitsuba's ``obj`` or ``ply`` plugin could not render, before any render.

    An OBJ must be text with well-formed ``v`` (three coordinates), ``vt``, ``vn`` and ``f`` lines (≥ 3
    corners ``v[/vt][/vn]``, indices from 1 within the file's elements: Mitsuba takes no negative index) and
    at least one face; a PLY a valid header (``ply``, ``format ascii|binary_*_endian 1.0``, ≥ 3 vertices,
    ≥ 1 face) and a body as long as the header promises (index values inside a binary body are not read).

    Raises
    ------
    SkinrenderError
        One line starting with ``where``: what is wrong (empty, binary, the bad line, no face, a bad or
        short PLY) and what was expected.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.NamedTemporaryFile("w", suffix=".obj", delete=False) as file:
    ...     _ = file.write("v 0 0 0\\nv 1 0 0\\nv 0 1 0\\n")
    >>> check_mesh_file(file.name, "--mesh")
    Traceback (most recent call last):
    ...
    skinrender.errors.SkinrenderError: --mesh has 3 vertices but no face ('f' line); expected a Wavefront OBJ: text, 'v x y z' vertex and 'f i j k' face lines, indices from 1
    """
    path = Path(path)
    data = read_input(path, MESH_BYTES_MAX, "a mesh (OBJ or PLY)", where)  # a pipe, too large: after where
    (_check_ply if path.suffix.lower() == ".ply" else _check_obj)(data, where)


def load_chart_scene(spec: str | Path | ChartScene) -> ChartScene:
    """
    A chart scene from a bundled name (``macbeth``, ``skin_patches``,
    ``face_chart``) or a path to a TOML file of the same format; a
    :class:`ChartScene` is returned as it is. A face scene is
    :func:`~skinrender.rendering.face.scene.load_face_scene`'s, either kind
    :func:`~skinrender.rendering.dispatch.load_scene`'s.

    Raises
    ------
    SkinrenderError
        Unknown name (the known ones are listed), unreadable TOML, a missing
        or mistyped field (named), or an unknown reflectance.
    """

    if isinstance(spec, ChartScene):
        return spec
    faces = sorted(p.stem for p in (ROOT_SCENES / "face").glob("*.toml"))
    path, table = read_scene_toml(spec, ROOT_SCENES, "scene", f"bundled scenes: {', '.join(list_scenes())} "
                                  f"(charts), {', '.join(faces)} (faces)")
    where = str(path)
    chart = from_table(_ChartTable, table, where)
    patches = [Patch(p.reflectance.split(":", 1)[-1] if p.name is None else p.name, p.reflectance, p.skin)
               for p in chart.patch]
    patches.append(Patch("white reference", chart.white, False))
    scene = ChartScene(name=path.stem if chart.name is None else chart.name, description=chart.description,
                       columns=chart.columns, patch_px=chart.patch_px, gap_px=chart.gap_px,
                       border_px=chart.border_px, patches=tuple(patches), source=where)
    if 2 * scene.border_px >= scene.patch_px:
        raise SkinrenderError(f"{where}: field 'border_px' ({scene.border_px}) leaves no pixel of a "
                              f"{scene.patch_px}-pixel patch")
    width, height = scene.size
    if width * height > PIXELS_MAX:
        raise SkinrenderError(f"{where}: the chart is {width} × {height} = {width * height:.3g} pixels, more than "
                              f"{PIXELS_MAX:.3g} (a render holds ~{width * height * 12 / 1e9:.2g} GB per image); "
                              "use a smaller patch_px or fewer patches")
    inner = scene.patch_px - 2 * scene.border_px
    if inner * inner < 2:
        raise SkinrenderError(f"{where}: a patch keeps {inner * inner} inner pixel(s); patch statistics need at least 2")
    values = scene.reflectances(GRID_DEFAULT)  # every reflectance resolves, or the error names the patch
    if not np.any(values[-1] > 0):
        raise SkinrenderError(f"{where}: field 'white' ({chart.white}) reflects no light: the white reference balances "
                              "every channel and must not be black")
    return scene
