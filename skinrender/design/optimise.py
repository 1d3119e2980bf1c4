"""
Continuous camera design
========================

Optimise a gbell camera's three peaks (and, optionally, the shared width and
slope) off the 10 nm grid, for the paper's ratio or for the detection
criterion.

-   :func:`objective`: the value of one camera under ``ratio`` (skin/Munsell
    all-calibration volume, lower is better) or ``detection`` (share of
    Munsell chromaticities inside the skin locus, lower is better).
-   :func:`optimise_camera`, :class:`Design`: derivative-free search
    (Nelder–Mead) from several starts.

Why derivative-free: the detection criterion is a count (piecewise constant in
the peaks), and the hull volume is differentiable only while its facet
structure stays fixed, which changes along any path of interest; Nelder–Mead
needs neither gradient nor smoothness, and several starts guard against its
local stalls. drjit's automatic differentiation is therefore not used here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..constants import TEMPERATURES_PAPER
from ..errors import SkinrenderError, check_flag
from ..hints import ArrayLike, NDArrayFloat
from ..methods import method_of, takes
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid, float_array
from .bank import sensor_bank
from .criteria import triplet_false_positive_rates, triplet_volumes_fast
from .inputs import design_inputs
from .noise_aware import TPR_MIN, NoisySetting, bank_rates, calibration_index, exposure_capped, triplet_noisy_rates

__all__ = ["OBJECTIVES", "objective_detection", "objective_ratio", "objective", "Design", "optimise_camera", "noisy_report"]

def objective_detection(banks: list, fwhm: float, slope: float, grid: WavelengthGrid,
                        noisy: NoisySetting | None = None) -> float:
    """Munsell false-positive rate inside the skin locus

    Of the camera of the skin and Munsell ``banks`` (one triplet); with ``noisy``, on noisy pixels: the FPR while
    the TPR holds at :data:`~skinrender.design.noise_aware.TPR_MIN`, else a penalty above any FPR."""
    if noisy is not None:
        tpr, fpr, _ = _noisy_rates(banks, fwhm, slope, grid, noisy)
        if not np.isfinite(fpr):
            return np.inf
        return fpr if tpr >= TPR_MIN else 1.0 + (TPR_MIN - tpr)
    rates = triplet_false_positive_rates(banks[0], banks[1], [0, 1, 2])
    return float(rates[0]) if np.isfinite(rates[0]) else np.inf  # the same for every calibration


def objective_ratio(banks: list, fwhm: float, slope: float, grid: WavelengthGrid) -> float:
    """skin/Munsell all-calibration gamut volume (the paper's Table 5)

    Of the camera of the skin and Munsell ``banks``; ``inf`` where a gamut is degenerate. Takes no noisy pixels."""
    volumes = [triplet_volumes_fast(bank, [0, 1, 2])[-1] for bank in banks]
    return volumes[0] / volumes[1] if volumes[0] > 0 and volumes[1] > 0 else np.inf


OBJECTIVES = {"detection": objective_detection, "ratio": objective_ratio}
"""Design objectives (lower is better), name → the function ``(banks, fwhm, slope, grid[, noisy]) → value``;
:func:`objective` dispatches (only an objective that takes ``noisy`` is given noisy pixels)."""

BOUNDS_NM = (400.0, 700.0)
"""Peaks stay on the integration range, nm."""


def objective(
    kind: str,
    peaks: ArrayLike,
    fwhm: float,
    skin: NDArrayFloat,
    munsell: NDArrayFloat,
    slope: float = 2.0,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    grid: WavelengthGrid = GRID_DEFAULT,
    noisy: NoisySetting | None = None,
) -> float:
    """
    The objective of a gbell camera with ``peaks`` (nm, any order), ``fwhm`` (nm) and ``slope``.

    Returns ``inf`` for a camera outside the bounds or with a degenerate skin
    or Munsell gamut (nothing to minimise there). With ``noisy`` (detection
    only) the criterion is the FPR on noisy pixels while their TPR stays at or
    above :data:`~skinrender.design.noise_aware.TPR_MIN`, and ``1 + (TPR_MIN − TPR)``
    below it (:mod:`skinrender.design.noise_aware`).
    """

    function = _objective_of(kind, noisy)
    peaks = np.sort(np.asarray(peaks, dtype=np.float64))
    if peaks[0] < BOUNDS_NM[0] or peaks[-1] > BOUNDS_NM[1] or np.any(np.diff(peaks) <= 0) or fwhm <= 0 or slope <= 0:
        return np.inf
    banks = [sensor_bank(fwhm / 10.0, values, peaks, illuminants, slope, grid=grid) for values in (skin, munsell)]
    return function(banks, fwhm, slope, grid, **({} if noisy is None else {"noisy": noisy}))


def _objective_of(kind: str, noisy: NoisySetting | None):
    """The function of objective ``kind``, checked (noisy pixels go with an objective that takes them)."""
    function = method_of(kind, OBJECTIVES, "objective")
    if noisy is not None and not takes(function, "noisy"):
        noisy_ones = " or ".join(name for name, each in OBJECTIVES.items() if takes(each, "noisy"))
        raise SkinrenderError(f"an imager (noisy pixels) goes with the {noisy_ones} objective, not the {kind}")
    return function


@dataclass(frozen=True)
class Design:
    """An optimised camera: ``peaks`` (nm, ascending), ``fwhm`` (nm), ``slope``, ``value``, per-start results."""

    objective: str
    peaks: NDArrayFloat
    fwhm: float
    slope: float
    value: float
    starts: list

    @property
    def camera_spec(self) -> str:
        """The camera as a spec string (``gbell:N,b=B@P1,P2,P3``)."""
        return f"gbell:{self.fwhm / 10:g},b={self.slope:g}@" + ",".join(f"{p:.1f}" for p in self.peaks)


def _finite_or_none(value: float) -> float | None:
    """The objective's value, or ``None`` where it is undefined (``inf``: a degenerate camera)."""
    return float(value) if np.isfinite(value) else None


def optimise_camera(
    kind: str,
    skin: NDArrayFloat,
    munsell: NDArrayFloat,
    starts: ArrayLike = ((450.0, 540.0, 610.0), (420.0, 550.0, 680.0), (480.0, 560.0, 640.0)),
    fwhm: float = 90.0,
    slope: float = 2.0,
    free_shape: bool = False,
    max_evaluations: int = 200,
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    grid: WavelengthGrid = GRID_DEFAULT,
    noisy: NoisySetting | None = None,
) -> Design:
    """
    Minimise ``kind`` over the peaks (and the width and slope with ``free_shape``) from each start.

    Parameters
    ----------
    kind
        ``ratio`` or ``detection``.
    skin, munsell
        Reflectances on ``grid``, or reflectance sets (names, CSV paths, ``SpectralSet``); ``illuminants``: K, or
        their ``--illuminants`` text.
    starts
        Starting peak triplets, nm.
    fwhm, slope
        The sensor shape (the starting one with ``free_shape``).
    max_evaluations
        Objective evaluations per start.
    noisy
        For ``detection``: judge cameras on noisy pixels
        (:class:`~skinrender.design.noise_aware.NoisySetting`; the same seed every
        evaluation, so the objective is deterministic).

    Returns
    -------
    :class:`Design`
        The best over the starts, with every start's result.
    """

    _objective_of(kind, noisy)
    grid = as_grid(grid)
    skin, munsell, illuminants = design_inputs(skin, munsell, illuminants, grid, noisy)
    if noisy is not None:
        calibration_index(np.asarray(illuminants, dtype=np.float64), noisy.calibration)
    free_shape = check_flag(free_shape, "free_shape")
    if isinstance(max_evaluations, bool) or not (isinstance(max_evaluations, (int, np.integer))
                                                 and max_evaluations >= 1):
        raise SkinrenderError(f"max_evaluations must be an integer ≥ 1 per start, got {max_evaluations!r}",
                              role="max_evaluations")
    for name, value in (("fwhm", fwhm), ("slope", slope)):
        if value is None or isinstance(value, (bool, str)) or np.size(value) != 1 \
                or not (np.isfinite(float_array(value, name)).all() and float(np.ravel(value)[0]) > 0):
            raise SkinrenderError(f"{name} must be a finite number > 0 (fwhm: nm, sensor N·10), got {value!r}",
                                  role=name)
    fwhm, slope = float(np.ravel(fwhm)[0]), float(np.ravel(slope)[0])
    starts = np.atleast_2d(float_array(starts, "starts"))
    if starts.ndim != 2 or starts.shape[1] != 3 or len(starts) == 0:
        raise SkinrenderError(f"starts must be triplets of peaks in nm, got shape {starts.shape}", role="starts")
    for start in starts:
        ordered = np.sort(start)
        if not (np.all(np.isfinite(start)) and ordered[0] >= BOUNDS_NM[0] and ordered[-1] <= BOUNDS_NM[1]
                and np.all(np.diff(ordered) > 0)):
            raise SkinrenderError(f"each start must be three distinct peaks in {BOUNDS_NM[0]:g}–{BOUNDS_NM[1]:g} nm, "
                                  f"got {start.tolist()}", role="starts")

    def unpack(x):
        if free_shape:
            return x[:3], x[3], x[4]
        return x, fwhm, slope

    def f(x):
        p, w, b = unpack(x)
        return objective(kind, p, w, skin, munsell, b, illuminants, grid, noisy)

    from scipy.optimize import minimize  # here: importing scipy.optimize costs every command ~0.6 s

    results = []
    for start in starts:
        x0 = np.concatenate([np.sort(start), [fwhm, slope]]) if free_shape else np.sort(start)
        simplex = [x0] + [x0 + np.eye(len(x0))[i] * (15.0 if i < 3 else (20.0 if i == 3 else 0.5)) for i in range(len(x0))]
        first = f(x0)
        found = minimize(f, x0, method="Nelder-Mead",
                         options={"maxfev": max_evaluations, "initial_simplex": np.array(simplex), "xatol": 0.5,
                                  "fatol": 1e-6})
        p, w, b = unpack(found.x)
        results.append({"start": np.sort(start).tolist(), "start_value": _finite_or_none(first),
                        "peaks": np.sort(p).tolist(), "fwhm": float(w), "slope": float(b),
                        "value": _finite_or_none(found.fun), "evaluations": int(found.nfev)})
    scored = [r for r in results if r["value"] is not None]
    if not scored:
        raise SkinrenderError(f"no start reached a camera whose {kind} criterion is defined (every camera tried had a "
                              "degenerate skin or Munsell gamut or locus); try other starts")
    best = min(scored, key=lambda r: r["value"])
    return Design(kind, np.array(best["peaks"]), best["fwhm"], best["slope"], best["value"], results)


def _noisy_rates(banks: list, fwhm: float, slope: float, grid: WavelengthGrid, noisy: NoisySetting) -> tuple:
    """A camera's noisy (TPR, FPR) from its skin and Munsell banks (peaks 0, 1, 2), with the banks' white rates."""
    rates = [bank_rates(bank, noisy, fwhm / 10.0, slope, grid) for bank in banks]
    return (*triplet_noisy_rates(*banks, *rates, [0, 1, 2], noisy), rates)


def noisy_report(design: Design, skin: NDArrayFloat, munsell: NDArrayFloat, noisy: NoisySetting,
                 illuminants: ArrayLike = TEMPERATURES_PAPER, grid: WavelengthGrid = GRID_DEFAULT) -> dict:
    """
    What a noisy detection design's ``value`` stands for: the best camera's noisy ``tpr`` and ``fpr`` and
    ``notes`` — the value is a penalty ``1 + (TPR_MIN − TPR)``, not an FPR, where no start kept the TPR at
    :data:`~skinrender.design.noise_aware.TPR_MIN`; an ``auto`` exposure stopped at a video frame.
    """
    banks = [sensor_bank(design.fwhm / 10.0, values, design.peaks, illuminants, design.slope, grid=grid)
             for values in (skin, munsell)]
    tpr, fpr, rates = _noisy_rates(banks, design.fwhm, design.slope, grid, noisy)
    notes = []
    if not tpr >= TPR_MIN:
        notes.append(f"no start kept a noisy TPR ≥ {TPR_MIN:g} (the best keeps {tpr:.3g}): the value "
                     f"{design.value:.4g} is the penalty 1 + ({TPR_MIN:g} − TPR), not a false-positive rate")
    capped = exposure_capped(noisy, rates[0], banks[0].temperatures, np.array([[0, 1, 2]]))
    if capped:
        notes.append(capped)
    return {"tpr": _finite_or_none(tpr), "fpr": _finite_or_none(fpr), "notes": notes}
