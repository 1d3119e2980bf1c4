"""
Benchmarks
==========

The toolkit measured, never asserted in unit tests: how fast it computes, how its renders' error falls with
the samples per pixel, how often its verdicts fail where their null holds, and what its simulated camera
gives when measured as a real one is.

-   :mod:`~skinrender.studies.benchmarks.bench`: speed (``skinrender bench search|analytic|sweep|render``).
-   :mod:`~skinrender.studies.benchmarks.bench_face`: the face render's error against spp per level of
    physics, and the presets it gives (``bench render --scene face``).
-   :mod:`~skinrender.studies.benchmarks.calibration`: the chart verdicts' calibration and what a
    validation costs (``bench calibration``, ``bench validate``);
    :mod:`~skinrender.studies.benchmarks.face_calibration`: the face's.
-   :mod:`~skinrender.studies.benchmarks.ptc`: photon transfer (EMVA 1288) of the simulated camera.
"""
