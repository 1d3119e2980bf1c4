"""
The paper reproduced
====================

Martinkauppi et al.'s Stage 2 and Stage 3 recomputed, set beside what the paper prints, and the unknowns that
separate them (:cite:`Martinkauppi2006`).

-   :mod:`~skinrender.studies.paper.tables`: Table 1 (the render as the "real camera"), Tables 2–5 from a
    Stage 3 search, and the paper's printed Tables 2–5.
-   :mod:`~skinrender.studies.paper.normalisation`: Stage 2, the data of Figs. 3–7.
-   :mod:`~skinrender.studies.paper.observations`: the paper's Stage 1 figures and Stage 2 observations per
    camera.
-   :mod:`~skinrender.studies.paper.matching`: how many table cells we reproduce.
-   :mod:`~skinrender.studies.paper.unknowns`: one choice of the paper's unknowns (:class:`Setting`) and the
    tables under it; :mod:`~skinrender.studies.paper.sweep`: the sweep over them.
-   :mod:`~skinrender.studies.paper.volumes`: triplet volumes for many searches at once, cached.
-   :mod:`~skinrender.studies.paper.reproduce`: every table and figure in a folder
    (:mod:`~skinrender.studies.paper.folders`: complete or absent).

References
----------
-   :cite:`Martinkauppi2006` : the two-stage design, Tables 1–5, Figs. 3–7 (docs/references.md).
"""
