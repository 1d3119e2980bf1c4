"""
Sensor-triplet search (Stage 3)
===============================

Every triplet of distinct sensor peaks on a position grid, each with its
per-calibration gamuts (one calibration case = the union over the prevailing
illuminants) and its all-calibration gamut, for a skin and a Munsell set: the
data behind the paper's Tables 2–5. The single sensors come from
:mod:`~skinrender.design.bank`, each triplet's volumes and detection
criterion from :mod:`~skinrender.design.criteria`; this module spreads the
triplets over every core (processes) or a Dask cluster and ranks them.

-   :func:`search`, :class:`SearchResult`: the whole search and the rows of
    Tables 2–5 with ties; CSV export of every triplet.
-   :data:`TOLERANCE_TIE`, :data:`SEARCH_METHODS`.

References
----------
-   :cite:`Martinkauppi2006` : Stage 3, Tables 2–5 (docs/references.md).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from .. import execution
from ..constants import TEMPERATURES_PAPER
from ..errors import SkinrenderError, check_flag, naming_role
from ..execution import DASK_TIMEOUT_S, WORKERS_MAX, check_workers, dask_client, stop_pool  # noqa: F401 (their earlier home)
from ..files import write_output
from ..evaluation.hull import HULL_KERNEL, notice_kernel
from ..hints import ArrayLike, NDArrayFloat
from ..methods import method_of
from ..spectra import GRID_DEFAULT, WavelengthGrid, as_grid
from ..workload import duration_text
from .bank import positions_grid, sensor_bank, triplets
from .inputs import design_inputs
from .criteria import triplet_false_positive_rates, triplet_volumes_many, triplet_volumes_naive
from .noise_aware import TPR_MIN, NoisySetting, bank_rates, calibration_index, exposure_capped, triplet_noisy_rates

__all__ = ["TOLERANCE_TIE", "SEARCH_METHODS", "WORKERS_MAX", "SECONDS_PER_TRIPLET", "SearchResult", "search", "stop_pool",
           "dask_client", "check_workers"]

SECONDS_PER_TRIPLET = 2.2e-3
"""One triplet's volumes (skin and Munsell, every calibration) on one core, s: the estimates' rate (measured with
``skinrender bench search``: docs/speed.md, "The Stage 3 search")."""

TOLERANCE_TIE = 1e-9
"""Two values within this relative difference are a tie; ties are reported."""

def volumes_fast(bank, chunk: NDArrayFloat) -> tuple[NDArrayFloat, str]:
    """hull vertices only, exact (default)

    The volumes of a chunk of index triplets ``(T, 3)``, shape ``(T, Q + 1)``
    (:func:`~skinrender.design.criteria.triplet_volumes_many`), and the hull kernel that computed them."""
    return triplet_volumes_many(bank, chunk), HULL_KERNEL


def volumes_naive(bank, chunk: NDArrayFloat) -> tuple[NDArrayFloat, str]:
    """Qhull on every case's full point set

    The volumes of a chunk of index triplets, triplet by triplet
    (:func:`~skinrender.design.criteria.triplet_volumes_naive`), and the kernel (``qhull``)."""
    return np.array([triplet_volumes_naive(bank, triplet) for triplet in chunk]).reshape(len(chunk), -1), "qhull"


SEARCH_METHODS = {"fast": volumes_fast, "naive": volumes_naive}
"""How the search computes each triplet's volumes, name → the function ``(bank, chunk) → (volumes, hull
kernel)``; :func:`search` dispatches."""


# --------------------------------------------------------------------------- #
# Parallel search
# --------------------------------------------------------------------------- #


def _volumes_chunk(shared: tuple, task: tuple, method, detection: bool = False):
    """
    Volumes of a chunk of index triplets for every bank, shape ``(len(banks), T, Q + 1)``, with ``detection``
    the false-positive rates of the skin locus ``(T, Q)``, and with noise (``shared``'s second item,
    ``(setting, rates_skin, rates_nonskin)``) the noisy (TPR, FPR) ``(T, 2)`` of the triplets; ``shared`` is
    ``(banks, noisy)``, ``task`` is ``(index triplets, their numbers)``; ``method`` one of
    :data:`SEARCH_METHODS`' functions. The hull kernel is the last item.
    """
    (banks, noisy), (chunk, numbers) = shared, task
    noisy_rates = None
    if noisy is not None:
        setting, rates_skin, rates_nonskin = noisy
        noisy_rates = np.array([triplet_noisy_rates(banks[0], banks[1], rates_skin, rates_nonskin, t, setting, int(n))
                                for t, n in zip(chunk, numbers)])
    out = np.empty((len(banks), len(chunk), banks[0].white.shape[0] + 1))
    for b, bank in enumerate(banks):
        out[b], kernel = method(bank, chunk)
    if not detection:
        return out, None, noisy_rates, kernel
    return out, np.array([triplet_false_positive_rates(banks[0], banks[1], t) for t in chunk]), noisy_rates, kernel


def _chunks(index: np.ndarray, count: int) -> list[np.ndarray]:
    return [part for part in np.array_split(index, max(1, count)) if len(part)]


@dataclass(frozen=True)
class SearchResult:
    """
    The volumes of a Stage 3 search.

    Attributes
    ----------
    sensor, slope
        Sensor number (1 = impulse) and gbell slope.
    positions
        Peak positions, nm, ``(J,)``.
    triplets
        Peak triplets in nm, ascending, ``(T, 3)``.
    temperatures
        Calibration illuminants, K, ``(Q,)``.
    skin, munsell
        Volumes, output units³, ``(T, Q + 1)``: one column per calibration
        case, the last for all calibrations.
    elapsed_s
        Wall time of the volume computation, s.
    """

    sensor: float
    slope: float
    positions: NDArrayFloat
    triplets: NDArrayFloat
    temperatures: NDArrayFloat
    skin: NDArrayFloat
    munsell: NDArrayFloat
    elapsed_s: float
    method: str = "fast"
    workers: int = 1
    normalization: str = "white"
    knee: bool = False
    info: dict = field(default_factory=dict)
    fpr: NDArrayFloat | None = None
    """With ``detection=True``: false-positive rate of the Munsell set inside the
    skin locus, per triplet and calibration, ``(T, Q)`` (see
    :func:`skinrender.design.criteria.triplet_false_positive_rates`)."""
    noisy: NDArrayFloat | None = None
    """With a noisy setting: each triplet's (TPR, FPR) on noisy pixels, ``(T, 2)``
    (:func:`skinrender.design.noise_aware.triplet_noisy_rates`)."""

    @property
    def ratio(self) -> NDArrayFloat:
        """Skin / Munsell volume, NaN where either gamut is degenerate (zero volume)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where((self.skin > 0) & (self.munsell > 0), self.skin / np.where(self.munsell > 0, self.munsell, 1.0), np.nan)

    def _rows(self, values: NDArrayFloat, columns: slice, best: str, tolerance: float) -> list[dict]:
        block = values[:, columns]
        finite = np.isfinite(block)
        if not finite.any():
            return []
        target = np.nanmax(block) if best == "max" else np.nanmin(block)
        close = finite & (np.abs(block - target) <= tolerance * abs(target))
        rows = []
        for t, c in zip(*np.nonzero(close)):
            temperature = None if columns.start == self.temperatures.size else float(self.temperatures[c])
            rows.append(
                {"triplet": [float(v) for v in self.triplets[t]], "temperature_K": temperature, "value": float(block[t, c])}
            )
        return rows

    def table(self, tolerance: float = TOLERANCE_TIE) -> dict:
        """
        The rows of Tables 2–5 with ties (``tolerance``: relative, finite, ≥ 0).

        Returns
        -------
        dict
            ``max_skin``, ``max_munsell``, ``min_ratio``: each a list of
            ``{triplet, temperature_K, value}``; one-calibration rows (Tables
            2, 3) carry the calibration temperature, all-calibration rows
            (Tables 4, 5) ``temperature_K = None``.
        """
        if not (np.isfinite(tolerance) and tolerance >= 0):
            raise SkinrenderError(f"tie tolerance must be a finite relative difference ≥ 0, got {tolerance!r}")
        one, everything = slice(0, self.temperatures.size), slice(self.temperatures.size, self.temperatures.size + 1)
        return {
            "max_skin": self._rows(self.skin, one, "max", tolerance) + self._rows(self.skin, everything, "max", tolerance),
            "max_munsell": self._rows(self.munsell, one, "max", tolerance)
            + self._rows(self.munsell, everything, "max", tolerance),
            "min_ratio": self._rows(self.ratio, one, "min", tolerance) + self._rows(self.ratio, everything, "min", tolerance),
            **({} if self.fpr is None else {"min_fpr": self._rows(self.fpr_table, one, "min", tolerance)
                                            + self._rows(self.fpr_table, everything, "min", tolerance)}),
            **({} if self.noisy is None else {"min_noisy_fpr": self._noisy_rows(tolerance)}),
        }

    def _noisy_rows(self, tolerance: float) -> list[dict]:
        """Triplets of least noisy FPR among those keeping a noisy TPR ≥ ``TPR_MIN``, ties listed."""
        tpr, fpr = self.noisy[:, 0], self.noisy[:, 1]
        eligible = np.isfinite(fpr) & (tpr >= TPR_MIN)
        if not eligible.any():
            return []
        best = fpr[eligible].min()
        close = np.nonzero(eligible & (np.abs(fpr - best) <= tolerance * max(abs(best), 1e-300)))[0]
        calibration = self.info.get("calibration_K")
        return [{"triplet": [float(v) for v in self.triplets[t]], "temperature_K": calibration,
                 "value": float(fpr[t]), "tpr": float(tpr[t])} for t in close]

    @property
    def fpr_table(self) -> NDArrayFloat:
        """False-positive rates per calibration and their mean over calibrations, ``(T, Q + 1)``."""
        return np.hstack([self.fpr, np.nanmean(self.fpr, axis=1, keepdims=True)])

    def to_csv(self, path, flag: str | None = None) -> None:
        """Every triplet's volumes (output units³) and ratios as CSV, whole or not at all (``flag``: the option
        that named ``path``, for the message when it cannot be written)."""
        labels = [f"{t:g}K" for t in self.temperatures] + ["all"]
        header = ["p1_nm", "p2_nm", "p3_nm"]
        header += [f"skin_{label}" for label in labels] + [f"munsell_{label}" for label in labels]
        header += [f"ratio_{label}" for label in labels]
        blocks = [self.triplets, self.skin, self.munsell, self.ratio]
        if self.fpr is not None:
            header += [f"fpr_{label}" for label in labels[:-1]] + ["fpr_mean"]
            blocks.append(self.fpr_table)
        if self.noisy is not None:
            header += ["noisy_tpr", "noisy_fpr"]
            blocks.append(self.noisy)
        data = np.hstack(blocks)
        row_format = ",".join(["%.17g"] * data.shape[1]) + "\n"  # one format per row: a third faster than per value
        text = ",".join(header) + "\n" + "".join(row_format % tuple(row) for row in data.tolist())
        write_output(path, text, flag)  # complete or absent, never half


def search(
    sensor: float,
    skin: NDArrayFloat,
    munsell: NDArrayFloat,
    positions: ArrayLike | str = "400:700:10",
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    slope: float = 2.0,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
    method: str = "fast",
    workers: int | None = None,
    dask: str | object | None = None,
    progress=None,
    label: str = "search",
    detection: bool = False,
    notice=sys.stderr,
    max_triplets: int = 1_000_000,
    noisy: NoisySetting | None = None,
) -> SearchResult:
    """
    The Stage 3 search: every triplet's per-calibration and all-calibration
    gamut volumes for a skin and a Munsell set.

    Parameters
    ----------
    sensor
        1 (impulse) or gbell N (FWHM N·10 nm).
    skin, munsell
        Reflectances on ``grid``, shape ``(N, grid.size)``, or reflectance sets (names, CSV paths, ``SpectralSet``).
    positions
        Peak positions (``"400:700:10"`` nm gives the paper's 31, 4495 triplets).
    illuminants
        The prevailing/calibration set (K), or its ``--illuminants`` text (``paper``, ``2000,3300,A``).
    slope
        gbell slope *b*.
    normalization, knee
        Eq. 4 options (the paper's Stage 3: ``white``, no knee).
    grid
        Integration grid, nm.
    method
        ``fast`` (hull vertices, exact) or ``naive`` (Qhull on every full set).
    workers
        Processes; ``None`` uses every core (``os.cpu_count()``).
    dask
        A Dask scheduler address (``tcp://host:8786``) or a
        ``distributed.Client``: chunks run on the cluster instead.
    progress
        A stream (``sys.stderr``) for a progress bar, or ``None``.
    detection
        Also compute the detection criterion: the false-positive rate of the
        Munsell set inside the skin locus, per calibration (``result.fpr``).
    noisy
        With a :class:`~skinrender.design.noise_aware.NoisySetting`, also every triplet's (TPR, FPR) on noisy
        pixels (``result.noisy``; table rows ``min_noisy_fpr``).
    max_triplets
        Refuse a search of more triplets than this (an estimate of its time is
        in the message).
    notice
        Stream for the one-line notice when the compiled hull kernel is
        missing (``result.info["hull_kernel"]`` says which kernel ran).

    Returns
    -------
    :class:`SearchResult`
    """

    volumes = method_of(method, SEARCH_METHODS, "method")
    knee, detection = check_flag(knee, "knee"), check_flag(detection, "detection")
    if isinstance(max_triplets, bool) or not isinstance(max_triplets, (int, np.integer)) or max_triplets < 1:
        raise SkinrenderError(f"max_triplets must be an integer ≥ 1, got {max_triplets!r}", role="max_triplets")
    grid = as_grid(grid)
    skin, munsell, illuminants = design_inputs(skin, munsell, illuminants, grid, noisy)
    where = positions_grid(positions)
    count = where.size * (where.size - 1) * (where.size - 2) // 6
    if count > max_triplets:
        raise SkinrenderError(f"{count} triplets ({where.size} positions) is more than max_triplets = {max_triplets} "
                              f"(about {duration_text(count * SECONDS_PER_TRIPLET / 2)} on 2 cores at the measured ~2 ms per "
                              "triplet per core); raise the limit (--max-triplets) or use fewer positions",
                              role="positions")
    workers = check_workers(workers, "workers")
    banks = tuple(naming_role(name, sensor_bank, sensor, values, where, illuminants, slope, normalization, knee, grid)
                  for name, values in (("skin", skin), ("munsell", munsell)))
    index = triplets(where.size)
    start = time.perf_counter()
    notice_kernel(notice)  # the compiled kernel's absence, said once
    # Several chunks per worker keep every core busy to the end.
    chunks = _chunks(np.arange(len(index)), 1 if workers == 1 and dask is None else 8 * max(workers, 4))
    out = np.empty((2, len(index), banks[0].white.shape[0] + 1))
    fpr = np.empty((len(index), banks[0].white.shape[0])) if detection else None
    pack = None
    if noisy is not None:
        calibration_index(banks[0].temperatures, noisy.calibration)
        pack = (noisy, bank_rates(banks[0], noisy, sensor, slope, grid), bank_rates(banks[1], noisy, sensor, slope, grid))
    noisy_rates = np.empty((len(index), 2)) if noisy is not None else None
    kernels = set()

    def store(number: int, result) -> None:
        chunk = chunks[number]
        out[:, chunk] = result[0]
        if detection:
            fpr[chunk] = result[1]
        if noisy is not None:
            noisy_rates[chunk] = result[2]
        kernels.add(result[3])

    execution.map_tasks(partial(_volumes_chunk, method=volumes, detection=detection), [(index[c], c) for c in chunks],
                  workers=workers, dask=dask, shared=(banks, pack), progress=progress, label=label, unit="triplet",
                  sizes=[len(c) for c in chunks], on_result=store)
    elapsed = time.perf_counter() - start
    return SearchResult(
        float(sensor), float(slope), where, where[index], banks[0].temperatures, out[0], out[1], elapsed,
        method, 1 if dask is not None else workers, normalization, knee, fpr=fpr, noisy=noisy_rates,
        info={"hull_kernel": ", ".join(sorted(kernels)),
              **({} if noisy is None else {"imager": noisy.imager.name, "illuminance_lux": noisy.illuminance_lux,
                                           "exposure": noisy.exposure, "calibration_K": noisy.calibration,
                                           "noise_samples": noisy.samples, "noise_seed": noisy.seed,
                                           "tpr_min": TPR_MIN,
                                           "exposure_note": exposure_capped(noisy, pack[1], banks[0].temperatures,
                                                                            index)})},
    )

