"""
One compiled kernel per structure: spectral face documents given new values
===========================================================================

Every Mitsuba object loaded in a JIT variant (``llvm_ad_spectral``,
``cuda_ad_spectral``) joins its class's registry, and a render's kernel
dispatches over that registry: a newly loaded document makes a new kernel,
compiled before it runs (measured on the face at 64 px, 16 spp, 61 bands:
~2.5 s of compilation against a 0.12 s render; drjit's disk cache serves it
again only to a process that loaded the same objects in the same order). A
sweep renders the same scene under many lights and skins: documents that
differ only in their values.

So a spectral render keeps one loaded document per *structure* (the scene's
geometry and props, the level's effects, the lights' names and positions, the
bands, spp, sampler, variant) and gives it the next render's values: the
lights' emitters and the skin's material, written as plain dictionaries
(:func:`~skinrender.rendering.face.document.light_documents`,
:func:`~skinrender.rendering.face.document.skin_material`), are flattened to
the parameter names Mitsuba exposes (``mi.traverse``: spectra, sampling
weights, positions, a coat's or a boundary's ``eta`` and ``alpha``, a medium's
coefficients) and copied in. The flattening is checked once per structure,
on the document first loaded: every value parameter it exposes must be found
with the value it holds (to float32 rounding), or the structure is loaded anew
for every render, as before. The copy is exact (tested: the image equals a
fresh document's, bit for bit in one process; a fresh document's kernel, compiled anew after others were
loaded, may round a pixel an ulp apart). ``scalar_spectral`` compiles nothing: there a
fresh document is loaded as before.

-   :func:`spectral_loaded`: the loaded document and its label image.
-   :data:`KEPT`: how many structures are kept.

Units: as the face's documents (metres or the level's scene unit, nm,
W·m⁻²·nm⁻¹ divided by the plan's scale).
"""

from __future__ import annotations

from collections import OrderedDict
from dataclasses import replace

import numpy as np

from ...spectra import WavelengthGrid
from ..variants import mitsuba
from .document import light_documents, skin_material
from .labels import SHAPE_SKIN
from .render import DocumentKey, load_document

__all__ = ["KEPT", "spectral_loaded", "flattened", "release"]

KEPT = 4
"""Structures whose loaded spectral document is kept (the least recently used goes first)."""

_KEPT: OrderedDict = OrderedDict()

_FIXED = ("sensor.", "prop_", "faces", "vertex_", "to_world", "allow_thread_reordering", "silhouette_sampling_weight",
          "wavelengths")
"""Parameters a structure fixes (the camera, the meshes, the props, the spectra's wavelengths): not copied."""

_RENAMED = {"interior": "interior_medium", "phase": "phase_function"}
"""Dictionary keys Mitsuba exposes under another name."""


def release() -> int:
    """Forget the kept documents; how many there were."""
    count = len(_KEPT)
    _KEPT.clear()
    return count


def _structure(plan, bands: WavelengthGrid) -> tuple:
    """What a document's structure depends on: everything but the lights' temperatures and illuminances and the
    skin (its values)."""
    def neutral(light):
        return None if light is None else replace(light, temperature=0.0, illuminance=0.0)

    scene = plan.scene
    geometry = replace(scene, name="", description="", source="", skin="", key=neutral(scene.key),
                       fill=neutral(scene.fill), environment=neutral(scene.environment))
    lights = tuple(sorted((name, light.position) for name, light in plan.lights.items()))
    return plan.variant, bands, plan.grid, plan.spp, plan.sampler, plan.level.document_key, geometry, lights


def _plain(key: str) -> str:
    """A parameter's name without Mitsuba's ``value`` wrappers (a texture's, a volume's)."""
    return ".".join(part for part in key.split(".") if part != "value")


def _flatten(prefix: str, node, out: dict) -> None:
    kind = node.get("type")
    if kind == "irregular":  # its wavelengths are the structure's grid
        out[f"{prefix}.values"] = np.array([float(v) for v in node["values"].split(",")])
        return
    if kind == "uniform":
        out[prefix] = np.array(float(node["value"]))
        return
    if "int_ior" in node and "ext_ior" in node:
        out[f"{prefix}.eta"] = np.array(float(node["int_ior"]) / float(node["ext_ior"]))
    for key, value in node.items():
        if key in ("type", "int_ior", "ext_ior") or isinstance(value, (str, bool)):
            continue
        name = "brdf_0" if kind == "twosided" and key == "bsdf" else _RENAMED.get(key, key)
        if isinstance(value, dict):
            _flatten(f"{prefix}.{name}", value, out)
        else:
            out[f"{prefix}.{name}"] = np.array(value, dtype=np.float64)


def flattened(plan) -> dict:
    """
    The value parameters of the plan's document, by their names without ``value`` wrappers
    (``light_key.intensity.values``, ``skin.bsdf.brdf_0.reflectance.values``, ``skin.interior_medium.scale``):
    NumPy arrays, from the plain dictionaries that build it.
    """
    out = {}
    for name, document in light_documents(plan.scene, plan.level, plan.grid, plan.lights, plan.scale).items():
        _flatten(name, document, out)
    _flatten(SHAPE_SKIN, skin_material(plan.scene, plan.level, plan.grid, plan.skin, plan.lights), out)
    return out


def _values(loaded, variant: str) -> dict:
    """The loaded document's value parameters, ``{plain name: (name, NumPy array)}``."""
    params = mitsuba(variant).traverse(loaded)
    return {_plain(key): (key, np.array(params[key])) for key in params.keys()
            if not any(part in key for part in _FIXED)}


def _matches(loaded, plan) -> bool:
    """Whether :func:`flattened` finds every value parameter of ``loaded`` (built from ``plan``) with its value."""
    found, mine = flattened(plan), _values(loaded, plan.variant)
    if set(found) != set(mine):
        return False
    return all(np.allclose(np.asarray(found[key], dtype=np.float32).ravel(), value.ravel(), rtol=1e-6, atol=0)
               for key, (_, value) in mine.items())


def _revalue(loaded, plan) -> None:
    """Copy the plan's values into ``loaded`` (a document of its structure, whose flattening matched)."""
    mi = mitsuba(plan.variant)
    params = mi.traverse(loaded)
    found = flattened(plan)
    for plain, (key, _) in _values(loaded, plan.variant).items():
        old, value = params[key], found[plain]
        if isinstance(old, (bool, int, float)):
            params[key] = type(old)(float(value))
        elif np.size(value) == 3 and "position" in key:
            params[key] = type(old)(*(float(v) for v in np.ravel(value)))
        else:
            params[key] = type(old)(np.asarray(value, dtype=np.float32).ravel() if np.ndim(value) else float(value))
    params.update()


def _fresh(plan, bands: WavelengthGrid):
    """The plan's document loaded anew (outside the face renderer's cache: its values will change)."""
    return load_document.__wrapped__(DocumentKey(plan.scene, None, plan.grid, bands, plan.level.document_key,
                                                 plan.skin, (), plan.spp, plan.sampler, plan.variant,
                                                 tuple(sorted(plan.lights.items())), plan.scale, plan.level,
                                                 plan.lights))


def spectral_loaded(plan, bands: WavelengthGrid):
    """
    The plan's document with ``bands`` as its film, and its label image: in a JIT variant the kept document of
    its structure given the plan's values (module docstring), else (or the first time) a fresh one.
    """
    if plan.variant.startswith("scalar"):
        loaded = plan.loaded(bands=bands)
        return loaded, plan.labels(loaded)
    key = _structure(plan, bands)
    if key in _KEPT:
        _KEPT.move_to_end(key)
        loaded, labels, revaluable = _KEPT[key]
        if revaluable:
            _revalue(loaded, plan)
            return loaded, labels
    loaded = _fresh(plan, bands)
    kept = _KEPT[key] = (loaded, plan.labels(loaded), _matches(loaded, plan))
    while len(_KEPT) > KEPT:
        _KEPT.popitem(last=False)
    return kept[:2]
