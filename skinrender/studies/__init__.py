"""
Studies
=======

Layer 6: what the toolkit computes from the layers below, by concept. Each subpackage is one concept;
:mod:`~skinrender.studies.figures` draws for all of them (the only module that imports matplotlib).

-   :mod:`skinrender.studies.paper`: the paper reproduced — Table 1 and Tables 2–5
    (:mod:`~skinrender.studies.paper.tables`), Stage 2's normalisations, the paper's observations and
    unknowns, the sweep over them, the volumes shared between searches, ``reproduce``'s folder.
-   :mod:`skinrender.studies.benchmarks`: the toolkit measured — speed (``bench``), the face render's error
    against spp, the calibration of the verdicts (charts and faces), photon transfer (EMVA 1288).
-   :mod:`skinrender.studies.face`: the face studies — the physics ladder, the effects table and its figure,
    sweeps over cameras × lights × skins × levels, skin loci from rendered faces, the renders' workers.
-   :mod:`skinrender.studies.figures` (every figure) and :mod:`skinrender.studies.labelled` (the figures of
    renders, registered for ``Rendering.figure()`` and ``FaceRendering.figure()``).

A name under ``skinrender.studies`` is always a module; the public functions and classes are imported from
their modules, or from ``skinrender`` itself.

The modules were one flat package before; their old names (:data:`MOVED`, ``skinrender.studies.ladder``,
``from skinrender.studies.tables import table1``) still import the module from its new place, with a
:class:`DeprecationWarning`.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import warnings

MOVED = {
    **{name: f"paper.{name}" for name in ("reproduce", "tables", "normalisation", "observations", "matching",
                                          "unknowns", "sweep", "volumes", "folders")},
    **{name: f"benchmarks.{name}" for name in ("bench", "bench_face", "calibration", "face_calibration", "ptc")},
    **{name: f"face.{name}" for name in ("ladder", "effects_table", "effect_figures")},
    "face_sweep": "face.sweep", "face_locus": "face.locus", "face_pool": "face.workers",
}
"""An earlier module name under ``skinrender.studies`` → where the module is now (relative to it)."""


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports ``skinrender.studies.<old name>`` as the module now at :data:`MOVED`'s place (the same object)."""

    def __init__(self) -> None:
        self.specs: dict = {}

    def find_spec(self, fullname, path, target=None):
        package, _, name = fullname.rpartition(".")
        if package == __name__ and name in MOVED:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        name = spec.name.rpartition(".")[2]
        warnings.warn(f"{spec.name} is now {__name__}.{MOVED[name]}", DeprecationWarning, stacklevel=2)
        module = importlib.import_module(f"{__name__}.{MOVED[name]}")
        self.specs[module.__name__] = module.__spec__
        return module

    def exec_module(self, module):
        # the import system gave the module the old name's spec: give it its own back
        module.__spec__ = self.specs[module.__name__]


if not any(isinstance(finder, _MovedModules) for finder in sys.meta_path):
    sys.meta_path.append(_MovedModules())
