"""
Sensor-triplet search (Stage 3)
===============================

Every triplet of distinct sensor peaks on a position grid, each with its
per-calibration gamuts (one calibration case = the union over the prevailing
illuminants) and its all-calibration gamut, for a skin and a Munsell set: the
data behind the paper's Tables 2–5.

-   :class:`SensorBank`, :func:`sensor_bank`: single-sensor responses of a
    reflectance set at every position under every illuminant, computed once.
-   :func:`triplets`: the ascending triplets of distinct positions.
-   :func:`triplet_volumes_naive`: Qhull on each case's full point set.
-   :func:`triplet_volumes_fast`: the same volumes from hull vertices only.
-   :func:`search`, :class:`SearchResult`: the whole search, on every core or a
    Dask cluster, and the rows of Tables 2–5 with ties.

The fast method is exact (NOTES.md; the issue's hints), not an approximation:

1.  Eq. 4 without the knee is, for one (prevailing *p*, calibration *q*) pair,
    a per-channel positive scaling of the prevailing cloud
    ``C_p = [Σ_λ I_p x_k o_i]``. A diagonal scaling maps hull vertices to hull
    vertices, so each ``C_p`` is reduced to its vertices ``V_p`` once per
    triplet and reused for every calibration.
2.  The hull of a union is the hull of the union of the parts' vertices: the
    case-*q* hull is built from ``∪_p scale_pq · V_p`` and the all-calibration
    hull from the case hulls' vertices.

Single-sensor responses are computed once per position and gathered per
triplet. The hulls are built by a compiled Quickhull (``skinrender/_hull3d.c``,
:data:`HULL_KERNEL`), with Qhull for the flat or doubtful clouds it declines;
volumes agree with the straightforward method to ~1e-12 relative
(tests/test_search.py checks < 1e-9 triplet by triplet).

The knee (Eq. 11) is not a diagonal scaling: with ``knee=True`` the search
uses the straightforward method.

References
----------
-   :cite:`Martinkauppi2006` : the paper, Stage 3, Tables 2–5.
-   :cite:`Barber1996` : Qhull.
"""

from __future__ import annotations

import itertools
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import numpy as np
from scipy.spatial import ConvexHull, QhullError

from .camera import NORMALISATIONS, _spd_on, knee as apply_knee, normalisation_factor, white_coefficient_from_whites
from .constants import CONSTANT_OUTPUT_SCALE, TEMPERATURES_PAPER
from .errors import SkinrenderError
from .gamut import gamut, is_flat
from .hints import ArrayLike, NDArrayFloat
from .illuminant import illuminants_array
from .spectra import GRID_DEFAULT, WavelengthGrid, gbell, impulse

try:
    from . import _hull3d
except ImportError:  # built without a C compiler: Qhull does every hull
    _hull3d = None

HULL_KERNEL = "quickhull" if _hull3d is not None else "qhull"
"""The fast method's hull kernel: ``quickhull`` (the compiled Quickhull of
``skinrender/_hull3d.c``, with Qhull for the flat and doubtful clouds it
declines) or ``qhull`` (scipy's Qhull for every hull, when the package was
installed without a C compiler; several times slower)."""

__all__ = [
    "TOLERANCE_TIE",
    "SENSORS_PAPER",
    "SensorBank",
    "sensor_bank",
    "positions_grid",
    "triplets",
    "triplet_volumes_naive",
    "triplet_volumes_fast",
    "SearchResult",
    "search",
]

TOLERANCE_TIE = 1e-9
"""Two values within this relative difference are a tie; ties are reported."""

SENSORS_PAPER = (1, 3, 5, 7, 9, 11, 13, 15)
"""The paper's sensors: 1 is the impulse, N ≥ 3 a gbell of FWHM N·10 nm."""


def positions_grid(spec: str | ArrayLike = "400:700:10") -> NDArrayFloat:
    """Sensor peak positions in nm from ``start:end:step`` (end included) or a sequence."""
    if isinstance(spec, str):
        try:
            start, end, step = (float(part) for part in spec.split(":"))
        except ValueError:
            raise SkinrenderError(f"positions must be START:END:STEP in nm, e.g. 400:700:10, got {spec!r}") from None
        if not (step > 0 and end > start):
            raise SkinrenderError(f"positions {spec!r}: need END > START and STEP > 0 (nm)")
        values = start + step * np.arange(int(np.floor((end - start) / step + 1e-9)) + 1)
    else:
        values = np.asarray(spec, dtype=np.float64).ravel()
    if values.size < 3 or not np.all(np.isfinite(values)) or np.any(np.diff(values) <= 0):
        raise SkinrenderError("positions must be at least three increasing wavelengths in nm")
    return values


def triplets(count: int) -> np.ndarray:
    """Index triplets ``(i, j, k)``, ``i < j < k``, of ``count`` positions, lexicographic; shape ``(T, 3)``."""
    return np.array(list(itertools.combinations(range(count), 3)), dtype=np.intp).reshape(-1, 3)


@dataclass(frozen=True)
class SensorBank:
    """
    Single-sensor responses of one reflectance set.

    Attributes
    ----------
    positions
        Sensor peaks, nm, shape ``(J,)``.
    temperatures
        Illuminants, K, shape ``(P,)``; they serve as prevailing and calibration.
    signal
        ``Σ_λ I_p(λ) x_j(λ) o_i(λ)``, shape ``(P, J, N)``.
    white
        ``Σ_λ I_p(λ) x_j(λ)``, shape ``(P, J)``.
    factor
        Normalisation factor ``F_p`` (Eqs. 5–7), shape ``(P,)``; ``None`` for ``white``.
    """

    positions: NDArrayFloat
    temperatures: NDArrayFloat
    signal: NDArrayFloat
    white: NDArrayFloat
    factor: NDArrayFloat | None
    scale: float = CONSTANT_OUTPUT_SCALE
    knee: bool = False
    diagonal: bool = False
    """True for the impulse: each prevailing cloud is a per-channel scaling of
    every other (``I_p(λ_k) o_i(λ_k)``), so all share one vertex set."""

    def gains(self, triplet: ArrayLike) -> NDArrayFloat:
        """Eq. 4 gains ``v · F_pq / W_qk`` for one index triplet (channels R, G, B), shape ``(P, Q, 3)``."""
        index = np.asarray(triplet)[::-1]  # R is the longest peak
        white = self.white[:, index]
        if self.factor is None:
            factor = white_coefficient_from_whites(white[:, None, :], white[None, :, :])  # WP (Eq. 8)
        else:
            factor = self.factor[:, None] / self.factor[None, :]
        return self.scale * factor[:, :, None] / white[None, :, :]

    def clouds(self, triplet: ArrayLike) -> NDArrayFloat:
        """Prevailing clouds ``C_p`` (channels R, G, B), shape ``(P, N, 3)``."""
        index = np.asarray(triplet)[::-1]
        return np.ascontiguousarray(self.signal[:, index, :].transpose(0, 2, 1))


def sensor_bank(
    sensor: float,
    reflectance: NDArrayFloat,
    positions: ArrayLike = positions_grid(),
    illuminants: ArrayLike = TEMPERATURES_PAPER,
    slope: float = 2.0,
    normalization: str = "white",
    knee: bool = False,
    grid: WavelengthGrid = GRID_DEFAULT,
) -> SensorBank:
    """
    Single-sensor responses at every position, computed once for a search.

    Parameters
    ----------
    sensor
        The paper's sensor number: 1 (impulse, a unit-area delta on the grid
        sample of its peak) or N > 1 (gbell, FWHM = N·10 nm).
    reflectance
        Reflectances on ``grid``, shape ``(N, grid.size)``, fractions.
    positions
        Sensor peaks, nm.
    illuminants
        Prevailing and calibration illuminants (K, ``A``, ``H`` …).
    slope
        gbell slope *b*.
    normalization
        ``white`` (Eq. 8, the paper's Stage 3) or ``none``/``560nm``/``euclidean``.
    knee
        Apply Eq. 11 (forces the straightforward method).
    grid
        Integration grid, nm.
    """

    if normalization not in NORMALISATIONS:
        raise SkinrenderError(f"normalization must be one of {', '.join(NORMALISATIONS)}, got {normalization!r}")
    if not (np.isfinite(sensor) and sensor > 0):
        raise SkinrenderError(f"sensor must be 1 (impulse) or a gbell number N > 1 (FWHM N·10 nm), got {sensor}")
    positions = np.asarray(positions, dtype=np.float64)
    if positions.min() < grid.start or positions.max() > grid.end:
        raise SkinrenderError(
            f"positions {positions.min():g}–{positions.max():g} nm leave the integration grid {grid}"
        )
    items, _ = illuminants_array(illuminants)
    spd = _spd_on(items, grid)  # (P, W)
    if sensor == 1:
        x = np.array([impulse(grid, peak) for peak in positions])
    else:
        x = gbell(grid.wavelengths[None, :], positions[:, None], float(sensor) * 10.0, slope)
    o = np.asarray(reflectance, dtype=np.float64)
    signal = np.einsum("iw,pjw->pji", o, spd[:, None, :] * x[None, :, :], optimize=True)
    white = spd @ x.T
    factor = None if normalization == "white" else normalisation_factor(items, normalization, grid)
    temperatures = np.array([item.temperature if item.temperature is not None else np.nan for item in items])
    return SensorBank(positions, temperatures, signal, white, factor, knee=knee, diagonal=sensor == 1)


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


SMALL_SET = 100
"""Reflectance sets up to this size skip the per-illuminant vertex reduction:
for them ten more hulls save nothing (30 skin spectra, sensor 9, compiled
kernel, three alternating runs over 60 triplets: 0.63–0.70 ms per triplet
either way); the 1269 Munsell chips need it."""

QHULL_OPTIONS = "Qt Q5 Q8"
"""Qhull options of the fast method: ``Qt`` (triangulated output, scipy's
default), ``Q5`` (no final check of outer planes) and ``Q8`` (no bookkeeping of
near-inside points): neither changes which points are vertices or the volume
(checked: identical volumes). One measurement showed them 40 % faster; a
careful rerun put the difference within the ±30 % run-to-run noise of these
machines, so no saving is claimed."""


FLAT_SUSPECT = 1e-6
"""A hull whose volume exceeds this fraction of ``L³`` (``L`` the bounding
box's longest side) is not flat by the test of
:func:`skinrender.gamut.is_flat`; only thinner hulls pay for that SVD test (and
the compiled kernel hands them to Qhull).

Why it is safe: a cloud of ``n`` points whose smallest principal extent is at
most 1e-10 of its largest has widths ``w1, w2 ≤ √3·L`` and ``w3 ≤ 2e-10·√(3n)·L``
(a width is at most twice the largest projection, a singular value at most √n
times it), so its hull volume is at most ``1.04e-9·√n·L³``: below this fraction
for every cloud of up to 900 000 points (the search's largest has 126 900)."""


def _hull(cloud: NDArrayFloat) -> tuple[float, np.ndarray | None]:
    """
    Volume and vertex indices of the hull of ``cloud``; for a degenerate cloud
    (flat by the test of :func:`skinrender.gamut.gamut`) volume 0 and ``None``
    (every point is kept, since none can be ruled out).

    The compiled Quickhull (:data:`HULL_KERNEL`) answers the general case;
    Qhull answers what it declines (flat or nearly flat clouds, numerical
    doubt) and everything when the kernel was not built.
    """

    if len(cloud) < 4:
        return 0.0, None
    if _hull3d is not None:
        answer = _hull3d.hull(np.ascontiguousarray(cloud, dtype=np.float64), FLAT_SUSPECT)
        if answer is not None:
            return answer[0], np.frombuffer(answer[1], dtype=np.int32)
    try:
        hull = ConvexHull(cloud, qhull_options=QHULL_OPTIONS)
    except QhullError:
        return 0.0, None
    volume = float(hull.volume)
    if not volume > FLAT_SUSPECT * float(np.max(hull.max_bound - hull.min_bound)) ** 3 and is_flat(cloud):
        return 0.0, None
    return volume, hull.vertices


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
    if _hull3d is not None:  # the same steps in one compiled call
        answer = _hull3d.triplet_volumes(clouds, np.ascontiguousarray(gains), clouds.shape[1] > SMALL_SET,
                                         bank.diagonal, FLAT_SUSPECT)
        if answer is not None:
            return np.frombuffer(answer, dtype=np.float64).copy()
    count_p, count_q = gains.shape[:2]
    if clouds.shape[1] > SMALL_SET:
        parts = []
        shared = _hull(clouds[0])[1] if bank.diagonal else None
        for cloud in clouds:
            vertices = shared if bank.diagonal else _hull(cloud)[1]
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
        volumes[q], vertices = _hull(points)
        case_vertices.append(points if vertices is None else points[vertices])
    volumes[count_q] = _hull(np.concatenate(case_vertices))[0]
    return volumes


# --------------------------------------------------------------------------- #
# Parallel search
# --------------------------------------------------------------------------- #

_WORKER_BANKS: tuple[SensorBank, ...] = ()


def _init_worker(banks: tuple[SensorBank, ...]) -> None:
    global _WORKER_BANKS
    _WORKER_BANKS = banks


def _volumes_chunk(chunk: np.ndarray, method: str, banks: tuple[SensorBank, ...] | None = None,
                   detection: bool = False):
    """
    Volumes of a chunk of index triplets for every bank, shape ``(len(banks), T, Q + 1)``,
    and with ``detection`` the false-positive rates of the skin locus ``(T, Q)`` (else ``None``).
    """
    banks = banks if banks is not None else _WORKER_BANKS
    out = np.empty((len(banks), len(chunk), banks[0].white.shape[0] + 1))
    for b, bank in enumerate(banks):
        volumes = triplet_volumes_fast if method == "fast" else triplet_volumes_naive
        for t, triplet in enumerate(chunk):
            out[b, t] = volumes(bank, triplet)
    if not detection:
        return out, None
    from .locus import triplet_false_positive_rates

    return out, np.array([triplet_false_positive_rates(banks[0], banks[1], t) for t in chunk])


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
    :func:`skinrender.locus.triplet_false_positive_rates`)."""

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
        The rows of Tables 2–5 with ties.

        Returns
        -------
        dict
            ``max_skin``, ``max_munsell``, ``min_ratio``: each a list of
            ``{triplet, temperature_K, value}``; one-calibration rows (Tables
            2, 3) carry the calibration temperature, all-calibration rows
            (Tables 4, 5) ``temperature_K = None``.
        """
        one, everything = slice(0, self.temperatures.size), slice(self.temperatures.size, self.temperatures.size + 1)
        return {
            "max_skin": self._rows(self.skin, one, "max", tolerance) + self._rows(self.skin, everything, "max", tolerance),
            "max_munsell": self._rows(self.munsell, one, "max", tolerance)
            + self._rows(self.munsell, everything, "max", tolerance),
            "min_ratio": self._rows(self.ratio, one, "min", tolerance) + self._rows(self.ratio, everything, "min", tolerance),
            **({} if self.fpr is None else {"min_fpr": self._rows(self.fpr_table, one, "min", tolerance)
                                            + self._rows(self.fpr_table, everything, "min", tolerance)}),
        }

    @property
    def fpr_table(self) -> NDArrayFloat:
        """False-positive rates per calibration and their mean over calibrations, ``(T, Q + 1)``."""
        return np.hstack([self.fpr, np.nanmean(self.fpr, axis=1, keepdims=True)])

    def to_csv(self, path) -> None:
        """Every triplet's volumes (output units³) and ratios as CSV."""
        labels = [f"{t:g}K" for t in self.temperatures] + ["all"]
        header = ["p1_nm", "p2_nm", "p3_nm"]
        header += [f"skin_{label}" for label in labels] + [f"munsell_{label}" for label in labels]
        header += [f"ratio_{label}" for label in labels]
        blocks = [self.triplets, self.skin, self.munsell, self.ratio]
        if self.fpr is not None:
            header += [f"fpr_{label}" for label in labels[:-1]] + ["fpr_mean"]
            blocks.append(self.fpr_table)
        data = np.hstack(blocks)
        with open(path, "w", encoding="utf-8", newline="\n") as handle:
            handle.write(",".join(header) + "\n")
            for row in data:
                handle.write(",".join(f"{v:.17g}" for v in row) + "\n")


def _progress(before: int, done: int, total: int, label: str, stream) -> None:
    """A progress bar on ``stream``: redrawn in place on a terminal, a line per tenth otherwise."""
    if stream is None:
        return
    tty = getattr(stream, "isatty", lambda: False)()
    if not tty and done not in (0, total) and 10 * done // total == 10 * before // total:
        return
    width = 30
    filled = int(width * done / max(total, 1))
    bar = f"{label} [{'#' * filled}{'.' * (width - filled)}] {done}/{total}"
    stream.write(("\r" + bar) if tty else (bar + "\n"))
    if tty and done >= total:
        stream.write("\n")
    stream.flush()


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
) -> SearchResult:
    """
    The Stage 3 search: every triplet's per-calibration and all-calibration
    gamut volumes for a skin and a Munsell set.

    Parameters
    ----------
    sensor
        1 (impulse) or gbell N (FWHM N·10 nm).
    skin, munsell
        Reflectances on ``grid``, shape ``(N, grid.size)``.
    positions
        Peak positions (``"400:700:10"`` nm gives the paper's 31, 4495 triplets).
    illuminants
        The prevailing/calibration set (K).
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
    notice
        Stream for the one-line notice when the compiled hull kernel is
        missing (``result.info["hull_kernel"]`` says which kernel ran).

    Returns
    -------
    :class:`SearchResult`
    """

    if method not in ("fast", "naive"):
        raise SkinrenderError(f"method must be 'fast' or 'naive', got {method!r}")
    where = positions_grid(positions)
    banks = tuple(
        sensor_bank(sensor, values, where, illuminants, slope, normalization, knee, grid) for values in (skin, munsell)
    )
    index = triplets(where.size)
    workers = (os.cpu_count() or 1) if workers is None else int(workers)
    if workers < 1:
        raise SkinrenderError(f"workers must be ≥ 1, got {workers}")
    start = time.perf_counter()
    if method == "fast":
        _notice_kernel(notice)
    # Several chunks per worker keep every core busy to the end.
    chunks = _chunks(np.arange(len(index)), 1 if workers == 1 and dask is None else 8 * max(workers, 4))
    out = np.empty((2, len(index), banks[0].white.shape[0] + 1))
    fpr = np.empty((len(index), banks[0].white.shape[0])) if detection else None
    done = 0

    def store(chunk, result) -> None:
        out[:, chunk] = result[0]
        if detection:
            fpr[chunk] = result[1]

    _progress(0, 0, len(index), label, progress)
    if dask is not None:
        client, own = _dask_client(dask)
        try:
            remote_banks = client.scatter(banks, broadcast=True)
            futures = [client.submit(_volumes_chunk, index[c], method, remote_banks, detection, pure=False)
                       for c in chunks]
            for chunk, future in zip(chunks, futures):
                store(chunk, future.result())
                done += len(chunk)
                _progress(done - len(chunk), done, len(index), label, progress)
        finally:
            if own:
                client.close()
    elif workers == 1:
        for chunk in chunks:
            store(chunk, _volumes_chunk(index[chunk], method, banks, detection))
            done += len(chunk)
            _progress(done - len(chunk), done, len(index), label, progress)
    else:
        with ProcessPoolExecutor(workers, initializer=_init_worker, initargs=(banks,)) as pool:
            futures = [pool.submit(_volumes_chunk, index[c], method, None, detection) for c in chunks]
            for chunk, future in zip(chunks, futures):
                store(chunk, future.result())
                done += len(chunk)
                _progress(done - len(chunk), done, len(index), label, progress)
    elapsed = time.perf_counter() - start
    return SearchResult(
        float(sensor), float(slope), where, where[index], banks[0].temperatures, out[0], out[1], elapsed,
        method, 1 if dask is not None else workers, normalization, knee, fpr=fpr,
        info={"hull_kernel": HULL_KERNEL if method == "fast" else "qhull"},
    )


_NOTICED: list[bool] = []


def _notice_kernel(stream) -> None:
    """One line on ``stream``, once per process, when the compiled hull kernel is missing."""
    if _hull3d is None and stream is not None and not _NOTICED:
        _NOTICED.append(True)
        print(
            "skinrender: notice: the compiled hull kernel skinrender._hull3d is missing (installed without a C "
            "compiler); the search uses Qhull for every hull, about 5x slower. Reinstall with gcc present.",
            file=stream,
        )


def _dask_client(dask):
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - depends on the environment
        raise SkinrenderError(
            "--dask needs the 'distributed' package: pip install 'skinrender[dask]'"
        ) from None
    if isinstance(dask, Client):
        return dask, False
    return Client(dask), True

