"""
Camera design
=============

Layer 5: the sensor bank, the per-triplet criteria, the Stage 3 search (on every core or Dask) and continuous optimisation. Never imports rendering.

-   :mod:`skinrender.design.bank`
-   :mod:`skinrender.design.criteria`
-   :mod:`skinrender.design.search`
-   :mod:`skinrender.design.optimise`

A name under ``skinrender.design`` is always a module; the public functions
and classes are imported from their modules, or from ``skinrender`` itself.
"""
