"""
Face studies
============

The face (:func:`skinrender.rendering.face.render_face`) rendered and scored for skin detection.

-   :mod:`~skinrender.studies.face.ladder`: the physics ladder, level by level against Eq. 4 and the
    detection budget.
-   :mod:`~skinrender.studies.face.effects_table`: what each effect does and costs, per skin tone (drawn by
    :mod:`~skinrender.studies.face.effect_figures` with the figures module's helpers).
-   :mod:`~skinrender.studies.face.sweep`: cameras × light pairs × skins × levels.
-   :mod:`~skinrender.studies.face.locus`: skin loci from rendered faces beside the analytic ones.
-   :mod:`~skinrender.studies.face.workers`: the renders' workers (one drjit thread each, the variant set,
    stdout kept for the JSON) on :mod:`skinrender.execution`.
"""
