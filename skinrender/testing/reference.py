"""
Stored reference renders
========================

A reference is two files beside each other: ``NAME.exr`` (the image, float32, channels named by the camera,
a face's ``label`` channel; the camera's curves' hash and the settings in its header) and ``NAME.json`` (the
sidecar: the settings, the EXR's SHA-256, and what is compared: each value's name, mean, standard error and
degrees of freedom). The means are recomputed from the EXR at every check (the EXR is the reference); the
standard errors come from the sidecar (a face's come from its replicates, which the EXR does not hold).

What a check reads from the sidecar is covered by a hash, so that a hand edit cannot switch the check off (every
``standard_error`` set to 1e30, or ``dof`` to 0, made a different camera pass): the SHA-256 of its settings,
channels, regions and compared values (:func:`statistics_sha256`) is written into the EXR's header
(``statistics_sha256``), and the EXR's own SHA-256 into the sidecar; a check recomputes both. The stored
standard errors must be finite and ≥ 0 and the degrees of freedom > 0.

-   :func:`write_reference`: both files, each written to a temporary name and renamed into place.
-   :func:`read_reference`, :class:`Reference`: both files checked (a missing, unreadable or foreign file, an
    EXR changed after its sidecar was written, each has its own one-line message).
-   :func:`state`: ``missing``, ``ours`` or a refusal, before anything is overwritten.

Units: output units (Eq. 4) for images and means, NCC fractions.
"""

from __future__ import annotations

import hashlib
import io
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..files import EXR_BYTES_MAX, Output, read_input, write_outputs
from ..hints import NDArrayFloat
from ..rendering.settings import SEED_MAX
from .regression import Measurement, values_of

__all__ = ["FORMAT", "FORMATS_KNOWN", "reference_seed", "statistics_sha256", "Reference", "ReferenceProblem", "shown", "sidecar_of", "state", "write_reference",
           "read_reference"]

FORMAT = 2
"""The sidecar format (key ``skinrender_reference``). 2: the reference rendered with its own seed
(:func:`reference_seed`), its statistics hashed into the EXR's header, a CSV
camera's path relative to the test file. A format-1 reference is refused with the command that rewrites it."""

FORMATS_KNOWN = (1, 2)
"""Sidecar formats that are skinrender's: ``--skinrender-regen`` may rewrite them; a check reads :data:`FORMAT`."""


def reference_seed(seed: int) -> int:
    """
    The seed a check's reference renders with, drawn from the check's ``seed`` by numpy's ``SeedSequence`` (a
    hash: the reference's sample streams are independent of the check's).

    Mitsuba seeds each pixel's sample stream from (seed, pixel): a reference rendered with the check's own seed
    at 4× its spp began with the check's very samples (on the scalar variants exactly, on LLVM in one pixel of
    four), so the difference's variance was 0.55–0.97 of what the test assumes, its family-wise false-alarm rate
    fell from 0.01 to 6e-5–0.003 and a shift had to be 1.1–1.3× larger to be caught. Never within one of
    ``seed`` (each measurement's calibration render takes seed + 1), and at most :data:`SEED_MAX`.

    >>> reference_seed(0), reference_seed(0) == reference_seed(0), reference_seed(1) == reference_seed(0)
    (..., True, False)
    """
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed <= SEED_MAX:
        raise SkinrenderError(f"seed must be an integer in [0, {SEED_MAX}], got {seed!r}", role="seed")
    seed = int(seed)
    for candidate in np.random.SeedSequence([seed, 0x2EFE2E]).generate_state(8):
        candidate = int(candidate)
        if candidate <= SEED_MAX and abs(candidate - seed) > 1:
            return candidate
    raise SkinrenderError(f"seed {seed}: no independent reference seed found")  # 8 draws all within 1: never


class ReferenceProblem(SkinrenderError):
    """A reference that is missing, unreadable, foreign or does not fit the check."""


@dataclass(frozen=True)
class Reference:
    """A stored reference: its image (and a face's labels), the means recomputed from them, the sidecar."""

    path: Path
    image: NDArrayFloat
    labels: NDArrayFloat | None
    mean: NDArrayFloat
    standard_error: NDArrayFloat
    dof: NDArrayFloat
    sidecar: dict

    @property
    def settings(self) -> dict:
        """What made it (:attr:`~skinrender.testing.regression.Measurement.settings`)."""
        return self.sidecar["settings"]

    @property
    def items(self) -> tuple[str, ...]:
        """The compared values' names."""
        return tuple(item["name"] for item in self.sidecar["compared"]["items"])


def shown(path: Path) -> Path:
    """``path`` relative to the working folder where it lies inside it (as pytest shows test files)."""
    try:
        return Path(path).resolve().relative_to(Path.cwd().resolve())
    except ValueError:
        return Path(path)


def sidecar_of(path: Path) -> Path:
    """The JSON sidecar of a reference EXR."""
    return Path(path).with_suffix(".json")


SIDECAR_BYTES_MAX = 10_000_000
"""Largest reference sidecar read, bytes (a face's is a few kB)."""


def _sha256(path: Path) -> str:
    """The SHA-256 of a reference EXR, read only if it is a regular file of bounded size."""
    try:
        return hashlib.sha256(read_input(path, EXR_BYTES_MAX, "a reference EXR")).hexdigest()
    except SkinrenderError as error:
        raise ReferenceProblem(f"the reference render is unusable ({error}): restore it, or delete it and its "
                               "sidecar and rerun with --skinrender-regen") from None


def _load_sidecar(path: Path) -> dict:
    sidecar = sidecar_of(path)
    try:
        document = json.loads(read_input(sidecar, SIDECAR_BYTES_MAX, "a reference sidecar").decode("utf-8"))
    except SkinrenderError as error:
        raise ReferenceProblem(f"the reference's sidecar is unusable ({error}); it was not rewritten: delete it (and "
                               f"{Path(path).name}) to regenerate") from None
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise ReferenceProblem(f"the reference's sidecar {shown(sidecar)} is unreadable ({type(error).__name__}: "
                               f"{error}); it was not rewritten: delete it (and {Path(path).name}) to regenerate"
                               ) from None
    if not isinstance(document, dict) or document.get("skinrender_reference") not in FORMATS_KNOWN:
        raise ReferenceProblem(f"{shown(sidecar)} is not a skinrender reference sidecar (no 'skinrender_reference': "
                               f"{FORMAT}); it was not overwritten: move it away or give the check another basename")
    return document


STATISTICS = ("settings", "channels", "regions", "compared")
"""The sidecar's keys a check reads, which :func:`statistics_sha256` covers."""


def statistics_sha256(document: dict) -> str:
    """
    The SHA-256 of what a check reads from a sidecar (:data:`STATISTICS`), as canonical JSON (keys sorted, no
    spaces): the same for the document written and the one read back.

    >>> statistics_sha256({"settings": {}, "channels": [], "regions": [], "compared": {"items": []}})[:12]
    '9f344f7079a8'
    """
    covered = {key: document.get(key) for key in STATISTICS}
    text = json.dumps(covered, sort_keys=True, ensure_ascii=False, separators=(",", ":"))
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def state(path: Path) -> str:
    """
    ``missing`` (neither file), ``ours`` (a readable skinrender sidecar, the EXR there or not); a
    :class:`ReferenceProblem` for an EXR without a sidecar (foreign: never overwritten) or a sidecar that is
    unreadable or not ours.
    """
    path, sidecar = Path(path), sidecar_of(path)
    if not path.exists() and not sidecar.exists():
        return "missing"
    if not sidecar.exists():
        raise ReferenceProblem(f"{shown(path)} is there but its sidecar {sidecar.name} is not: it is not a skinrender "
                               "reference (or its sidecar was lost); it was not overwritten: move it away or give "
                               "the check another basename")
    _load_sidecar(path)
    return "ours"


def _json_number(value: float) -> float | None:
    return float(value) if math.isfinite(value) else None


def write_reference(path: Path, measurement: Measurement, alpha: float) -> tuple[Path, Path]:
    """
    Write ``measurement`` as the reference ``path`` (EXR) and its sidecar, both whole or neither
    (:func:`skinrender.files.write_outputs`: no half-written reference is ever left); returns both paths.
    """
    from ..rendering.exr import write_exr

    path = Path(path)
    settings = measurement.settings
    header = {key: json.dumps(value) if not isinstance(value, str) else value for key, value in settings.items()}
    header["skinrender_reference"] = str(FORMAT)
    names = measurement.channels
    image = measurement.image
    if measurement.labels is not None:
        names, image = (*names, "label"), np.concatenate([image, measurement.labels[..., None].astype(np.float32)],
                                                         axis=-1)
    regions = measurement.regions if isinstance(measurement.regions, dict) else list(measurement.regions)
    document = {
        "skinrender_reference": FORMAT,
        "exr": path.name,
        "exr_sha256": None,
        "statistics_sha256": None,
        "settings": settings,
        "channels": list(measurement.channels),
        "regions": regions,
        "compared": {
            "test": ("difference of each value from the check's over the combined standard error of both, "
                     "Student t, Šidák over all values (skinrender.testing.regression)"),
            "alpha_when_written": alpha,
            "items": [{"name": n, "mean": float(m), "standard_error": float(s), "dof": _json_number(d)}
                      for n, m, s, d in zip(measurement.items, measurement.mean, measurement.standard_error,
                                            measurement.dof)],
        },
    }
    # round-tripped through JSON first, so that the hash is of what a check will read back
    document = json.loads(json.dumps(document))
    document["statistics_sha256"] = header["statistics_sha256"] = statistics_sha256(document)
    exr = io.BytesIO()
    write_exr(exr, image, names, header)
    document["exr_sha256"] = hashlib.sha256(exr.getvalue()).hexdigest()
    sidecar = sidecar_of(path)
    write_outputs(Output(path, None, exr.getvalue()),
                  Output(sidecar, None, json.dumps(document, indent=1, ensure_ascii=False) + "\n"))
    return path, sidecar


def read_reference(path: Path, new: Measurement) -> Reference:
    """
    The reference ``path`` for the check ``new``: both files read and checked, and its means recomputed from
    the EXR in the order of ``new``'s values. A :class:`ReferenceProblem` (one line) when a file is missing,
    unreadable or foreign, the EXR changed after the sidecar was written, or the reference is of another kind,
    size or set of patches/regions than the check.
    """
    from ..rendering.exr import read_exr

    path = Path(path)
    document = _load_sidecar(path)
    if document["skinrender_reference"] != FORMAT:
        raise ReferenceProblem(f"{shown(path)} was written by an older skinrender (reference format "
                               f"{document['skinrender_reference']}, rendered with the check's own seed): rerun with "
                               "--skinrender-regen to write it again")
    if not path.exists():
        raise ReferenceProblem(f"the reference render {shown(path)} is missing (its sidecar {sidecar_of(path).name} is "
                               "there): restore it, or delete the sidecar and rerun with --skinrender-regen")
    if _sha256(path) != document.get("exr_sha256"):
        raise ReferenceProblem(f"{shown(path)} changed after its sidecar was written (SHA-256 differs): restore it, or "
                               "rerun with --skinrender-regen to write both again")
    try:
        settings, compared = document["settings"], document["compared"]["items"]
        kind, channels = settings["kind"], tuple(document["channels"])
        names = [item["name"] for item in compared]
        se = np.array([item["standard_error"] for item in compared], dtype=np.float64)
        dof = np.array([np.inf if item["dof"] is None else item["dof"] for item in compared], dtype=np.float64)
    except (KeyError, TypeError, ValueError) as error:
        raise ReferenceProblem(f"the sidecar {shown(sidecar_of(path))} lacks {error} (not written by this version of "
                               "skinrender?): rerun with --skinrender-regen") from None
    _check_statistics(path, document, se, dof)
    if kind != new.kind:
        raise ReferenceProblem(f"{shown(path)} is the reference of a {kind}, the check renders a {new.kind}: rerun with "
                               "--skinrender-regen if the scene changed on purpose")
    try:
        labelled = new.labels is not None  # a face's (the reference's kind is the check's)
        stored = read_exr(path, (*channels, "label") if labelled else channels)
    except Exception as error:  # OpenEXR raises bare exceptions for a damaged file
        raise ReferenceProblem(f"the reference render {shown(path)} is unreadable ({' '.join(str(error).split())}): "
                               "restore it, or delete it and its sidecar and rerun with --skinrender-regen") from None
    image, labels = stored[..., :3], (stored[..., 3].astype(np.int32) if labelled else None)
    if image.shape != new.image.shape:
        (h, w), (nh, nw) = image.shape[:2], new.image.shape[:2]
        raise ReferenceProblem(f"{shown(path)} is {w}×{h} pixels, the render now {nw}×{nh}: the scene or its size "
                               "changed; rerun with --skinrender-regen if on purpose")
    if tuple(names) != tuple(new.items):
        gone = [n for n in names if n not in new.items][:4]
        added = [n for n in new.items if n not in names][:4]
        raise ReferenceProblem(f"the values compared differ from {shown(path)}'s (the reference has {gone or 'no others'}"
                               f", the render now {added or 'no others'}): the scene changed; rerun with "
                               "--skinrender-regen if on purpose")
    regions = document.get("regions")
    mean = values_of(kind, image, labels, regions, new.scene)
    return Reference(path, image, labels, mean, se, dof, document)


def _check_statistics(path: Path, document: dict, se: NDArrayFloat, dof: NDArrayFloat) -> None:
    """The sidecar's statistics are those written with the EXR (their hash in its header) and are standard errors
    and degrees of freedom at all; a :class:`ReferenceProblem` otherwise."""
    from ..rendering.exr import read_exr_attributes

    try:
        stored = read_exr_attributes(path).get("statistics_sha256")
    except Exception as error:  # OpenEXR raises bare exceptions for a damaged file
        raise ReferenceProblem(f"the reference render {shown(path)} is unreadable ({' '.join(str(error).split())}): "
                               "restore it, or delete it and its sidecar and rerun with --skinrender-regen") from None
    found = statistics_sha256(document)
    if stored is None or found != stored or document.get("statistics_sha256") != stored:
        raise ReferenceProblem(f"the sidecar {shown(sidecar_of(path))} was changed after the reference was written "
                               f"(its settings or statistics no longer match the SHA-256 in {path.name}'s header): "
                               "restore it, or rerun with --skinrender-regen to write both again")
    if not (np.all(np.isfinite(se)) and np.all(se >= 0) and np.all(dof > 0)):
        raise ReferenceProblem(f"the sidecar {shown(sidecar_of(path))} holds standard errors that are not finite and "
                               "≥ 0, or degrees of freedom ≤ 0: rerun with --skinrender-regen")
