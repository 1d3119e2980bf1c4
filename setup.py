"""
Build of skinrender's one compiled module; everything else is in pyproject.toml.

``skinrender.evaluation._hull3d`` is the Stage 3 search's convex-hull kernel (C, needing
only Python's headers). It is optional: without a C compiler the package still
installs, and the search uses Qhull for every hull (several times slower) and
says so once.
"""

from setuptools import Extension, setup

setup(ext_modules=[Extension("skinrender.evaluation._hull3d", sources=["skinrender/evaluation/_hull3d.c"], optional=True)])
