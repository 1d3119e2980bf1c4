"""
The paper's analytic camera model
=================================

Layer 3. A light from a spec (:mod:`~skinrender.model.illuminant`); the camera and its sensors
(:mod:`~skinrender.model.camera`); Eqs. 1–11 with the one Eq. 4 gain (:mod:`~skinrender.model.response`) and
the normalised colour coordinates (:mod:`~skinrender.model.chromaticity`); Stage 1's illuminant selection
(:mod:`~skinrender.model.stage1`); and the image sensor — presets (:mod:`~skinrender.model.imager`), photons to
electrons and exposure (:mod:`~skinrender.model.exposure`), noise to digital numbers
(:mod:`~skinrender.model.noise`). Modules only here; functions come from them or from ``skinrender``.
"""
