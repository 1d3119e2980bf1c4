"""
Noise
=====

From expected electrons to digital numbers (DN): the shot, read and
quantisation noise, full-well saturation and ADC clipping of the EMVA 1288
linear camera model, as analytic mean and variance and as seeded Monte Carlo
frames, and the noise carried to white-balanced NCC chromaticities.

-   :func:`statistics_dn`, :func:`signal_dn`: the analytic mean (DN) and
    variance (DN²) of a pixel.
-   :func:`code_probabilities`: the probability of each output code, DN,
    where the noise is narrow (a few codes: the lattice the tests need).
-   :func:`simulate_dn`, :func:`random_generator`: one noisy frame, seeded;
    :func:`simulate_dn_clipped`: the same frame and which pixels the full
    well or the ADC range clipped; :func:`clipping_counts`,
    :func:`clipping_note`: how much, per channel.
-   :func:`ncc_covariance`: first-order propagation to NCC (Eq. 2).

The chain, as in a real sensor: Poisson photo- and dark electrons, the charge
clipped to the well [0, full_well_e] e⁻; read noise added to the voltage after
the charge; × K (DN/e⁻); + black level (DN); rounded to a code; clipped to the
ADC range [0, 2^bits − 1] DN. With a black level several read-noise σ above
0 DN, a dark frame keeps its read noise unclipped (its mean is the black
level, its variance K² σ_r² + 1/12 DN²), as a photon-transfer measurement
needs.

Units: charge e⁻, output DN, variance DN², system gain K in DN/e⁻.

References
----------
-   :cite:`EMVA1288` : European Machine Vision Association (2021). EMVA
    Standard 1288, Release 4.0 Linear: μ_y = μ_y.dark + K μ_e,
    σ_y² = K² σ_d² + K² μ_e + σ_q², σ_q² = 1/12 DN², and saturation.
-   :cite:`Owen1956` : D. B. Owen (1956). Tables for computing bivariate
    normal probabilities. Ann. Math. Statist. 27(4), 1075–1090 (the bivariate
    normal CDF through Owen's T, used near the full well).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..errors import SkinrenderError
from ..hints import ArrayLike, NDArrayFloat
from .imager import Imager, checked_array, is_integer
from .imager import imager as imager_of

__all__ = ["clipping_counts", "clipping_note", "code_probabilities", "ncc_covariance", "random_generator", "signal_dn",
           "simulate_dn", "simulate_dn_clipped", "statistics_dn"]

_WINDOW_SIGMA = 8.0  # exact sums over codes reach ±8 σ: the normal tail beyond is < 1e-15
_SWITCH_DN = 4.0  # σ ≥ 4 DN: closed form, whose Euler–Maclaurin remainder is < 1e-5 DN
_POISSON_CAP = 1e18  # numpy's Poisson limit; any larger mean fills every real well
_CHUNK_CELLS = 1 << 21  # pixel × code cells summed at once (bounded memory)


def _moments_closed(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """Normal N(m, s²) censored at the codes low, high, plus the Euler–Maclaurin rounding terms."""
    from scipy.special import ndtr  # in the functions that use it: a heavy import most commands never use
    za, zb = (low - m) / s, (high - m) / s
    below, above = ndtr(za), ndtr(-zb)
    inside = np.maximum(1.0 - below - above, 0.0)
    fa, fb = np.exp(-0.5 * za**2) / math.sqrt(2 * math.pi), np.exp(-0.5 * zb**2) / math.sqrt(2 * math.pi)
    mz = za * below + zb * above + fa - fb  # E[clip(Z, za, zb)], Z standard normal
    vz = ((za - mz) ** 2 * below + (zb - mz) ** 2 * above + (1 + mz**2) * inside
          - 2 * mz * (fa - fb) + za * fa - zb * fb)  # Var[clip(Z, za, zb)]
    c1 = (fb - fa) / (24 * s)
    variance = s**2 * vz + inside / 12 + ((zb - mz) * fb - (za - mz) * fa) / 12 - c1**2
    # m + s·mz, written from the code U when m lies beyond it (m may then dwarf U in float64)
    beyond = high + s * (za * below - zb * ndtr(zb) + fa - fb)
    return np.where(m > high, beyond, m + s * mz) + c1, np.maximum(variance, 0.0)


def _exceed_normal(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """The window's first code, DN, its steps and P(DN > code) of clip(round(N(m, s²)), low, high), per row."""
    from scipy.special import ndtr
    start = np.clip(np.floor(m - _WINDOW_SIGMA * s), low, high)
    steps = np.arange(math.ceil(2 * _WINDOW_SIGMA * s.max(initial=0.0)) + 2, dtype=np.float64)
    code = start[:, None] + steps
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        z = (m[:, None] - code - 0.5) / s[:, None]
    z = np.where(s[:, None] > 0, z, np.where(m[:, None] > code + 0.5, np.inf, -np.inf))
    return start, steps, np.where(code < high, ndtr(z), 0.0)


def _moments_exact(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """Mean and variance of clip(round(N(m, s²)), low, high), summed code by code."""
    start, steps, exceed = _exceed_normal(m, s, low, high)  # E[d] = Σ P(d > j), E[d²] = Σ (2j+1) P(d > j)
    shift = exceed.sum(axis=1)
    return start + shift, np.maximum(((2 * steps + 1) * exceed).sum(axis=1) - shift**2, 0.0)


def _moments_normal(m: NDArrayFloat, s: NDArrayFloat, low: float, high: float) -> tuple[NDArrayFloat, ...]:
    """clip(round(N(m, s²)), low, high): linear far from the bounds, closed form for s ≥ 4 DN, else exact."""
    mean, variance = np.empty_like(m), np.empty_like(m)
    free = (m - low > _WINDOW_SIGMA * s) & (high - m > _WINDOW_SIGMA * s) & (s >= _SWITCH_DN)
    mean[free], variance[free] = m[free], s[free] ** 2 + 1 / 12  # unclipped: the linear model
    wide = (s >= _SWITCH_DN) & ~free
    with np.errstate(over="ignore", under="ignore"):
        mean[wide], variance[wide] = _moments_closed(m[wide], s[wide], low, high)
    narrow = np.flatnonzero(s < _SWITCH_DN)
    narrow = narrow[np.argsort(s[narrow], kind="stable")]  # chunks of like σ need like windows
    for chunk in np.array_split(narrow, max(1, narrow.size // 65536)):
        mean[chunk], variance[chunk] = _moments_exact(m[chunk], s[chunk], low, high)
    return mean, variance


def _bivariate_normal_cdf(h: NDArrayFloat, k: NDArrayFloat, rho: NDArrayFloat, r: NDArrayFloat) -> NDArrayFloat:
    """P(Z₁ < h, Z₂ < k) for standard normals of correlation ρ, r = √(1 − ρ²) > 0, by Owen's T [Owen1956]."""
    from scipy.special import ndtr, owens_t
    h = np.where(h == 0, 1e-300, h)  # the formula divides by h and k; the nudge changes nothing else
    k = np.where(k == 0, 1e-300, k)
    with np.errstate(over="ignore"):
        t = owens_t(h, (k - rho * h) / (h * r)) + owens_t(k, (h - rho * k) / (k * r))
    return 0.5 * (ndtr(h) + ndtr(k)) - t - np.where(h * k < 0, 0.5, 0.0)


def _moments_filling(mu: NDArrayFloat, im: Imager) -> tuple[NDArrayFloat, ...]:
    """Mean and variance, code by code, of pixels whose well fills in some frames and not in others.

    Y = b + K (min(X, μ_sat) + R), X ~ N(μ, μ), R ~ N(0, σ_r²):
    P(Y < y) = Φ₂(h, k; ρ) + (1 − Φ(h)) Φ((w − μ_sat) / σ_r) with w = (y − b) / K,
    h = (μ_sat − μ) / √μ, k = (w − μ) / √(μ + σ_r²), ρ = √(μ / (μ + σ_r²)).
    """
    from scipy.special import ndtr
    gain, black, well, read = im.gain_dn_per_e, im.black_level_dn, im.full_well_e, im.read_noise_e
    spread = _WINDOW_SIGMA * (np.sqrt(mu) + read)  # e⁻
    start = np.clip(np.floor(black + gain * (np.minimum(mu, well) - spread)) - 1, 0, im.max_dn)
    end = np.full_like(mu, np.clip(math.ceil(black + gain * (well + _WINDOW_SIGMA * read)) + 1, 0, im.max_dn))
    mean, variance = np.empty_like(mu), np.empty_like(mu)
    order = np.argsort(end - start, kind="stable")
    widest = float((end - start).max(initial=0.0)) + 1
    for chunk in np.array_split(order, max(1, math.ceil(order.size * widest / _CHUNK_CELLS))):
        steps = np.arange(float((end[chunk] - start[chunk]).max(initial=0.0)) + 1)
        code = start[chunk, None] + steps  # DN
        m = mu[chunk, None]
        w = (code + 0.5 - black) / gain  # e⁻: DN > code ⇔ Y ≥ code + ½
        h = (well - m) / np.sqrt(m)
        if read > 0:
            total = np.sqrt(m + read**2)
            below = _bivariate_normal_cdf(h, (w - m) / total, np.sqrt(m) / total, read / total)
            below = below + ndtr(-h) * ndtr((w - well) / read)
        else:  # no read noise: Y < y ⇔ min(X, μ_sat) < w
            below = np.where(w > well, 1.0, ndtr((np.minimum(w, well) - m) / np.sqrt(m)))
        exceed = np.where(code < im.max_dn, np.clip(1.0 - below, 0.0, 1.0), 0.0)  # P(DN > code)
        shift = exceed.sum(axis=1)
        mean[chunk] = start[chunk] + shift
        variance[chunk] = np.maximum(((2 * steps + 1) * exceed).sum(axis=1) - shift**2, 0.0)
    return mean, variance


def statistics_dn(imager: str | Path | Imager, electrons_mean: ArrayLike) -> tuple[NDArrayFloat, ...]:
    """
    The analytic mean, DN, and variance, DN², of the pixels :func:`simulate_dn` draws.

    Parameters
    ----------
    imager
        An :class:`~skinrender.model.imager.Imager`, a preset name or a TOML path.
    electrons_mean
        Expected electrons, photo plus dark, e⁻ ≥ 0, any shape.

    Returns
    -------
    tuple of :class:`numpy.ndarray`
        ``(mean, variance)``, DN and DN², each of ``electrons_mean``'s shape.

    Notes
    -----
    The photo- and dark charge X is taken as normal, mean μ, variance μ
    (Poisson); the well keeps min(X, μ_sat); the read noise R ~ N(0, σ_r²) is
    added after it, so DN = clip(round(Y), 0, 2^bits − 1) with
    Y = b + K (min(X, μ_sat) + R). Three cases:

    -   the well never fills (μ_sat − μ > 8 √μ): Y ~ N(K μ + b, K² (μ + σ_r²));
    -   it always fills (μ − μ_sat > 8 √μ): Y ~ N(K μ_sat + b, K² σ_r²), so a
        saturated pixel keeps its read noise unless the ADC clips it;
    -   in between, the CDF of Y is a bivariate normal one (see
        ``_moments_filling``) and the moments are summed over the codes.

    A normal Y censored at the ADC codes 0 and U = 2^bits − 1 has its moments
    summed exactly over the codes for s < 4 DN; above, they are the censored
    normal plus the Euler–Maclaurin terms of the rounding (remainder < 1e-5 DN),
    which give the quantisation variance 1/12 DN² weighted by the unclipped
    probability. Far from 0 and U: mean K μ + b, variance K² (μ + σ_r²) + 1/12.
    The normal approximation ignores the Poisson skew (μ^-1/2) and the lattice
    of a count without read noise: expect errors up to ~1e-2 DN where
    σ_r ≪ 1 e⁻ and the signal is a few electrons (against 200 000-pixel Monte
    Carlo runs; elsewhere within their error).

    Examples
    --------
    >>> mean, var = statistics_dn("sony-imx174", [0.0, 1e4, 1e6])  # K = 0.1225 DN/e⁻, b = 16 DN
    >>> print(f"{mean[0]:.2f} {var[0]:.3f} | {mean[1]:.2f} {var[1]:.2f} | {mean[2]:.2f} {var[2]:.3f}")
    16.00 0.783 | 1241.00 150.85 | 4020.65 0.783
    """

    im = imager_of(imager)
    mu = np.minimum(checked_array(electrons_mean, "electrons_mean", "e⁻"), _POISSON_CAP)
    flat = mu.ravel()
    m, s, normal = _normal_parameters(im, flat)
    mean, variance = np.empty_like(flat), np.empty_like(flat)
    mean[normal], variance[normal] = _moments_normal(m[normal], s[normal], 0.0, float(im.max_dn))
    filling = ~normal
    mean[filling], variance[filling] = _moments_filling(flat[filling], im)
    return mean.reshape(mu.shape), variance.reshape(mu.shape)


def signal_dn(imager: str | Path | Imager, electrons_mean: ArrayLike) -> NDArrayFloat:
    """
    The analytic mean output, DN, for ``electrons_mean`` e⁻ (:func:`statistics_dn`'s mean).

    Examples
    --------
    >>> print(f"{signal_dn('sony-imx174', 0.0):.3f} DN")  # a dark pixel reads the black level
    16.000 DN
    """
    return statistics_dn(imager, electrons_mean)[0]


def _normal_parameters(im: Imager, flat: NDArrayFloat) -> tuple[NDArrayFloat, ...]:
    """Per pixel: the normal Y's mean m, DN, and std s, DN, and whether the well never or always fills."""
    gain, black, well, read = im.gain_dn_per_e, im.black_level_dn, im.full_well_e, im.read_noise_e
    shot = np.sqrt(flat)
    empty_well, full_well = well - flat > _WINDOW_SIGMA * shot, flat - well > _WINDOW_SIGMA * shot
    m = np.where(empty_well, gain * flat, gain * well) + black
    s = np.where(empty_well, gain * np.sqrt(flat + read**2), gain * read)
    return m, s, empty_well | full_well


def code_probabilities(imager: str | Path | Imager, electrons_mean: ArrayLike) -> tuple[NDArrayFloat, ...]:
    """
    The probability of every output code, DN, of pixels whose noise spans a few codes.

    Parameters
    ----------
    imager
        An :class:`~skinrender.model.imager.Imager`, a preset name or a TOML path.
    electrons_mean
        Expected electrons, photo plus dark, e⁻ ≥ 0, shape ``(n,)``.

    Returns
    -------
    tuple of :class:`numpy.ndarray`
        ``(first, pmf)``: the first code of each pixel's window, DN, ``(n,)``,
        and P(DN = first + j), ``(n, w)``, each row summing to 1 (to < 1e-14).
        Rows are NaN where this model gives no code by code law: the noise
        σ ≥ 4 DN (closed-form moments) or a well that fills in some frames.

    Notes
    -----
    The law :func:`statistics_dn` sums (the normal Y rounded and clipped to
    the ADC range): P(DN = j) = P(DN > j − 1) − P(DN > j). With sub-DN noise a
    pixel takes one to three codes, and tests on patch statistics need this
    lattice, not a normal law.

    Examples
    --------
    >>> first, pmf = code_probabilities("sony-icx418", [1000.0])  # 8 + 6 DN, σ = 0.22 DN
    >>> print(int(first[0] + pmf[0].argmax()), f"{pmf[0].max():.4f}")
    14 0.9741
    """
    im = imager_of(imager)
    flat = np.minimum(checked_array(electrons_mean, "electrons_mean", "e⁻"), _POISSON_CAP).ravel()
    m, s, normal = _normal_parameters(im, flat)
    narrow = normal & (s < _SWITCH_DN)
    first = np.full(flat.shape, np.nan)
    start, _, exceed = _exceed_normal(m[narrow], s[narrow], 0.0, float(im.max_dn))
    pmf = np.full((flat.size, exceed.shape[1]), np.nan)
    first[narrow] = start
    pmf[narrow] = -np.diff(np.concatenate([np.ones((exceed.shape[0], 1)), exceed], axis=1), axis=1)
    return first, np.maximum(pmf, 0.0, where=~np.isnan(pmf), out=pmf)


def random_generator(rng_or_seed: np.random.Generator | int, name: str = "rng_or_seed") -> np.random.Generator:
    """
    A numpy Generator: ``rng_or_seed`` itself, or a new one from an integer seed in [0, 2³²).

    Raises
    ------
    SkinrenderError
        Naming ``name`` for anything else (a negative or too large seed, a
        float, a bool, a string).

    Examples
    --------
    >>> print(f"{random_generator(7).random():.6f}")
    0.625095
    """
    if isinstance(rng_or_seed, np.random.Generator):
        return rng_or_seed
    if is_integer(rng_or_seed) and 0 <= rng_or_seed < 2**32:
        return np.random.default_rng(int(rng_or_seed))
    raise SkinrenderError(f"{name} must be a numpy Generator or an integer seed in [0, 2**32), got {rng_or_seed!r}")


def simulate_dn(
    imager: str | Path | Imager, electrons_mean: ArrayLike, rng_or_seed: np.random.Generator | int
) -> NDArrayFloat:
    """
    One noisy frame, DN, for the expected electrons ``electrons_mean``.

    Parameters
    ----------
    imager, electrons_mean
        As :func:`statistics_dn`: the imager, and the expected electrons (e⁻, any shape).
    rng_or_seed
        A numpy Generator, or an integer seed in [0, 2³²).

    Returns
    -------
    :class:`numpy.ndarray`
        Integer codes, DN, as floats, of ``electrons_mean``'s shape;
        deterministic for a seed or a Generator's state.

    Notes
    -----
    Poisson(μ) electrons (shot noise with dark) → clip to the well
    [0, full_well_e] e⁻ → + Normal(0, σ_r²) read noise → × K + black level →
    round to the nearest code (ties to even) → clip to [0, 2^bits − 1] DN.

    Examples
    --------
    >>> frame = simulate_dn("sony-imx174", np.zeros(100_000), 7)  # dark: black level 16 DN, read noise kept
    >>> print(f"{frame.mean():.2f} DN, {frame.std():.2f} DN")
    16.00 DN, 0.88 DN
    """

    return simulate_dn_clipped(imager, electrons_mean, rng_or_seed)[0]


def simulate_dn_clipped(
    imager: str | Path | Imager, electrons_mean: ArrayLike, rng_or_seed: np.random.Generator | int
) -> tuple[NDArrayFloat, NDArrayFloat, NDArrayFloat]:
    """
    :func:`simulate_dn`'s frame (the same draws) and where it was clipped.

    Returns
    -------
    tuple of :class:`numpy.ndarray`
        ``(dn, well_full, adc_clipped)``: the frame, DN, and two boolean
        arrays of its shape: the charge reached the full well (and was
        clipped to it), the code fell outside [0, 2^bits − 1] DN (and was
        clipped to the range).

    Examples
    --------
    >>> dn, full, clipped = simulate_dn_clipped("sony-icx418", [1e3, 5e4, 5e5], 7)  # well 40 000 e⁻
    >>> full.tolist(), clipped.tolist()
    ([False, True, True], [False, False, False])
    """
    im = imager_of(imager)
    mu = checked_array(electrons_mean, "electrons_mean", "e⁻")
    rng = random_generator(rng_or_seed)
    drawn = rng.poisson(np.minimum(mu, _POISSON_CAP))
    charge = np.minimum(drawn, im.full_well_e)  # the well: [0, μ_sat] e⁻
    volts = im.gain_dn_per_e * (charge + rng.normal(0.0, im.read_noise_e, mu.shape)) + im.black_level_dn
    codes = np.rint(volts)
    return np.clip(codes, 0.0, float(im.max_dn)), drawn >= im.full_well_e, (codes < 0) | (codes > im.max_dn)


def clipping_counts(well_full: ArrayLike, adc_clipped: ArrayLike, pixels: int | None = None) -> dict:
    """
    How much of a frame ``(..., 3)`` the full well and the ADC range clipped, per channel R, G, B.

    ``well_full``, ``adc_clipped``: :func:`simulate_dn_clipped`'s masks, or counts of clipped draws per pixel;
    ``pixels``: the pixels (draws) per channel, default the frame's. Returns ``pixels``, ``well_full`` and
    ``adc_clipped`` (counts per channel) and their ``*_share`` (fractions of ``pixels``).

    Examples
    --------
    >>> counts = clipping_counts(np.array([[[1, 0, 0]], [[1, 1, 0]]]), np.zeros((2, 1, 3)))
    >>> counts["well_full"], counts["well_full_share"], counts["adc_clipped"]
    ([2, 1, 0], [1.0, 0.5, 0.0], [0, 0, 0])
    """
    full = np.asarray(well_full, dtype=np.int64).reshape(-1, 3).sum(axis=0)
    clipped = np.asarray(adc_clipped, dtype=np.int64).reshape(-1, 3).sum(axis=0)
    pixels = int(np.prod(np.shape(well_full)[:-1])) if pixels is None else int(pixels)
    return {"pixels": pixels, "well_full": full.tolist(), "well_full_share": (full / max(pixels, 1)).tolist(),
            "adc_clipped": clipped.tolist(), "adc_clipped_share": (clipped / max(pixels, 1)).tolist()}


def clipping_note(counts: dict) -> str | None:
    """One line where :func:`clipping_counts` found clipped pixels, ``None`` where none were."""
    if not (any(counts["well_full"]) or any(counts["adc_clipped"])):
        return None
    shares = lambda key: "/".join(f"{100 * v:.3g}" for v in counts[key + "_share"])  # noqa: E731
    return (f"clipped: {shares('well_full')} % of the pixels (R/G/B) at the full well, {shares('adc_clipped')} % "
            "at the ADC range: their values are not the light's")


def ncc_covariance(mean: ArrayLike, cov_or_var: ArrayLike, gains: ArrayLike) -> NDArrayFloat:
    """
    Covariance of the NCC chromaticities of white-balanced channels, by first-order propagation.

    Parameters
    ----------
    mean
        Channel means x (black level subtracted), DN, shape ``(..., 3)``.
    cov_or_var
        Their variances, DN², shape ``(..., 3)`` (independent channels), or
        covariance, DN², ``(..., 3, 3)``.
    gains
        White-balance gains g_k > 0 (Eq. 4 style, out_k = g_k x_k), output
        units per DN, ``(..., 3)``.

    Returns
    -------
    :class:`numpy.ndarray`
        Covariance of (r, g, b) = out / Σ out (unitless), shape ``(..., 3, 3)``;
        rows sum to 0.

    Notes
    -----
    J_ij = ∂c_i/∂x_j = (g_j / S)(δ_ij − c_i) with S = Σ g_k x_k, and
    Σ_c = J Σ_x Jᵀ; the neglected terms are of relative order (σ/x)².

    Examples
    --------
    >>> cov = ncc_covariance([100.0, 100.0, 100.0], [100.0, 100.0, 100.0], [1, 1, 1])
    >>> print(f"{cov[0, 0]:.7f} {cov[0, 1]:.7f}")  # 100/300² · (4/9 + 2/9) and · (−1/3)
    0.0007407 -0.0003704
    """

    x = checked_array(mean, "mean", "DN", low=None)
    c = checked_array(cov_or_var, "cov_or_var", "DN²", low=None)
    g = checked_array(gains, "gains", "(output units per DN)")
    if x.ndim == 0 or x.shape[-1] != 3 or g.ndim == 0 or g.shape[-1] != 3 or np.any(g <= 0):
        raise SkinrenderError("mean and gains must have 3 channels last, and gains must be > 0")
    if c.ndim >= 2 and c.ndim == x.ndim + 1 and c.shape[-2:] == (3, 3):
        covariance = c
    elif c.ndim == x.ndim and c.shape[-1] == 3 and np.all(c >= 0):
        covariance = c[..., :, None] * np.eye(3)
    else:
        raise SkinrenderError(
            f"cov_or_var must be variances ≥ 0, shape (..., 3), or a covariance, (..., 3, 3); got {c.shape}"
        )
    out = g * x
    total = out.sum(axis=-1)
    if np.any(total <= 0):
        raise SkinrenderError("mean: the white-balanced channels must have a positive sum")
    ncc = out / total[..., None]
    jacobian = (g[..., None, :] / total[..., None, None]) * (np.eye(3) - ncc[..., :, None])
    return jacobian @ covariance @ np.swapaxes(jacobian, -1, -2)
