"""
Studies
=======

Layer 6: the paper's tables and figures, the reproduction and the benchmarks. :mod:`~skinrender.studies.figures` is the only module that imports matplotlib.

-   :mod:`skinrender.studies.tables`
-   :mod:`skinrender.studies.figures`
-   :mod:`skinrender.studies.labelled` (the figures of renders, registered
    for ``Rendering.figure()`` and ``FaceRendering.figure()``)
-   :mod:`skinrender.studies.reproduce`
-   :mod:`skinrender.studies.bench`
-   the face: :mod:`skinrender.studies.ladder`, :mod:`skinrender.studies.effects_table` (drawn by
    :mod:`skinrender.studies.effect_figures` through the figures module's helpers),
    :mod:`skinrender.studies.face_calibration`

A name under ``skinrender.studies`` is always a module; the public functions
and classes are imported from their modules, or from ``skinrender`` itself.
"""
