"""
A chart validation's document
=============================

The JSON document of a chart's validation, one for every front door: ``skinrender validate CHART --json`` prints
it (with the verdict and exit status the command adds), :meth:`~skinrender.rendering.validation.Validation.document`
returns it to Python.

-   :func:`chart_document`: the document of a :class:`~skinrender.rendering.validation.Validation`.
-   :func:`subsurface_keys`: what a subsurface chart's document (and its render's) adds.
-   :data:`SIGMAS_DEPRECATED`: why the key ``sigmas`` is kept and what to read instead.
"""

from __future__ import annotations

__all__ = ["SIGMAS_DEPRECATED", "chart_document", "subsurface_keys"]

SIGMAS_DEPRECATED = (
    "deprecated, to be removed in a later release: the tolerance is no longer k standard errors (k was 5) but "
    "relative (--tolerance); 'sigmas' is now the equivalence's critical value c, the standard errors added in each "
    "bound |error| + c·SE: read checks.equivalence.critical")
"""The JSON's ``deprecated.sigmas``: why ``sigmas`` is kept and what to read instead."""


def chart_document(validation, spp_requested=None) -> dict:
    """
    The document of a chart's ``validation``: the render (scene, camera, lights K, normalisation, knee, spp used
    and ``spp_requested``, sampler, seed, variant, seconds), the tolerance (relative), the white level and dark
    floor (output units), the bound and spp needed, both checks' verdicts, every patch's values, errors, bounds
    and tolerances (output units), the worst patches, and a subsurface chart's skin slabs
    (:func:`subsurface_keys`); ``spp_auto`` where the spp was chosen (``spp="auto"``).
    """
    from .agreement import DARK_LEVEL

    r, tolerance = validation.rendering, validation.tolerance_relative
    checks = {"equivalence": validation.verdict, "difference": validation.difference}
    document = {"scene": r.scene.name, "camera": r.camera.name, "prevailing_K": r.prevailing,
                "calibration_K": r.calibration, "normalization": r.normalization, "knee": r.knee,
                "spp": r.raw[0].spp, "spp_requested": spp_requested, "sampler": r.raw[0].sampler,
                "seed": r.raw[0].seed, "variant": r.variant, "elapsed_s": r.seconds, "tolerance": tolerance,
                "white_level": validation.white_level,
                "dark_floor_output": tolerance * DARK_LEVEL * validation.white_level,
                "sigmas": validation.verdict.details.get("critical"), "deprecated": {"sigmas": SIGMAS_DEPRECATED},
                "bound": validation.bound, "spp_needed": validation.spp_needed,
                "checks": {name: v.document() for name, v in checks.items()}, "patches": validation.patches(),
                "worst": validation.worst(), "max_rel_error": float(validation.rel_error.max()),
                "quadrature_rel_difference": validation.quadrature}
    document.update(subsurface_keys(r, document["patches"]))  # subsurface: each skin patch's slab
    if validation.spp_auto is not None:
        document["spp_auto"] = validation.spp_auto
    return document


def subsurface_keys(rendering, rows: list[dict] | None = None) -> dict:
    """
    The keys a subsurface chart's JSON adds (``{}`` at ``direct``): ``physics``, ``light`` (the sky), and per
    patch ``skin_model``: the layers' ``spec``, ``source`` (``parameters`` or ``fit``), ``parameters``,
    ``fit_rms``, ``bounds_hit`` and ``dermis_mm`` (the rendered dermis' thickness at ``subsurface-volume``;
    ``None`` at ``subsurface``, whose table is the model's semi-infinite dermis) (``None`` for a Lambertian
    patch), as a list in the scene's order, or, given the document's per-patch ``rows``, added to each row.
    """
    if "skin_model" not in rendering.info:  # the chart's level renders no slab
        return {}
    models = rendering.info["skin_model"]
    keys = {"physics": rendering.info["physics"],
            "light": "a uniform sky of radiance P(λ)/π (Planck's P at the prevailing temperature), seen straight "
                     "down: a skin patch's analytic value is Eq. 4 of its slab's adding-doubling reflectance (total, "
                     "collimated normal incidence)"}
    if rows is None:
        return {**keys, "skin_model": models}
    for row, model in zip(rows, models):
        row["skin_model"] = model
    return keys
