"""
Evaluation
==========

Layer 4: arrays in, numbers out, whichever road (analytic or rendered) fed them.

Gamut volumes come from :mod:`~skinrender.evaluation.gamut` (Qhull and the compiled Quickhull of
:mod:`~skinrender.evaluation.hull` behind one function); the skin locus from
:mod:`~skinrender.evaluation.locus`, and the detection budget an error of Eq. 4 may use from
:mod:`~skinrender.evaluation.budget`; detection rates from :mod:`~skinrender.evaluation.detection` and, through
an image sensor, :mod:`~skinrender.evaluation.noisy_detection`; the verdicts every statistical check gives
(pass, fail, inconclusive) from :mod:`~skinrender.evaluation.verdict`. The package exposes modules only; the
public names are re-exported by ``skinrender``.
"""
