"""
Tests for :mod:`skinrender.rendering.face`: where the analytic model holds on a face, exactly.

Four analytic limits, each rendered small (48 × 48 or less, a few spp) and replicated with
independent seeds, checked by :mod:`skinrender.rendering.face.limits` (the statistics ``skinrender
validate`` runs too): every per-pixel statistic is compared with its analytic value against its own
measured noise (the jackknife over the replicates, Student's t with K − 1 degrees of freedom), the
critical value Šidák-corrected for the number of pixels and channels tested, so that a correct
renderer fails a test with probability :data:`~skinrender.rendering.face.limits.ALPHA` at most. The
controls that must fail are in ``tests/rendering/face/test_limits.py``.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.model.camera import camera
from skinrender.model.chromaticity import ncc
from skinrender.rendering.exr import read_exr
from skinrender.rendering.face import render_face, white_references, write_face_exr
from skinrender.rendering.face.document import channel_integral, light_irradiance
from skinrender.rendering.face.limit_scenes import check_furnace, check_sphere, furnace_radiance, sphere_channels
from skinrender.rendering.face.limits import REPLICATES, check_dichromatic, check_shading
from skinrender.rendering.face.scene import load_face_scene, skin_reflectance_of
from skinrender.rendering.face.effects.sheen import dichromatic_colours
from skinrender.rendering.validation import analytic_reference
from skinrender.spectra import GRID_DEFAULT

pytest.importorskip("mitsuba")

CAMERA = "gbell:9@450,540,610"
SIZE = 48
"""Image side, pixels: ~350 interior skin pixels."""
SKIN = "skin:089 skin -- caucasian (light)"


def replicates(seed0: int = 0, **kwargs) -> tuple[list, np.ndarray]:
    """``REPLICATES`` renders with consecutive seeds; their balanced images, shape ``(K, h, w, 3)``."""
    renders = [render_face(CAMERA, seed=seed0 + k, **kwargs) for k in range(REPLICATES)]
    return renders, np.array([r.image for r in renders], dtype=np.float64)


def eq4_ncc(skin: str, prevailing: float, calibration: float) -> np.ndarray:
    return ncc(analytic_reference(CAMERA, skin_reflectance_of(skin)[None], prevailing, calibration))[0]


class TestShadingCancels:
    def test_every_skin_pixel_has_the_ncc_of_eq4(self):
        """
        Direct light of one Planckian spectrum (the key and its ambient sky): a skin pixel's radiance is
        ``ρ(λ) E(λ) G`` with ``G`` the shading (cosine, distance, shadowing, the pixel's coverage, the two
        lights' shares) independent of λ, so its channels are ``G ∫ ρ E x_k`` and its NCC is Eq. 4's,
        whatever ``G`` (per pixel and pooled).
        """
        renders, images = replicates(size=SIZE, spp=16, skin=SKIN, prevailing=2856, calibration=5900)
        check = check_shading(images, renders[0].labels, eq4_ncc(SKIN, 2856, 5900))
        assert check.pixels > 100, check
        assert check.details["shading_range"] > 3, "the tested pixels' shading varies more than threefold"
        assert check.passed, check
        assert renders[0].scene.mesh_smooth and list(renders[0].info["lights"]) == ["key", "ambient"]
        skin = renders[0].labels == 1
        assert (images.mean(axis=0)[skin].max(axis=-1) > 0).all(), "the ambient sky leaves no skin pixel black"


class TestWhiteFurnace:
    def test_a_white_head_in_a_uniform_sky_returns_the_sky(self):
        """
        A head of reflectance 1 (both sides) inside a uniform environment of radiance ``L``: the
        radiance leaving every surface is ``L`` (it is the fixed point of ``L_o = ∫ ρ/π L_i cos``
        with ``ρ = 1`` and ``L_i = L`` from every direction), so with every bounce every pixel, the
        concavities included, reads ``∫ L x_k dλ``.
        """
        radiance, labels, expected = furnace_radiance(CAMERA, "face", range(REPLICATES), size=32, spp=16)
        assert (labels == 1).sum() > 100
        check = check_furnace(radiance, labels, expected)
        assert check.passed, check
        # balanced to the sky's own temperature, a white reads 255 everywhere
        sky = replace(load_face_scene("face"), props=(), key=None, fill=None,
                      environment=replace(load_face_scene("face").environment, temperature=5000.0))
        result = render_face(CAMERA, sky, skin="perfect", size=8, spp=1)
        lam, irradiance = light_irradiance(sky.environment, GRID_DEFAULT)
        white = channel_integral(camera(CAMERA), GRID_DEFAULT, lam, irradiance / np.pi)
        assert np.allclose(result.gain * white, 255.0)


class TestClosedSphere:
    def test_interreflection_in_a_closed_sphere_saturates_colour(self):
        """
        A closed Lambertian sphere of reflectance ρ(λ) emitting E(λ) uniformly, seen from inside. By
        symmetry the radiance L(λ) is the same at every point and in every direction, and leaves each
        point as emission plus reflection of the uniform incident field:
        ``L = E + (ρ/π) ∫ L cos θ dω = E + ρ L``, so ``L = E / (1 − ρ)`` (every bounce: E Σ ρⁿ),
        whereas one bounce gives ``E (1 + ρ)``. The higher terms ρⁿ are ever more coloured: the
        chromaticity moves further from the light's.
        """
        rho = skin_reflectance_of(SKIN)
        every, one = (sphere_channels(CAMERA, rho, depth) for depth in (-1, 2))
        check = check_sphere(CAMERA, rho, every, one)
        assert check.passed, check
        far, near = check.details["distance_from_light"]
        assert far > near


class TestDichromatic:
    def test_sheen_lies_in_the_plane_of_body_and_light_colour(self):
        """
        Shafer's dichromatic model: a coated (roughplastic) surface under one light reflects
        ``m_b(geometry) ρ(λ) E(λ) + m_s(geometry) F E(λ)`` with a spectrally flat Fresnel term (one
        refractive index), so each pixel's channels are a non-negative mix of the body colour
        ``∫ ρ E x_k`` and the light's colour ``∫ E x_k``: at zero distance from their plane.
        """
        renders, images = replicates(size=SIZE, spp=16, skin=SKIN, physics="sheen", prevailing=2856,
                                     calibration=2856)
        check = check_dichromatic(images, renders[0].labels, *dichromatic_colours(renders[0], renders[0].scene.key))
        assert check.passed, check
        # and the highlights are there: some pixels carry the light's colour well beyond their noise
        assert check.details["highlights"], check


class TestLabels:
    def test_skin_props_and_background_are_labelled(self, tmp_path):
        result = render_face(CAMERA, size=SIZE, spp=4)
        names = result.label_names
        assert names["background"] == 0 and names["skin"] == 1
        assert list(names.values()) == list(range(len(names)))
        counts = np.bincount(result.labels.ravel(), minlength=len(names))
        assert np.all(counts > 0), dict(zip(names, counts))
        assert result.spp == 4 and result.physics == "direct" and result.skin == result.scene.skin
        path, png = write_face_exr(tmp_path / "face.exr", result)
        back = read_exr(path, (*result.channels, "label"))
        assert np.array_equal(back[..., 3], result.labels) and png.exists()
        assert np.allclose(back[..., :3], result.image)

    def test_the_scalar_variant_labels_alike(self):
        """The scalar fallback builds the mesh and casts the label rays one by one: the same labels."""
        scalar = render_face(CAMERA, size=12, spp=1, variant="scalar_spectral")
        vectorised = render_face(CAMERA, size=12, spp=1)
        assert scalar.variant == "scalar_spectral" and np.array_equal(scalar.labels, vectorised.labels)

    def test_white_at_the_target_reads_255(self):
        scene = load_face_scene("face")
        white_p, white_c = white_references(scene, camera(CAMERA), scene.key.temperature)
        result = render_face(CAMERA, size=8, spp=1)
        assert np.allclose(result.gain * white_p, 255.0)


class TestRegression:
    """The package's own face regressions, on its pytest plugin (:mod:`skinrender.testing`): each region's mean
    and the skin's NCC within their noise of the stored render's (``tests/rendering/face/test_render/``)."""

    @pytest.mark.parametrize("physics", ["direct", "interreflection+sheen"])
    def test_the_face_renders_as_its_reference(self, render_regression, physics):
        render_regression.check("face", camera="Kodak DCS-200", prevailing="A", calibration=5900, physics=physics,
                                basename=f"face_{physics.replace('+', '_')}")


class TestRefusals:
    @pytest.mark.parametrize("kwargs, match", [
        ({"physics": "glossy"}, "physics"),
        ({"physics": "direct+sheen"}, "direct"),
        ({"skin": "skin:nobody"}, "skin"),
        ({"skin": "skin-model:melanin=-1"}, "melanin"),
        ({"skin": "skin-model:hair=1"}, "hair"),
        ({"prevailing": "nonsense.csv"}, "prevailing|nonsense"),
        ({"spp": 0}, "spp"),
        ({"seed": -1}, "seed"),
        ({"size": 0}, "size"),
        ({"sampler": "sobol"}, "sampler"),
    ])
    def test_bad_arguments_are_named(self, kwargs, match):
        with pytest.raises(SkinrenderError, match=match):
            render_face(CAMERA, **{"size": 8, "spp": 1, **kwargs})

    def test_mixed_needs_a_second_light(self):
        scene = replace(load_face_scene("face"), fill=None, environment=None)
        with pytest.raises(SkinrenderError, match="mixed"):
            render_face(CAMERA, scene, physics="mixed", size=8, spp=1)


def test_loaded_documents_are_reused_and_keyed_by_the_curves(tmp_path):
    """A face's Mitsuba document is loaded once per scene, camera curves and settings; a CSV camera rewritten under
    the same path is another camera, so its render sees the new curves (a hand-made cache keyed by the path alone
    would render the old ones)."""
    from skinrender.rendering.face.render import load_document

    wavelengths = GRID_DEFAULT.wavelengths
    curves = camera("gbell:9@450,540,610").sensitivities(GRID_DEFAULT)
    path = tmp_path / "cam.csv"
    np.savetxt(path, np.column_stack([wavelengths, curves.T]), delimiter=",", header="nm,R,G,B", comments="")
    before = load_document.cache_info()
    first = render_face(str(path), "face", 2856, 2856, spp=1, size=8, seed=1)
    again = render_face(str(path), "face", 2856, 2856, spp=1, size=8, seed=1)
    middle = load_document.cache_info()
    assert middle.hits - before.hits >= middle.misses - before.misses > 0  # the second render reused the first's
    assert np.array_equal(first.image, again.image)
    np.savetxt(path, np.column_stack([wavelengths, curves[::-1].T]), delimiter=",", header="nm,R,G,B", comments="")
    swapped = render_face(str(path), "face", 2856, 2856, spp=1, size=8, seed=1)
    assert load_document.cache_info().misses > middle.misses
    assert not np.allclose(swapped.radiance, first.radiance)


@pytest.mark.parametrize("exposure", ["x", -1, 0.0, float("nan")])
def test_a_bad_exposure_is_refused_before_any_render(exposure, monkeypatch):
    """Issue 36 (a late refusal): a face's exposure was checked by the noise level's setup, after the white
    references had rendered (~5 s)."""
    import skinrender as sr
    import skinrender.rendering.face.render as face_render

    monkeypatch.setattr(face_render, "render_face_request",
                        lambda *a, **k: pytest.fail("rendered before the exposure was checked"))
    with pytest.raises(sr.SkinrenderError, match="exposure must be .?auto.? or") as error:
        sr.render("face", "gbell:9@450,540,610", "A", "A", spp=4, size=8, physics="noise", imager="sony-imx174",
                  exposure=exposure)
    assert error.value.role == "exposure"
