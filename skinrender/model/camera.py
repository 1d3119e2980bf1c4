"""
Camera
======

The paper's camera: three sensors (gbell, impulse or measured), made once
from a spec string at the public boundary and passed on as an object.

-   :class:`Camera`, :func:`camera`: a camera from a spec string.
-   :func:`sensor_curves`: the paper's gbell (sensor N, FWHM N·10 nm) or
    impulse (sensor 1) curves at given peaks; the Stage 3 search builds its
    single sensors with it too.
-   :data:`CHANNELS`, :data:`GBELL_SLOPE_DEFAULT`.

Units: wavelength in nm; sensitivities are unitless (gbell peak 1, impulse a
unit-area delta, measured curves as published).

References
----------
-   :cite:`Martinkauppi2006` : the paper's Stage 3 sensors (docs/references.md).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..datasets import SpectralSet, camera_sensitivities, looks_like_path
from ..errors import SkinrenderError, given_role
from ..hints import ArrayLike, Literal, NDArrayFloat
from ..methods import validate_method
from ..spectra import EXTRAPOLATIONS, GRID_DEFAULT, WavelengthGrid, as_grid, gbell, impulse
from ..spectral_csv import read_spectra_csv

__all__ = ["CHANNELS", "GBELL_SLOPE_DEFAULT", "Camera", "camera", "sensor_curves"]

CHANNELS = ("R", "G", "B")
"""Channel order of every camera: R is the longest-wavelength sensor, B the shortest."""

GBELL_SLOPE_DEFAULT = 2.0
"""Default gbell slope *b* (the paper does not give it; see :func:`skinrender.spectra.gbell`)."""

@dataclass(frozen=True, eq=False)
class Camera:
    """
    A three-channel camera.

    Parameters
    ----------
    name
        The spec it was made from (``gbell:9@450,540,610``, a camera name, a path).
    kind
        ``gbell``, ``impulse`` or ``measured``.
    peaks
        Sensor peaks in nm, in channel order R, G, B (longest first), for gbell
        and impulse cameras.
    fwhm
        gbell full width at half maximum, nm (sensor *N* ⇒ ``N · 10`` nm).
    slope
        gbell slope *b*.
    measured
        Measured sensitivities (R, G, B rows) for ``kind == "measured"``.
    """

    name: str
    kind: Literal["gbell", "impulse", "measured"]
    peaks: tuple[float, float, float] | None = None
    fwhm: float | None = None
    slope: float = GBELL_SLOPE_DEFAULT
    measured: SpectralSet | None = None
    _cache: dict = field(default_factory=dict, repr=False)

    @property
    def channels(self) -> tuple[str, str, str]:
        """Channel names, ``("R", "G", "B")``."""
        return CHANNELS

    @property
    def extrapolation(self) -> str | None:
        """
        How measured curves extend beyond their data onto a wider grid (``refuse``, ``zero``, ``constant``: the
        ``extrapolation`` the camera was made with), ``None`` for a model camera (gbell, impulse).

        >>> camera("gbell:9@450,540,610").extrapolation is None
        True
        """
        return None if self.measured is None else self.measured.extrapolation

    def sensitivities(self, grid: WavelengthGrid = GRID_DEFAULT) -> NDArrayFloat:
        """
        Sensitivities on ``grid``, shape ``(3, grid.size)``, rows R, G, B.

        gbell curves are evaluated at the grid wavelengths (peak 1); the
        impulse is a unit-area delta on the grid sample of its peak (the peak
        must lie on the grid); measured curves are linearly interpolated with
        the dataset's extrapolation rule (zero outside the measured range for
        bundled cameras).
        """
        grid = as_grid(grid)
        if grid not in self._cache:
            if self.kind == "measured":
                values = self.measured.on(grid)
            else:
                _check_peaks(self, grid)
                values = sensor_curves(self.peaks, grid, self.fwhm, self.slope)
            values = np.ascontiguousarray(values, dtype=np.float64)
            values.setflags(write=False)
            self._cache[grid] = values
        return self._cache[grid]

    def __str__(self) -> str:
        return self.name


_PATTERN_GBELL = re.compile(
    r"^gbell:\s*(?P<n>[0-9.eE+-]+)\s*(,\s*b\s*=\s*(?P<b>[0-9.eE+-]+))?\s*@(?P<peaks>.*)$", re.IGNORECASE
)
_PATTERN_IMPULSE = re.compile(r"^impulse\s*@(?P<peaks>.*)$", re.IGNORECASE)


def _check_peaks(cam: "Camera", grid: WavelengthGrid) -> None:
    """A model camera's peaks lie on the grid's range, nm (outside it a channel sees only its curve's tail)."""
    start, end = float(grid.wavelengths[0]), float(grid.wavelengths[-1])
    outside = [p for p in cam.peaks if not start <= p <= end]
    if outside:
        hint = " (peaks are in nm, not µm)" if max(outside) < 10 else ""
        which = "peak " + ", ".join(f"{p:g}" for p in outside) + (" nm lies" if len(outside) == 1 else " nm lie")
        raise SkinrenderError(f"camera {cam.name!r}: {which} outside "
                              f"the grid {start:g}–{end:g} nm{hint}: give peaks inside it, or a wider grid",
                              role="camera")


def _parse_peaks(text: str, spec: str) -> tuple[float, float, float]:
    try:
        peaks = tuple(float(p) for p in text.replace("nm", "").split(","))
    except ValueError:
        peaks = ()
    if len(peaks) != 3 or not all(np.isfinite(p) and p > 0 for p in peaks):
        raise SkinrenderError(
            f"camera {spec!r}: expected three peak wavelengths in nm after '@', e.g. @450,540,610", role="camera"
        )
    # channel order R, G, B: longest wavelength first
    return tuple(sorted(peaks, reverse=True))  # type: ignore[return-value]


def camera(spec: str | Camera, extrapolation: str = "refuse") -> Camera:
    """
    A camera from its spec.

    Parameters
    ----------
    spec
        -   ``gbell:N@P1,P2,P3``: the paper's sensor *N* (FWHM ``N · 10`` nm,
            ``N > 0``; the paper uses 3, 5, …, 15) at peaks P1, P2, P3 nm;
            ``gbell:N,b=B@…`` sets the slope (default
            :data:`GBELL_SLOPE_DEFAULT`).
        -   ``impulse@P1,P2,P3``: the paper's sensor 1.
        -   a bundled camera name (``skinrender cameras`` lists them).
        -   a CSV path: wavelength (nm), then R, G, B sensitivities.

        Channels are ordered R, G, B from the longest peak to the shortest,
        whatever order the peaks are written in.
    extrapolation
        For a CSV camera: the rule where the integration grid leaves the
        measured range (``refuse``, the default, ``zero`` or ``constant``).

    Returns
    -------
    :class:`Camera`
        ``sensitivities(grid)`` gives its three curves on a grid (nm), rows R, G, B, unitless.

    Raises
    ------
    SkinrenderError
        A malformed spec (``role`` ``camera``), an unknown camera name, a CSV that cannot be read, has
        other than three sensitivity columns or a channel zero everywhere, or an unknown ``extrapolation``.

    Examples
    --------
    Peaks may be written in any order; channels come out R, G, B (longest first):

    >>> camera("gbell:9@450,540,610").peaks
    (610.0, 540.0, 450.0)

    A CSV camera measured over 450–650 nm, its curves held at their end values beyond the data with
    ``extrapolation="constant"`` (with the default, ``refuse``, a wider grid is an error):

    >>> import tempfile
    >>> path = Path(tempfile.mkdtemp()) / "cam.csv"
    >>> _ = path.write_text("wavelength,R,G,B\\n450,0.0,0.2,1.0\\n550,0.2,1.0,0.2\\n650,1.0,0.2,0.0\\n")
    >>> cam = camera(str(path), extrapolation="constant")
    >>> cam.kind, cam.extrapolation
    ('measured', 'constant')
    >>> cam.sensitivities(WavelengthGrid(400, 700, 50))[0].tolist()  # R
    [0.0, 0.0, 0.1, 0.2, 0.6, 1.0, 1.0]
    """

    validate_method(extrapolation, EXTRAPOLATIONS, "extrapolation")  # a bundled camera's own rule is its dataset's
    if isinstance(spec, Camera):
        return spec
    text = str(spec).strip()
    match = _PATTERN_GBELL.match(text)
    if match:
        try:
            n = float(match["n"])
            slope = float(match["b"]) if match["b"] else GBELL_SLOPE_DEFAULT
        except ValueError:
            raise SkinrenderError(f"camera {text!r}: sensor number and slope must be numbers",
                                  role="camera") from None
        if not (np.isfinite(n * 10.0) and n > 0):
            raise SkinrenderError(f"camera {text!r}: sensor number N must be > 0 (FWHM = N·10 nm)", role="camera")
        if not (np.isfinite(slope) and slope > 0):
            raise SkinrenderError(f"camera {text!r}: slope b must be > 0", role="camera")
        return Camera(text, "gbell", _parse_peaks(match["peaks"], text), n * 10.0, slope)
    match = _PATTERN_IMPULSE.match(text)
    if match:
        return Camera(text, "impulse", _parse_peaks(match["peaks"], text))
    if text.lower().startswith(("gbell", "impulse")):
        raise SkinrenderError(
            f"camera {text!r}: expected 'gbell:N@P1,P2,P3', 'gbell:N,b=B@P1,P2,P3' or 'impulse@P1,P2,P3'",
            role="camera",
        )
    return given_role("camera", _measured_camera, text, extrapolation)  # a file's or a name's fault: the camera's


def _measured_camera(text: str, extrapolation: str) -> Camera:
    """A camera from a CSV path or a bundled camera's name."""
    if looks_like_path(text):
        table = read_spectra_csv(text, kind="sensitivity", expected_columns=3)
        if np.any(table.values.max(axis=1) <= 0):
            raise SkinrenderError(f"{text}: a channel is zero at every wavelength")
        measured = SpectralSet(
            Path(text).name, table.wavelengths, table.values, CHANNELS, source=text,
            licence="user data", extrapolation=extrapolation, kind="sensitivity",
        )
        return Camera(text, "measured", measured=measured)
    return Camera(text, "measured", measured=camera_sensitivities(text))


def sensor_curves(peaks: ArrayLike, grid: WavelengthGrid, fwhm: float | None = None,
                  slope: float = GBELL_SLOPE_DEFAULT) -> NDArrayFloat:
    """
    The paper's sensors at ``peaks`` (nm) on ``grid``, shape ``(len(peaks), grid.size)``.

    ``fwhm`` (nm) gives gbell curves of peak 1 (sensor *N* has ``N · 10`` nm)
    with slope *b*; ``None`` gives impulses, each a unit-area delta on the
    grid sample of its peak (which must lie on the grid).

    Examples
    --------
    Sensor 9 (FWHM 90 nm, so a = 45 nm) with b = 2, 10 nm off its peak:
    ``1 / (1 + (10/45)⁴) = 0.99757``.

    >>> sensor_curves([540.0], WavelengthGrid(530, 550, 10), fwhm=90.0).round(5).tolist()
    [[0.99757, 1.0, 0.99757]]
    """
    peaks = np.asarray(peaks, dtype=np.float64)
    if fwhm is None:
        return np.array([impulse(grid, peak) for peak in peaks]).reshape(peaks.size, grid.size)
    return gbell(grid.wavelengths[None, :], peaks[:, None], fwhm, slope)
