"""
The paper's analytic camera model
=================================

Layer 3: one light from a spec, the camera and its sensors, Eqs. 1–11 with the one Eq. 4 gain, and Stage 1.

-   :mod:`skinrender.model.illuminant`
-   :mod:`skinrender.model.camera`
-   :mod:`skinrender.model.response`
-   :mod:`skinrender.model.stage1`

A name under ``skinrender.model`` is always a module; the public functions
and classes are imported from their modules, or from ``skinrender`` itself.
"""
