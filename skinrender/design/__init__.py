"""
Camera design
=============

Layer 5: the sensor bank, the per-triplet criteria, the Stage 3 search (on every core or Dask) and continuous
optimisation. Never imports rendering.

:mod:`~skinrender.design.bank` holds single-sensor responses per position and forms triplets from them;
:mod:`~skinrender.design.criteria` turns a triplet into gamut volumes, their ratio and detection rates;
:mod:`~skinrender.design.noise_aware` adds the image sensor's noise to those criteria;
:mod:`~skinrender.design.search` runs Stage 3 over every triplet; :mod:`~skinrender.design.optimise` moves a
gbell camera's peaks off the grid. Each name under ``skinrender.design`` is a module: import the functions
from their modules, or from ``skinrender``.
"""
