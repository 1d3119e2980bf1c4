"""
Assert that a render agrees with the analytic model
===================================================

:func:`assert_matches_analytic`: a chart rendered through a camera is *shown* within a tolerance of Eq. 4
(the equivalence verdict of :func:`skinrender.rendering.validation.validate`: every patch's simultaneous
confidence bound inside the tolerance), or the assertion fails. An inconclusive verdict (too few samples to
show it either way) fails too, saying how many samples per pixel would decide.

Units: temperatures K; the tolerance in the units :func:`~skinrender.rendering.validation.validate` states
(relative error of the patch means).
"""

from __future__ import annotations

__all__ = ["assert_matches_analytic"]


def assert_matches_analytic(scene, *, camera, prevailing, calibration, spp: int, seed: int = 0, tolerance: float):
    """
    Render ``scene`` through ``camera`` (prevailing and calibration Planckian lights, K, ``A`` or ``H``) at
    ``spp`` samples per pixel and assert that every patch is shown within ``tolerance`` of Eq. 4.

    Returns the validation (its ``verdict``, ``bound`` and ``spp_needed``) when it passes; raises
    :class:`AssertionError` when it fails or is inconclusive (with the spp needed); a bad argument raises
    :class:`~skinrender.errors.SkinrenderError`.

    Examples
    --------
    In a test (renders, so not run here)::

        from skinrender.testing import assert_matches_analytic

        def test_my_camera_renders_as_eq4():
            assert_matches_analytic("macbeth", camera="my_camera.csv", prevailing="A", calibration=5000,
                                    spp=1024, tolerance=0.01)
    """
    from ..rendering.validation import validate

    result = validate(scene, camera, prevailing, calibration, spp=spp, seed=seed, tolerance=tolerance)
    verdict = result.verdict
    where = f"{scene} through {camera} at {spp} spp (seed {seed})"
    if verdict.outcome == "pass":
        return result
    bound = "" if result.bound is None else f"; the bound reached is {result.bound:.3g}"
    if verdict.outcome == "inconclusive":
        needed = ("no spp can show it (some error is at or beyond the tolerance)" if result.spp_needed is None
                  else f"about {result.spp_needed} spp would decide")
        raise AssertionError(f"{where}: not shown within tolerance {tolerance:g} of Eq. 4, inconclusive: "
                             f"{verdict.reason}{bound}; {needed}")
    raise AssertionError(f"{where}: not within tolerance {tolerance:g} of Eq. 4 ({verdict.outcome}): "
                         f"{verdict.reason}{bound}")
