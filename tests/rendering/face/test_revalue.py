"""
Tests for :mod:`skinrender.rendering.face.revalue`: the dictionaries' values are found in every level's loaded
document, and a kept document given another light and skin renders what a fresh one does.
"""

from __future__ import annotations

import numpy as np
import pytest

from skinrender.rendering.bands import WavelengthGrid
from skinrender.rendering.validation import FLOAT32_FLOOR
from skinrender.rendering.face import revalue
from skinrender.rendering.face.effects import LEVELS_EACH
from skinrender.rendering.face.request import face_request
from skinrender.rendering.face.spectral_face import FacePlan, render_face_spectral

pytest.importorskip("mitsuba")

BANDS = WavelengthGrid(400, 700, 50)
"""Seven bands: a small kernel; the film is the structure's, whatever its bands."""


@pytest.mark.parametrize("level", [level for level in LEVELS_EACH if level != "subsurface"] + ["sheen+mixed"])
def test_every_value_parameter_is_found_in_the_dictionaries(level):
    """Each level's loaded document (JIT variant) against :func:`revalue.flattened`: the same names, the same
    values to float32 rounding; a level that did not match would be loaded anew for every render (slower, not
    wrong). ``subsurface-volume`` renders in ``scalar_spectral``, which compiles nothing and is never revalued;
    ``subsurface`` is the next test's."""
    plan = FacePlan.of(face_request("face", None, 2856, skin="skin-model:melanin=0.02", physics=level, spp=1, size=4,
                                    variant="llvm_ad_spectral", bands=BANDS))
    assert revalue._matches(revalue._fresh(plan, BANDS), plan)


def test_the_fast_subsurface_is_loaded_anew_for_every_skin():
    """The fast ``subsurface``'s skin is a table outside the document's dictionary (the plugin names it by a key
    and exposes no parameter): its documents must not match their flattening, or a kept one would render the
    skin it was loaded with. It is loaded anew (slower, not wrong); a second skin renders as its own fresh render."""
    plan = FacePlan.of(face_request("face", None, 2856, skin="skin-model:melanin=0.02", physics="subsurface", spp=1,
                                    size=4, variant="llvm_ad_spectral", bands=BANDS))
    assert not revalue._matches(revalue._fresh(plan, BANDS), plan)
    revalue.release()
    render_face_spectral("face", 2856, "skin-model:melanin=0.02", "subsurface", 4, 1, 8, bands=BANDS)
    kept = render_face_spectral("face", 2856, "skin-model:melanin=0.3", "subsurface", 4, 1, 8, bands=BANDS)
    revalue.release()
    fresh = render_face_spectral("face", 2856, "skin-model:melanin=0.3", "subsurface", 4, 1, 8, bands=BANDS)
    floor = FLOAT32_FLOOR * float(np.max(fresh.image))
    assert np.allclose(kept.image, fresh.image, rtol=FLOAT32_FLOOR, atol=floor)


def test_a_kept_document_renders_what_a_fresh_one_does():
    """Render at one light and skin, then at another through the kept document; then, everything released, the
    second anew: the two images are equal to the renderer's float32 floor (the values copied are the document's
    whole state; a wrong or missing one moves pixels by percent: another skin, another light). In one process
    they came out bit for bit equal; after other documents were loaded the fresh one's kernel, compiled anew,
    rounded a pixel 1 ulp apart (1.2e-7 of 5.9)."""
    revalue.release()
    render_face_spectral("face", 2856, "skin-model:melanin=0.02", "sheen", 4, 1, 8, bands=BANDS)
    kept = render_face_spectral("face", 2300, "skin-model:melanin=0.3", "sheen", 4, 1, 8, bands=BANDS)
    assert len(revalue._KEPT) == 1
    revalue.release()
    fresh = render_face_spectral("face", 2300, "skin-model:melanin=0.3", "sheen", 4, 1, 8, bands=BANDS)
    floor = FLOAT32_FLOOR * float(np.max(fresh.image))  # a kernel compiled anew may round a pixel an ulp apart
    assert np.allclose(kept.image, fresh.image, rtol=FLOAT32_FLOOR, atol=floor) and kept.scale == fresh.scale
    assert np.array_equal(kept.labels, fresh.labels)
