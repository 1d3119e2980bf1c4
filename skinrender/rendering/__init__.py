"""
Spectral rendering with Mitsuba 3
=================================

Layer 5 (beside design, independent of it): scene files, Mitsuba variants, the renderer, the white balance of renders, EXR/PNG files and the validation against the analytic model. Rendering itself needs the ``[render]`` extra (mitsuba, drjit, OpenEXR); importing this package does not.

-   :mod:`skinrender.rendering.scene`
-   :mod:`skinrender.rendering.variants`
-   :mod:`skinrender.rendering.renderer`
-   :mod:`skinrender.rendering.balance`
-   :mod:`skinrender.rendering.exr`
-   :mod:`skinrender.rendering.validation`
-   :mod:`skinrender.rendering.face` (the face: scenes, effects of physics,
    render, labels, limits, validation)
-   :mod:`skinrender.rendering.loaded` (the scenes kept loaded between renders;
    ``release_scenes`` for long-lived processes)
-   :mod:`skinrender.rendering.outputs` (a result's ``.save()`` and
    ``.figure()``), :mod:`skinrender.rendering.dispatch` (one ``render`` for
    charts and faces)

A name under ``skinrender.rendering`` is always a module; the public functions
and classes are imported from their modules, or from ``skinrender`` itself.
"""
