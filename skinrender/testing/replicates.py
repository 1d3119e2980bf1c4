"""
Face statistics from replicates
===============================

A face's regions (label 0 background, 1 skin, 2… props) are not flat patches:
a region's shading varies pixel to pixel, so its pixels are not samples of
one mean and their spread says nothing of the render's noise. The face is
therefore rendered as :data:`REPLICATES` independent replicates of
``spp / REPLICATES`` samples each (seeds drawn from the check's seed,
:func:`replicate_seeds`); the image is their mean, and each pixel's Monte
Carlo covariance of that mean is its sample covariance over the replicates
divided by their number. Pixels are independent (a ``box`` filter), so a
region mean's covariance is the sum of its pixels' over ``n²``, with
Satterthwaite's degrees of freedom ``(Σ v_i)² / Σ (v_i² / (K − 1))``
:cite:`Satterthwaite1946`; the skin's NCC ``r, g`` (Eq. 2 of the skin
region's mean) takes its standard errors by the delta method. The labels come
from the geometry and are the same in every replicate.

-   :func:`replicate_seeds`, :func:`region_values`, :func:`measure_face`.

Units: images, means and standard errors in Eq. 4 output units; NCC
fractions; temperatures K; illuminance lx.

References
----------
-   :cite:`Satterthwaite1946` : F. E. Satterthwaite (1946). An approximate
    distribution of estimates of variance components. Biometrics Bulletin 2,
    110–114.
"""

from __future__ import annotations

import numpy as np

from ..errors import SkinrenderError
from ..hints import NDArrayFloat

__all__ = ["REPLICATES", "replicate_seeds", "region_values", "measure_face", "face_check_request", "reduce_face"]

REPLICATES = 4
"""Independent replicates a face is rendered as, for its per-pixel Monte Carlo covariance."""


def replicate_seeds(seed: int, count: int = REPLICATES) -> list[int]:
    """
    The 32-bit seeds of a face's replicates: distinct for every ``seed`` and replicate.

    >>> len(set(replicate_seeds(0) + replicate_seeds(1)))
    8
    """
    return [int(s) for s in np.random.SeedSequence([int(seed), 0xFACE]).generate_state(count)]


def region_values(image: NDArrayFloat, labels: NDArrayFloat, regions: dict,
                  covariance: NDArrayFloat | None = None) -> tuple:
    """
    The region means per channel and the skin NCC ``r, g`` of ``image``; with the per-pixel ``covariance``
    of the mean ``(h, w, 3, 3)`` also their standard errors and Satterthwaite degrees of freedom.
    """
    means, ses, dofs = [], [], []
    pixels = np.asarray(image, dtype=np.float64)
    for name, label in regions.items():
        mask = labels == label
        n = int(mask.sum())
        region = pixels[mask].mean(axis=0)
        means.append(region)
        if covariance is not None:
            cov = covariance[mask].sum(axis=0) / n**2
            variances = np.diagonal(covariance[mask], axis1=1, axis2=2)  # (n, 3)
            total = variances.sum(axis=0)
            spread = np.sum(variances**2, axis=0) / (REPLICATES - 1)
            dof = np.divide(total**2, spread, out=np.full(3, np.inf), where=spread > 0)
            ses.append(np.sqrt(np.maximum(np.diagonal(cov), 0.0)))
            dofs.append(dof)
            if name == "skin":
                skin_cov, skin_dof = cov, float(np.min(dof))
    if "skin" in regions:
        skin = means[list(regions).index("skin")]
        total = skin.sum()
        ncc = skin / total if total > 0 else np.full(3, 1 / 3)
        means.append(ncc[:2])
        if covariance is not None:
            jacobian = (np.eye(3) - ncc[:, None]) / (total if total > 0 else 1.0)
            ses.append(np.sqrt(np.maximum(np.diagonal(jacobian @ skin_cov @ jacobian.T)[:2], 0.0)))
            dofs.append(np.full(2, skin_dof))
    mean = np.concatenate(means)
    if covariance is None:
        return mean, None, None
    se = np.concatenate(ses)
    return mean, se, np.where(se > 0, np.concatenate(dofs), np.inf)


def measure_face(scene, cam, prevailing: float, calibration: float, spp: int, seed: int, physics: str | None,
                 skin: str | None, imager: str | None, illuminance: float | None, size, variant: str | None) -> tuple:
    """
    Render the face ``scene`` as :data:`REPLICATES` replicates of ``spp / REPLICATES`` samples (temperatures
    K, illuminance lx, ``size`` pixels) and reduce it: ``(image, labels, channels, regions, items, mean,
    standard_error, dof, settings)`` as :class:`~skinrender.testing.regression.Measurement` holds them.
    ``imager`` adds physics ``noise``; ``illuminance`` without it or ``noise`` is refused.
    """
    from ..rendering.kinds import FACE

    request = face_check_request(scene, cam, prevailing, calibration, spp, seed, physics, skin, imager, illuminance,
                                 size, variant)
    return reduce_face([FACE.render(request, s) for s in replicate_seeds(seed)], cam)


def face_check_request(scene, cam, prevailing: float, calibration: float, spp: int, seed: int, physics: str | None,
                       skin: str | None, imager: str | None, illuminance: float | None, size, variant: str | None,
                       bands=None):
    """A face check's request (the one request of every door: an imager adds noise there; illuminance without it
    or noise is refused), its ``spp`` split over :data:`REPLICATES`; ``bands``: a spectral one (``cam``
    ``None``)."""
    from ..rendering.kinds import FACE

    if spp < REPLICATES:
        raise SkinrenderError(f"spp: a face check renders {REPLICATES} replicates, so spp must be at least "
                              f"{REPLICATES}, got {spp}")
    return FACE.request(scene, cam, prevailing, calibration, skin=skin, physics=physics or "direct", size=size,
                        spp=spp // REPLICATES, seed=seed, variant=variant, imager=imager, illuminance=illuminance,
                        **({} if bands is None else {"bands": bands}))


def reduce_face(renders: list, cam) -> tuple:
    """:func:`measure_face`'s reduction of the replicate renders of one camera (``renders``, one per seed)."""
    from ..rendering.renderer import channel_names

    first = renders[0]
    stack = np.array([r.image for r in renders], dtype=np.float64)
    image = stack.mean(axis=0).astype(np.float32)
    deviation = stack - stack.mean(axis=0)
    covariance = np.einsum("khwi,khwj->hwij", deviation, deviation) / (REPLICATES - 1) / REPLICATES
    present = np.unique(first.labels)
    regions = {name: int(label) for name, label in first.label_names.items() if label in present}
    mean, se, dof = region_values(image, first.labels, regions, covariance)
    items = tuple(f"{n} / {c}" for n in regions for c in cam.channels)
    items += ("skin NCC / r", "skin NCC / g") if "skin" in regions else ()
    settings = {"spp": int(first.spp) * REPLICATES, "variant": first.variant, "physics": first.physics,
                "skin": first.skin, "size": [int(first.image.shape[1]), int(first.image.shape[0])],
                "replicates": REPLICATES, "scene_name": first.scene.name,
                **({"imager": first.info["imager"], "illuminance_lux": first.info["illuminance_lux"]}
                   if "imager" in first.info else {})}
    return image, first.labels.astype(np.int32), channel_names(cam), regions, items, mean, se, dof, settings
