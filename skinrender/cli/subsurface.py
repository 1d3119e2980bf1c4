"""
``--physics subsurface`` on a chart (``render``, ``validate``, ``detect``)
==========================================================================

The chart commands take ``--physics direct`` (the default) or ``subsurface``:
the chart's skin patches rendered as the skin model's two layers under a
dielectric boundary, lit by a uniform sky
(:mod:`skinrender.rendering.subsurface_chart`), each checked by ``validate``
against Eq. 4 of its slab's adding-doubling reflectance.

-   :func:`check_chart_subsurface`: the flags that do not go with it refused,
    and a render too long refused with its estimate, before any work.
-   :func:`subsurface_keys`: what the JSON of a subsurface chart adds.
-   :func:`subsurface_lines`: the text lines it adds.
"""

from __future__ import annotations

import argparse

from ..errors import SkinrenderError

__all__ = ["check_chart_subsurface", "subsurface_keys", "subsurface_lines"]


def check_chart_subsurface(args: argparse.Namespace, inputs, settings):
    """
    The render settings of a chart command (``render``, ``validate``, ``detect``) at its ``--physics``
    (``inputs``: its :class:`~skinrender.cli.inputs.ChartInputs`; ``settings``: the
    :class:`~skinrender.rendering.settings.RenderSettings` of the flags). At ``direct``, ``settings``. At
    ``subsurface``, ``settings`` with :data:`~skinrender.rendering.subsurface_chart.SAMPLER_SUBSURFACE` unless
    ``--sampler`` is given, after refusing, naming the flag, what a subsurface chart does not take (``--imager``
    and its settings, ``--gamut``, ``--spp auto``), a chart without a skin patch, and a render whose estimate
    (:func:`~skinrender.rendering.subsurface_chart.estimate_seconds` on every core) exceeds ``--max-minutes``
    (:func:`skinrender.workload.check_work`, naming ``--spp``).
    """
    if inputs.physics != "subsurface":
        return settings
    import os

    from ..rendering.subsurface_chart import SAMPLER_SUBSURFACE, SAMPLES_PER_S_SLAB, estimate_seconds
    from ..workload import check_work

    for name in ("imager", "illuminance", "exposure"):
        if getattr(args, name, None) is not None:
            raise SkinrenderError(f"--{name}: a chart at --physics subsurface is rendered without an image sensor; "
                                  "drop it (or use --physics direct)", flag=f"--{name}")
    if getattr(args, "gamut", False):
        raise SkinrenderError("--gamut compares the Lambertian chart's gamut volumes; it does not go with --physics "
                              "subsurface", flag="--gamut")
    scene = inputs.scene
    if not any(patch.skin for patch in scene.patches):
        raise SkinrenderError(f"--physics subsurface renders a chart's skin patches (skin = true) as the skin "
                              f"model's layers; {scene.name} has none", flag="--physics")
    if str(getattr(args, "spp", None)).strip().lower() == "auto":
        raise SkinrenderError("--spp auto picks spp from the Lambertian chart's pilot renders; give --spp N with "
                              "--physics subsurface", flag="--spp")
    if inputs.translate_mm is not None:  # float32's range: the skins' fits are the render's, made once (cached)
        from ..rendering.subsurface_chart import check_chart_range, subsurface_chart

        check_chart_range(subsurface_chart(scene, inputs.grid), inputs.translate_mm)
    if getattr(args, "sampler", None) is None:  # the pixels' errors honest (SAMPLER_SUBSURFACE's measurement)
        settings = settings.replace(sampler=SAMPLER_SUBSURFACE)
    cores = os.cpu_count() or 1
    check_work(estimate_seconds(scene, settings.spp) / cores, "--spp",
               f"the {sum(p.skin for p in scene.patches)} skin patches of {scene.name} as media at {settings.spp} "
               f"spp ({SAMPLES_PER_S_SLAB:g} samples/s per core, {cores} core{'s' * (cores > 1)})",
               getattr(args, "max_minutes", None), fewer="lower --spp")
    return settings


def subsurface_keys(rendering, rows: list[dict] | None = None) -> dict:
    """
    The keys a subsurface chart's JSON adds (``{}`` at ``direct``): ``physics``, ``light`` (the sky), and per
    patch ``skin_model``: the layers' ``spec``, ``source`` (``parameters`` or ``fit``), ``parameters``,
    ``fit_rms``, ``bounds_hit`` and ``dermis_mm`` (``None`` for a Lambertian patch), as a list in the scene's
    order, or, given the document's per-patch ``rows``, added to each row.
    """
    if rendering.info.get("physics") != "subsurface":
        return {}
    models = rendering.info["skin_model"]
    keys = {"physics": "subsurface",
            "light": "a uniform sky of radiance P(λ)/π (Planck's P at the prevailing temperature), seen straight "
                     "down: a skin patch's analytic value is Eq. 4 of its slab's adding-doubling reflectance (total, "
                     "collimated normal incidence)"}
    if rows is None:
        return {**keys, "skin_model": models}
    for row, model in zip(rows, models):
        row["skin_model"] = model
    return keys


def subsurface_lines(rendering) -> list[str]:
    """The text lines a subsurface chart adds (none at ``direct``): its skin patches' layers and their fits."""
    if rendering.info.get("physics") != "subsurface":
        return []
    rows = [row for row in rendering.info["skin_model"] if row is not None]
    fits = [row["fit_rms"] for row in rows if row["fit_rms"] is not None]
    fitted = f", {len(fits)} fitted to their measured reflectance (RMS ≤ {max(fits):.4f})" if fits else ""
    return [f"subsurface: {len(rows)} skin patches as the skin model's layers{fitted}, under a uniform sky; "
            f"analytic: each slab's adding-doubling reflectance through Eq. 4"]
