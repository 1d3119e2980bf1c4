"""
Triplet criteria
================

What the Stage 3 search computes for one sensor triplet: its gamut volumes
(ten one-calibration cases and all calibrations) the straightforward way and
the fast, exact way, and the detection criterion (false-positive rate of a
non-skin set inside the skin locus).

The fast method is exact (docs/references.md, :cite:`Martinkauppi2006` Stage 3),
not an approximation:

1.  Eq. 4 without the knee is, for one (prevailing *p*, calibration *q*) pair,
    a per-channel positive scaling of the prevailing cloud
    ``C_p = [Σ_λ I_p x_k o_i]``. A diagonal scaling maps hull vertices to hull
    vertices, so each ``C_p`` is reduced to its vertices ``V_p`` once per
    triplet and reused for every calibration.
2.  The hull of a union is the hull of the union of the parts' vertices: the
    case-*q* hull is built from ``∪_p scale_pq · V_p`` and the all-calibration
    hull from the case hulls' vertices.

The knee (Eq. 11) is not a diagonal scaling: with ``knee=True`` the volumes
are computed the straightforward way.

-   :func:`triplet_volumes_naive`, :func:`triplet_volumes_fast`: volumes.
-   :func:`triplet_false_positive_rates`, :func:`search_false_positive_rates`:
    the detection criterion.

References
----------
-   :cite:`Martinkauppi2006`, :cite:`Barber1996` (docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ..constants import TEMPERATURES_PAPER
from ..evaluation.gamut import gamut
from ..evaluation.hull import FLAT_SUSPECT, compiled_kernel, hull_volume_vertices
from ..evaluation.locus import hull_locus
from ..hints import ArrayLike, NDArrayFloat
from ..model.chromaticity import ncc
from ..model.response import knee as apply_knee
from ..spectra import GRID_DEFAULT, WavelengthGrid
from .bank import SensorBank, positions_grid, sensor_bank, triplets

__all__ = ["SMALL_SET", "triplet_volumes_naive", "triplet_volumes_fast", "triplet_gains", "triplet_volumes_many",
           "triplet_false_positive_rates",
           "search_false_positive_rates"]

def triplet_volumes_naive(bank: SensorBank, triplet: ArrayLike) -> NDArrayFloat:
    """
    Gamut volumes of one triplet the straightforward way: Qhull on every case's
    full point set (:func:`skinrender.gamut.gamut`).

    Returns
    -------
    :class:`numpy.ndarray`
        Shape ``(Q + 1,)``: one calibration case per illuminant (the union over
        every prevailing illuminant), then all calibrations; output units³.
    """

    points = bank.clouds(triplet)[:, None, :, :] * bank.gains(triplet)[:, :, None, :]  # (P, Q, N, 3)
    if bank.knee:
        points = apply_knee(points)
    volumes = [gamut(points[:, q]).volume for q in range(points.shape[1])]
    volumes.append(gamut(points).volume)
    return np.array(volumes)


SMALL_SET = 20
"""Reflectance sets up to this size skip the per-illuminant vertex reduction:
for them ten more hulls save nothing (the same time per triplet with and
without, for the first 20 skin spectra); from about 30 it pays (a sixth less
for the 30 skin spectra), and the 1269 Munsell chips need it. Measured with
sensor 9, the compiled kernel and four alternating runs over 450 triplets
(docs/speed.md, "The rates behind the estimates")."""

def triplet_volumes_fast(bank: SensorBank, triplet: ArrayLike) -> NDArrayFloat:
    """
    The volumes of :func:`triplet_volumes_naive` from hull vertices only.

    Each prevailing cloud is reduced to its hull vertices (sets larger than
    :data:`SMALL_SET`), the calibration cases are built from the scaled
    vertices and the all-calibration hull from the cases' vertices. With the
    compiled kernel the whole triplet is one call
    (``_hull3d.triplet_volumes``); where it declines a hull (a flat or
    doubtful cloud) the triplet is redone here, hull by hull, with Qhull
    answering what the kernel declines.

    Returns
    -------
    :class:`numpy.ndarray`
        Volumes ``(Q + 1,)`` in output units³.
    """

    if bank.knee:
        return triplet_volumes_naive(bank, triplet)
    clouds = bank.clouds(triplet)
    gains = bank.gains(triplet)
    kernel = compiled_kernel()
    if kernel is not None:  # the same steps in one compiled call
        answer = kernel.triplet_volumes(clouds, np.ascontiguousarray(gains), clouds.shape[1] > SMALL_SET,
                                         bank.diagonal, FLAT_SUSPECT)
        if answer is not None:
            return np.frombuffer(answer, dtype=np.float64).copy()
    count_p, count_q = gains.shape[:2]
    if clouds.shape[1] > SMALL_SET:
        parts = []
        shared = hull_volume_vertices(clouds[0])[1] if bank.diagonal else None
        for cloud in clouds:
            vertices = shared if bank.diagonal else hull_volume_vertices(cloud)[1]
            parts.append(cloud if vertices is None else cloud[vertices])
        owner = np.repeat(np.arange(count_p), [len(part) for part in parts])
        reduced = np.concatenate(parts)
    else:
        owner = np.repeat(np.arange(count_p), clouds.shape[1])
        reduced = clouds.reshape(-1, 3)
    volumes = np.empty(count_q + 1)
    case_vertices = []
    scale = gains[owner]  # (points, Q, 3)
    for q in range(count_q):
        points = reduced * scale[:, q]
        volumes[q], vertices = hull_volume_vertices(points)
        case_vertices.append(points if vertices is None else points[vertices])
    volumes[count_q] = hull_volume_vertices(np.concatenate(case_vertices))[0]
    return volumes


def triplet_gains(bank: SensorBank, index: NDArrayFloat) -> NDArrayFloat:
    """
    :meth:`SensorBank.gains` (white normalisation) of many index triplets at
    once, shape ``(T, P, Q, 3)``: the same operations in the same order,
    element by element, so the same numbers to the bit (tested).
    """
    white = np.moveaxis(bank.white[:, index[:, ::-1]], 1, 0)  # (T, P, 3), channels R, G, B
    white_p, white_c = white[:, :, None, :], white[:, None, :, :]
    factor = 3.0 / np.sum(white_p / white_c, axis=-1)  # WP, Eq. 8 (model.response.white_coefficient_from_whites)
    return np.ascontiguousarray(bank.scale * factor[..., None] / white_c)


def triplet_volumes_many(bank: SensorBank, index: NDArrayFloat) -> NDArrayFloat:
    """
    :func:`triplet_volumes_fast` of many index triplets ``(T, 3)``, shape
    ``(T, Q + 1)``, the same numbers to the bit: with the compiled kernel and
    the white normalisation without the knee (Stage 3's), one call for all
    (``_hull3d.chunk_volumes``: the gains in one step, the clouds gathered in
    C, which took ~50 µs per triplet in numpy), :func:`triplet_volumes_fast`
    for the triplets it declines; otherwise triplet by triplet.
    """
    index = np.asarray(index)
    kernel = compiled_kernel()
    if kernel is None or bank.knee or bank.factor is not None:
        return np.array([triplet_volumes_fast(bank, t) for t in index]).reshape(len(index), -1)
    signal = np.ascontiguousarray(bank.signal.transpose(1, 0, 2))  # (J, P, N): the responses by position
    gains = triplet_gains(bank, index)
    channels = np.ascontiguousarray(index[:, ::-1], dtype=np.int64)  # R is the longest peak
    volumes, declined = kernel.chunk_volumes(signal, channels, gains, signal.shape[2] > SMALL_SET, bank.diagonal,
                                             FLAT_SUSPECT)
    out = np.frombuffer(volumes, dtype=np.float64).reshape(len(index), gains.shape[2] + 1).copy()
    for row in np.flatnonzero(np.frombuffer(declined, dtype=np.uint8)):
        out[row] = triplet_volumes_fast(bank, index[row])
    return out


def triplet_false_positive_rates(bank_skin, bank_nonskin, triplet: ArrayLike) -> NDArrayFloat:
    """
    The detection criterion of one Stage 3 triplet: for each calibration q, the
    share of the non-skin set's chromaticities (every prevailing light,
    balanced to q) inside the convex-hull skin locus of the skin set under the
    same lights — the false-positive rate at 100 % acceptance of the training
    skin. Shape ``(Q,)``; NaN where the skin locus has no area.

    ``bank_skin``, ``bank_nonskin``: :class:`~skinrender.design.bank.SensorBank` of the
    two sets (responses are gathered, not recomputed).
    """

    skin = bank_skin.clouds(triplet)[:, None] * bank_skin.gains(triplet)[:, :, None]  # (P, Q, N, 3)
    other = bank_nonskin.clouds(triplet)[:, None] * bank_nonskin.gains(triplet)[:, :, None]
    rates = np.full(skin.shape[1], np.nan)
    for q in range(skin.shape[1]):
        locus = hull_locus(ncc(skin[:, q].reshape(-1, 3))[:, :2], bank_skin.temperatures, bank_skin.temperatures[q])
        if locus is not None:
            rates[q] = np.mean(locus.contains(ncc(other[:, q].reshape(-1, 3))[:, :2]))
    return rates


def search_false_positive_rates(sensor: float, skin: NDArrayFloat, nonskin: NDArrayFloat,
                                positions="400:700:10", illuminants: ArrayLike = TEMPERATURES_PAPER,
                                slope: float = 2.0, grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
    """:func:`triplet_false_positive_rates` for every triplet of a position grid, shape ``(T, Q)``."""
    where = positions_grid(positions)
    banks = [sensor_bank(sensor, values, where, illuminants, slope, grid=grid) for values in (skin, nonskin)]
    return np.array([triplet_false_positive_rates(*banks, t) for t in triplets(where.size)])
