"""
Evaluation
==========

Layer 4: gamut volumes (Qhull and the compiled Quickhull behind one function), the skin locus and detection rates; arrays in, numbers out, whichever road (analytic or rendered) fed them.

-   :mod:`skinrender.evaluation.gamut`
-   :mod:`skinrender.evaluation.hull`
-   :mod:`skinrender.evaluation.locus`
-   :mod:`skinrender.evaluation.detection`

A name under ``skinrender.evaluation`` is always a module; the public functions
and classes are imported from their modules, or from ``skinrender`` itself.
"""
