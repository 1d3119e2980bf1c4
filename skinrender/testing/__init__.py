"""
Testing your own scenes
=======================

A pytest plugin (registered with the ``pytest11`` entry point: any project with skinrender installed has
it, no conftest needed) and assertions for users' own cameras and scenes.

-   :mod:`skinrender.testing.plugin`: the ``render_regression`` fixture and the ``--skinrender-regen``,
    ``--skinrender-results`` options.
-   :mod:`skinrender.testing.regression`: what a check renders and how it tells a change from noise.
-   :mod:`skinrender.testing.replicates`: a face's statistics from independent replicates.
-   :mod:`skinrender.testing.reference`: the stored reference (EXR and JSON sidecar).
-   :mod:`skinrender.testing.analytic`: :func:`assert_matches_analytic`.
-   :mod:`skinrender.testing.figures`: the difference figure of a failed check.

Sits beside :mod:`skinrender.cli` at the top of the layers: it may use every layer, and nothing imports it.
"""

from __future__ import annotations

from .analytic import assert_matches_analytic

__all__ = ["assert_matches_analytic"]
