"""
Tests for :mod:`skinrender.rendering.face.effects.levels`: physics specs, the registry (every effect has its
parts; levels compose; unknown and duplicate effects refused as before), and a toy effect registered for a test
only, rendered with and seen by ``ladder --json``. The tests of the registry read it rather than name its levels;
an effect's own tests (its module's) name it.
"""

from __future__ import annotations

import itertools
import re
from dataclasses import replace

import numpy as np
import pytest

from skinrender.errors import SkinrenderError
from skinrender.rendering.face.effects import (EFFECTS, EFFECTS_DEFAULT, LEVELS_EACH, LEVELS_LADDER, PHYSICS,
                                               PHYSICS_BASE, PHYSICS_EFFECTS, Effect, Limits, active_lights,
                                               levels_each, levels_ladder, parse_physics, physics_level)
from skinrender.rendering.face.effects.base import Frame
from skinrender.rendering.face.effects.direct import DIRECT
from skinrender.rendering.face.effects.noise import NOISE
from skinrender.rendering.face.effects.sheen import SHEEN
from skinrender.rendering.face.labels import LABEL_SKIN
from skinrender.rendering.face.scene import Light, load_face_scene
from skinrender.rendering.renderer import mitsuba_spectrum
from skinrender.spectra import GRID_DEFAULT
from skinrender.studies.benchmarks.bench_face import LEVELS_BENCH
from skinrender.studies.face.ladder import LEVELS_DEFAULT

CAM = "gbell:9@450,540,610"


class TestParsePhysics:
    def test_levels_and_combinations(self):
        assert parse_physics(PHYSICS_BASE) == ()
        last, before = EFFECTS[-1], EFFECTS[-2]
        assert parse_physics(f" {last} + {before} ") == (before, last)
        assert parse_physics("+".join(reversed(EFFECTS_DEFAULT))) == EFFECTS_DEFAULT
        assert set(EFFECTS) | {PHYSICS_BASE} == set(PHYSICS)

    @pytest.mark.parametrize("spec", ["", "glossy", f"{PHYSICS_BASE}+{EFFECTS[-1]}", f"{EFFECTS[0]}+", "bssrdf"])
    def test_refused(self, spec):
        with pytest.raises(SkinrenderError, match="physics"):
            parse_physics(spec)


class TestActiveLights:
    def test_levels_choose_lights(self):
        scene = load_face_scene("face")
        assert list(active_lights(scene, ())) == ["key", "ambient"]
        assert list(active_lights(replace(scene, ambient=0.0), ())) == ["key"]
        assert list(active_lights(scene, ("mixed",))) == ["key", "fill", "environment"]
        sky = replace(scene, key=None, fill=None)
        assert list(active_lights(sky, ())) == ["environment"]
        with pytest.raises(SkinrenderError, match="mixed"):
            active_lights(replace(scene, fill=None, environment=None), ("mixed",))


def test_an_effect_named_twice_is_refused():
    with pytest.raises(SkinrenderError, match="named twice"):
        parse_physics(f"{EFFECTS[1]}+{EFFECTS[0]}+{EFFECTS[1]}")


class TestRegistry:
    def test_every_effect_has_its_parts(self):
        """A name (its key), a one-line description, each part a function or None, and limits that say why."""
        parts = ("integrator", "skin", "prop", "lights", "post")
        assert next(iter(PHYSICS_EFFECTS)) == PHYSICS_BASE == "direct"
        for name, effect in PHYSICS_EFFECTS.items():
            assert isinstance(effect, Effect) and effect.name == name and re.fullmatch(r"[a-z]+(-[a-z]+)*", name)
            assert effect.description.strip() and "\n" not in effect.description and PHYSICS[name] == effect.description
            assert all(getattr(effect, part) is None or callable(getattr(effect, part)) for part in parts)
            assert isinstance(effect.limits, Limits)
            for hook in (effect.limits.check, effect.limits.measure):
                assert hook is None or callable(hook)
            if effect.limits.check is not None or not effect.limits.holds:
                assert effect.limits.why, f"{name}: a check or a broken limit says why"
            changes = [part for part in parts if getattr(effect, part) is not None] + (
                ["measure"] if effect.limits.measure else [])
            assert changes, f"{name} changes nothing"
        base = PHYSICS_EFFECTS[PHYSICS_BASE]
        assert all(getattr(base, part) is not None for part in ("integrator", "skin", "prop", "lights"))
        assert base.limits.check is not None and base.limits.holds

    def test_level_lists_are_read_from_the_registry(self):
        """Every effect is registered; the default levels leave out those a user names (by_default: the
        volumetric reference, subsurface-volume), and the face bench those slower per sample than the base."""
        assert EFFECTS == tuple(PHYSICS_EFFECTS)[1:] and len(EFFECTS) >= 2
        assert EFFECTS_DEFAULT == tuple(name for name in EFFECTS if PHYSICS_EFFECTS[name].by_default)
        assert "subsurface" in EFFECTS_DEFAULT and "subsurface-volume" in set(EFFECTS) - set(EFFECTS_DEFAULT)
        assert LEVELS_EACH == (PHYSICS_BASE, *EFFECTS_DEFAULT) == levels_each()
        assert LEVELS_LADDER == (*LEVELS_EACH, "+".join(EFFECTS_DEFAULT)) == levels_ladder()
        base_rate = PHYSICS_EFFECTS[PHYSICS_BASE].samples_per_s
        assert LEVELS_DEFAULT is LEVELS_LADDER and LEVELS_BENCH == tuple(
            level for level in LEVELS_EACH if physics_level(level).samples_per_s >= base_rate)
        assert list(PHYSICS) == list(PHYSICS_EFFECTS) and dict(PHYSICS)["noise"] == NOISE.description
        orders = [effect.order for effect in PHYSICS_EFFECTS.values()]
        assert orders == sorted(orders) and len(set(orders)) == len(orders)  # the modules' order, each its own

    def test_every_module_of_the_package_with_an_effect_is_registered(self):
        """A new effect is one module: the registry takes the ``EFFECT`` of every module of the package."""
        import importlib
        import pkgutil

        import skinrender.rendering.face.effects as package

        found = {}
        for info in pkgutil.iter_modules(package.__path__):
            effect = getattr(importlib.import_module(f"{package.__name__}.{info.name}"), "EFFECT", None)
            if effect is not None:
                found[effect.name] = effect
        assert found == PHYSICS_EFFECTS


ALL = ", ".join(PHYSICS_EFFECTS)
"""Every registered effect, as a refusal lists them."""


class TestRefusals:
    """Unknown and duplicate effects are refused with the messages they had before the registry."""

    @pytest.mark.parametrize("spec, message", [
        ("glossy", f"physics ('glossy') must be one of {ALL}, got 'glossy'"),
        ("", f"physics ('') must be one of {ALL}, got ''"),
        (f"{EFFECTS[1]}+", f"physics ('{EFFECTS[1]}+') must be one of {ALL}, got ''"),
        (f"{PHYSICS_BASE}+{EFFECTS[-1]}",
         f"physics: '{PHYSICS_BASE}' is the base and combines with nothing, got '{PHYSICS_BASE}+{EFFECTS[-1]}'"),
        (f"{EFFECTS[1]}+{EFFECTS[0]}+{EFFECTS[1]}",
         f"physics: {EFFECTS[1]} named twice in '{EFFECTS[1]}+{EFFECTS[0]}+{EFFECTS[1]}'; name each effect once"),
        ("subsurface-volume+subsurface", "physics: 'subsurface-volume' and 'subsurface' are two transports of the same "
                                         "skin and do not combine, got 'subsurface-volume+subsurface'; name one"),
    ])
    def test_messages(self, spec, message):
        for parse in (parse_physics, physics_level):
            with pytest.raises(SkinrenderError) as error:
                parse(spec)
            assert str(error.value) == message


def _old_integrator(effects: tuple[str, ...], lights: dict, scene) -> dict:
    points = all(light.position is not None for light in lights.values())
    hidden = {"hide_emitters": True} if scene.key is not None and not points else {}  # the sky hidden, added since
    if "interreflection" in effects:
        return {"type": "path", "max_depth": -1, "rr_depth": 5, **hidden}
    return {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0 if points else 1, **hidden}


def _old_bsdf(reflectance, sheen: bool) -> dict:
    spectrum = mitsuba_spectrum(GRID_DEFAULT.wavelengths, reflectance)
    if not sheen:
        inner = {"type": "diffuse", "reflectance": spectrum}
    else:
        inner = {"type": "roughplastic", "distribution": "ggx", "alpha": 0.35, "int_ior": 1.4, "ext_ior": 1.0,
                 "nonlinear": True, "diffuse_reflectance": spectrum}  # the coat's internal scattering, on since
    return {"type": "twosided", "bsdf": inner}


def _old_lights(scene, effects: tuple[str, ...]) -> dict:
    if "mixed" in effects:
        return {name: getattr(scene, name) for name in ("key", "fill", "environment") if getattr(scene, name)}
    if scene.key is None:
        return {"environment": scene.environment}
    ambient = Light(scene.key.temperature, scene.key.illuminance * scene.ambient)  # the base's sky, added since
    return {"key": scene.key, "ambient": ambient} if scene.ambient > 0 else {"key": scene.key}


EFFECTS_BEFORE = ("interreflection", "sheen", "mixed", "noise")
"""The effects registered when the registry replaced the branches (``subsurface`` and ``subsurface-volume`` came
later: their own tests)."""

LEVELS_ALL = ["+".join(c) for n in range(len(EFFECTS_BEFORE) + 1) for c in itertools.combinations(EFFECTS_BEFORE, n)]
"""Every level of those: direct (the empty combination) and each of the 15 combinations of the four effects."""


@pytest.mark.parametrize("spec", LEVELS_ALL)
def test_each_level_composes_what_its_branches_built_before_the_registry(spec):
    """
    The parts of every level equal what the ``if "sheen" in effects`` branches of face_dict and face_validation
    built before the registry (written out above, with the defaults changed since on purpose: the base's
    ambient sky of the key's spectrum, hidden from the camera, and the coat's internal scattering): the integrator, the skin's and props'
    BSDFs, the lights, the effects that change the document, the check run and eq4_shift's reason. (A render
    from the same document and seed is the same image: measured bit-for-bit on every level before and after the
    registry, docs/effects.md.)
    """
    level = physics_level(spec or "direct")
    effects = level.names
    assert effects == parse_physics(spec or "direct") and level.name == ("+".join(effects) or "direct")
    scene = load_face_scene("face")
    for variant in (scene, replace(scene, key=None, fill=None)):  # point lights; and the sky alone
        if "mixed" in effects and variant.key is None:
            continue
        lights = level.lights(variant)
        assert lights == _old_lights(variant, effects)
        setup = level.setup(variant, None, GRID_DEFAULT, lights)
        assert level.integrator(setup) == _old_integrator(effects, lights, variant)
    rho = np.linspace(0.2, 0.6, GRID_DEFAULT.size)
    assert level.skin(rho, setup) == {"bsdf": _old_bsdf(rho, "sheen" in effects)}
    assert level.prop(rho, setup) == {"bsdf": _old_bsdf(rho, False)}
    assert level.document_key == tuple(e for e in effects if e != "noise")
    one_light = not {"interreflection", "mixed"} & set(effects)
    expected_check = None if not one_light else (SHEEN if "sheen" in effects else DIRECT).limits.check
    assert level.check is expected_check
    why = ("interreflection" if "interreflection" in effects else "mixed" if "mixed" in effects
           else "sheen" if "sheen" in effects else "direct")
    assert level.why == PHYSICS_EFFECTS[why].limits.why
    measures = [effect.name for effect in level.effects if effect.limits.measure is not None]
    assert measures == (["noise"] if "noise" in effects else [])  # through the sensor: its terms
    if not measures:
        images = np.ones((3, 2, 2, 3))
        assert level.measure(images, None).images is images


def _sky(lights: dict, scene) -> dict:
    """A uniform sky at the key light's temperature, a fifth of its illuminance (the docs' worked example)."""
    key = lights.get("key") or scene.key
    return {**lights, "sky": Light(key.temperature, key.illuminance / 5)}


SKY = Effect("sky", "a uniform sky at the key light's temperature, a fifth of its illuminance: no pure-black "
             "shadow, and one Planckian still lights the face", lights=_sky)


def test_a_toy_effect_registered_for_a_test_only_renders_and_validates(monkeypatch):
    """
    Adding an effect is its module and its line in the registry: here a toy registered for this test only
    (monkeypatch puts the registry back), on a scene without the base's own ambient sky. It composes with the
    others, renders, and keeps the base's analytic limit: its light has the key's spectrum, so the shading
    still cancels in NCC.
    """
    pytest.importorskip("mitsuba")
    from skinrender.rendering.face import render_face, validate_face

    monkeypatch.setitem(PHYSICS_EFFECTS, "sky", SKY)
    dark = replace(load_face_scene("face"), ambient=0.0)
    assert parse_physics("sky+sheen") == ("sheen", "sky") and "sky" in PHYSICS
    assert list(physics_level("mixed+sky").lights(dark)) == ["key", "fill", "environment", "sky"]
    kwargs = {"size": 24, "spp": 8, "seed": 1, "prevailing": 2856, "calibration": 2856}
    direct, lit = render_face(CAM, dark, physics="direct", **kwargs), render_face(CAM, dark, physics="sky", **kwargs)
    assert lit.physics == "sky" and list(lit.info["lights"]) == ["key", "sky"]
    skin = lit.labels == LABEL_SKIN
    assert (direct.image[skin].max(axis=-1) == 0).any(), "the key light alone leaves some skin pixel black"
    assert (lit.image[skin].min(axis=-1) > 0).all(), "the sky reaches every skin pixel"
    result = validate_face(CAM, dark, physics="sky", size=32, spp=48, limits=(), prevailing=2856, calibration=2856)
    assert [c.name for c in result.checks] == ["shading_cancels", "detection", "eq4_shift"]
    assert result.checks[0].passed is True, result.checks[0]
    assert "sky" not in PHYSICS_EFFECTS or PHYSICS_EFFECTS["sky"] is SKY


def _dim(frame: Frame, setup) -> Frame:
    """The frame and its whites at half their signal: Eq. 4's gain (their ratio) cancels it."""
    return Frame(frame.signal / 2, frame.white_prevailing / 2, frame.white_calibration / 2, frame.info)


DIM = Effect("dim", "the frame and its whites at half their signal (a toy: Eq. 4's gain cancels it)", post=_dim)


def test_a_toy_effect_registered_from_a_test_alone_appears_in_the_ladder(monkeypatch, capsys):
    """
    Issue 35: a new level is one module and its test, nothing edited elsewhere. The toy, registered here alone
    (monkeypatch puts the registry back), is a level of ``ladder --json``: parsed by ``--levels``, rendered,
    scored and judged against the budget as any other, and in the ladder's default levels as registered now. It
    halves the frame and its whites, which Eq. 4's gain cancels: its rows are direct's (the same seeds). (16 px, 12 spp over the replicates: a small ladder whose skin is scored.)
    """
    pytest.importorskip("mitsuba")
    import json

    from skinrender.cli import main

    monkeypatch.setitem(PHYSICS_EFFECTS, "dim", DIM)
    assert "dim" in levels_each() and levels_ladder()[-1].endswith("+dim")
    try:
        status = main(["ladder", "--camera", CAM, "--prevailing", "2856", "--calibration", "2856", "--levels",
                       "direct,dim", "--size", "16", "--spp", "12", "--json"])
    except SystemExit as verdict:  # a command with a verdict exits with its status
        status = verdict.code
    out, err = capsys.readouterr()
    assert status in (0, 1, 3), err[-500:]
    rows = json.loads(out)["levels"]
    assert [row["name"] for row in rows] == ["direct", "dim"], rows
    assert rows[1]["skin_ncc_mean"] == pytest.approx(rows[0]["skin_ncc_mean"], abs=1e-5)  # Eq. 4 cancels the dimming
    for key in ("tpr", "fpr", "eq4_shift", "within_budget"):
        assert rows[1][key] == pytest.approx(rows[0][key], abs=1e-6), key
