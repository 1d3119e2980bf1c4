"""
``--physics subsurface`` and ``subsurface-volume`` on a chart (``render``, ``validate``, ``detect``)
===================================================================================================

The chart commands take ``--physics direct`` (the default), ``subsurface``
(the chart's skin patches as the skin model's layers, the slab's angular
reflectance as a BSDF: :mod:`skinrender.rendering.slab_chart`) or
``subsurface-volume`` (the same layers as media under a dielectric boundary,
path traced: :mod:`skinrender.rendering.subsurface_chart`), both lit by a
uniform sky, each skin patch checked by ``validate`` against Eq. 4 of its
slab's adding-doubling reflectance.

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
    ``subsurface`` (the chart's default sampler) or ``subsurface-volume`` (with
    :data:`~skinrender.rendering.subsurface_chart.SAMPLER_SUBSURFACE` unless ``--sampler`` is given), ``settings``
    after refusing, naming the flag, what such a chart does not take (``--imager`` and its settings, ``--gamut``,
    ``--spp auto``), a chart without a skin patch, and a render whose estimate exceeds ``--max-minutes``
    (:func:`skinrender.workload.check_work`, naming ``--spp``): the paths on every core
    (:func:`~skinrender.rendering.subsurface_chart.estimate_seconds`), or the chart's pixels on every core and
    its tables and fits on one (:func:`~skinrender.rendering.slab_chart.estimate_seconds`).
    """
    physics = inputs.physics
    if physics == "direct":
        return settings
    import os

    from ..rendering.subsurface_chart import SAMPLER_SUBSURFACE
    from ..workload import check_work

    for name in ("imager", "illuminance", "exposure"):
        if getattr(args, name, None) is not None:
            raise SkinrenderError(f"--{name}: a chart at --physics {physics} is rendered without an image sensor; "
                                  "drop it (or use --physics direct)", flag=f"--{name}")
    if getattr(args, "gamut", False):
        raise SkinrenderError("--gamut compares the Lambertian chart's gamut volumes; it does not go with --physics "
                              f"{physics}", flag="--gamut")
    scene = inputs.scene
    if not any(patch.skin for patch in scene.patches):
        raise SkinrenderError(f"--physics {physics} renders a chart's skin patches (skin = true) as the skin "
                              f"model's layers; {scene.name} has none", flag="--physics")
    if str(getattr(args, "spp", None)).strip().lower() == "auto":
        raise SkinrenderError("--spp auto picks spp from the Lambertian chart's pilot renders; give --spp N with "
                              f"--physics {physics}", flag="--spp")
    if physics == "subsurface-volume" and getattr(args, "sampler", None) is None:  # SAMPLER_SUBSURFACE's measurement
        settings = settings.replace(sampler=SAMPLER_SUBSURFACE)
    cores = os.cpu_count() or 1
    skins = sum(p.skin for p in scene.patches)
    plural = f"{cores} core{'s' * (cores > 1)}"
    if physics == "subsurface":
        from ..rendering.slab_chart import SAMPLES_PER_S_TABLE, estimate_seconds

        fits = _fits(scene)
        seconds = estimate_seconds(scene, settings.spp, fits=fits, cores=cores)
        what = (f"{scene.name} at {settings.spp} spp with {skins} skin patches' tables and {fits} fits "
                f"({SAMPLES_PER_S_TABLE:g} samples/s per core, {plural})")
    else:
        from ..rendering.subsurface_chart import SAMPLES_PER_S_SLAB, estimate_seconds

        seconds = estimate_seconds(scene, settings.spp) / cores
        what = (f"the {skins} skin patches of {scene.name} as media at {settings.spp} spp "
                f"({SAMPLES_PER_S_SLAB:g} samples/s per core, {plural})")
    check_work(seconds, "--spp", what, getattr(args, "max_minutes", None), fewer="lower --spp")
    return settings


def _fits(scene) -> int:
    """The skin patches given as measured reflectances, which the skin model is fitted to."""
    from ..rendering.scene import skin_parameters_of

    return sum(1 for p in scene.patches if p.skin and skin_parameters_of(p.reflectance, "SCENE") is None)


def subsurface_keys(rendering, rows: list[dict] | None = None) -> dict:
    """
    The keys a subsurface chart's JSON adds (``{}`` at ``direct``): ``physics``, ``light`` (the sky), and per
    patch ``skin_model``: the layers' ``spec``, ``source`` (``parameters`` or ``fit``), ``parameters``,
    ``fit_rms``, ``bounds_hit`` and ``dermis_mm`` (the rendered dermis' thickness at ``subsurface-volume``;
    ``None`` at ``subsurface``, whose table is the model's semi-infinite dermis) (``None`` for a Lambertian
    patch), as a list in the scene's order, or, given the document's per-patch ``rows``, added to each row.
    """
    physics = rendering.info.get("physics")
    if physics in (None, "direct"):
        return {}
    models = rendering.info["skin_model"]
    keys = {"physics": physics,
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
    physics = rendering.info.get("physics")
    if physics in (None, "direct"):
        return []
    rows = [row for row in rendering.info["skin_model"] if row is not None]
    fits = [row["fit_rms"] for row in rows if row["fit_rms"] is not None]
    fitted = f", {len(fits)} fitted to their measured reflectance (RMS ≤ {max(fits):.4f})" if fits else ""
    how = "media, path traced" if physics == "subsurface-volume" else "their slab's angular reflectance (a BSDF)"
    return [f"{physics}: {len(rows)} skin patches as the skin model's layers{fitted}, {how}, under a uniform sky; "
            f"analytic: each slab's adding-doubling reflectance through Eq. 4"]
