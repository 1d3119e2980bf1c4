"""
Constants
=========

Physical constants, the paper's camera constants and the test tolerances,
each with its unit and reference.

References
----------
-   :cite:`CODATA2018` : Tiesinga, E., Mohr, P. J., Newell, D. B., & Taylor,
    B. N. (2021). CODATA recommended values of the fundamental physical
    constants: 2018. Reviews of Modern Physics, 93(2), 025010.
-   :cite:`Martinkauppi2006` : the paper implemented here,
    ``../shared/paper/skin-camera-paper.txt`` ("Designing a Simple 3-Channel
    Camera for Skin Detection").
"""

from __future__ import annotations

__all__ = [
    "CONSTANT_C",
    "CONSTANT_H",
    "CONSTANT_K_B",
    "CONSTANT_OUTPUT_SCALE",
    "CONSTANT_KNEE_FACTOR",
    "CONSTANT_KNEE_POINT",
    "CONSTANT_KNEE_END",
    "CONSTANT_KNEE_CEILING",
    "SENSOR_RULE",
    "TEMPERATURES_PAPER",
    "TEMPERATURE_A",
    "TEMPERATURE_HORIZON",
    "TEMPERATURE_MAX",
    "TOLERANCE_ABSOLUTE_TESTS",
    "TOLERANCE_RELATIVE_TESTS",
]

CONSTANT_C: float = 299_792_458.0
"""Speed of light in vacuum, m·s⁻¹ (exact, SI 2019)."""

CONSTANT_H: float = 6.626_070_15e-34
"""Planck constant, J·s (exact, SI 2019)."""

CONSTANT_K_B: float = 1.380_649e-23
"""Boltzmann constant, J·K⁻¹ (exact, SI 2019)."""

CONSTANT_OUTPUT_SCALE: float = 255.0
"""The paper's output scale *v* of Eq. 4 (8-bit output range 0–255)."""

SENSOR_RULE: str = "1 (impulse) or else a gbell number N > 0 (FWHM N·10 nm; the paper's 3, 5, …, 15)"
"""What the paper's sensor number may be (:cite:`Martinkauppi2006`), in the words every command's help and refusal
use (``search --sensor``, ``reproduce --sensors``)."""

CONSTANT_KNEE_FACTOR: float = 0.0127
"""Knee factor *a* of Eq. 11, read by the paper from the Sony manual."""

CONSTANT_KNEE_POINT: float = 244.0
"""Knee point of Eq. 11, output units: the response is linear below it."""

CONSTANT_KNEE_END: float = 1109.0
"""End of the knee slope of Eq. 11, output units. The paper prints the last
branch as ``X > 255``; it must be ``X > 1109`` since
``244 (1 - a) + a · 1109 ≈ 255`` (NOTES.md erratum)."""

CONSTANT_KNEE_CEILING: float = 255.0
"""Output of Eq. 11 above :data:`CONSTANT_KNEE_END`, output units."""

TEMPERATURES_PAPER: tuple[float, ...] = (
    2000.0,
    2200.0,
    2500.0,
    2800.0,
    3300.0,
    3900.0,
    4800.0,
    5900.0,
    7500.0,
    10000.0,
)
"""The paper's ten Stage 1 illuminants, colour temperatures in K."""

TEMPERATURE_A: float = 2856.0
"""CIE illuminant A modelled as a Planckian radiator, K."""

TEMPERATURE_HORIZON: float = 2300.0
"""The paper's Horizon (H) light, a Planckian radiator, K."""

TEMPERATURE_MAX: float = 1e12
"""Highest temperature accepted, K. Planck radiance grows as ``2ckT/λ⁴`` far
above the visible Wien peak and overflows float64 near 1e300 K; 1e12 K keeps
it below ~1e15 W·m⁻²·sr⁻¹·nm⁻¹ with all digits, far beyond any light source."""

TOLERANCE_ABSOLUTE_TESTS: float = 1e-7
"""Absolute tolerance for deterministic (analytic) tests: float64 sums of a
few hundred terms of order one keep about 1e-13 relative error, so 1e-7
absolute leaves ample room while still catching any formula change."""

TOLERANCE_RELATIVE_TESTS: float = 1e-9
"""Relative tolerance for comparing two float64 routes to the same quantity."""
