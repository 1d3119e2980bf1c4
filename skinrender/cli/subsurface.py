"""
``--physics subsurface`` and ``subsurface-volume`` on a chart (``render``, ``validate``, ``detect``)
====================================================================================================

The chart commands take ``--physics direct`` (the default), ``subsurface`` or
``subsurface-volume`` (the chart's registry of effects,
:mod:`skinrender.rendering.chart_effects`, whose subsurface levels refuse what
does not go with them where the request is built): the chart's skin patches
as the skin model's layers, lit by a uniform sky, their flat slab's angular
reflectance as a BSDF (:mod:`skinrender.rendering.slab_chart`) or media under
a dielectric boundary, path traced
(:mod:`skinrender.rendering.subsurface_chart`), each checked by ``validate``
against Eq. 4 of its slab's adding-doubling reflectance.

-   :func:`subsurface_keys`: what the JSON of a subsurface chart adds.
-   :func:`subsurface_lines`: the text lines it adds.
"""

from __future__ import annotations

__all__ = ["subsurface_keys", "subsurface_lines"]


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


def subsurface_lines(rendering) -> list[str]:
    """The text lines a subsurface chart adds (none at ``direct``): its skin patches' layers and their fits."""
    if "skin_model" not in rendering.info:
        return []
    rows = [row for row in rendering.info["skin_model"] if row is not None]
    fits = [row["fit_rms"] for row in rows if row["fit_rms"] is not None]
    fitted = f", {len(fits)} fitted to their measured reflectance (RMS ≤ {max(fits):.4f})" if fits else ""
    physics, how = rendering.info["physics"], rendering.info["slabs_as"]
    return [f"{physics}: {len(rows)} skin patches as the skin model's layers{fitted}, {how}, under a uniform sky; "
            f"analytic: each slab's adding-doubling reflectance through Eq. 4"]
