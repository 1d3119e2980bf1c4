"""
Tests for :mod:`skinrender.design.noise_aware`: the noise-aware detection criterion rejects crowded triplets that
the noise-free criterion prefers, tends to the noise-free value as the light grows, and feeds the search and
the design.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from skinrender.cli import main
from skinrender.datasets import reflectances
from skinrender.design.bank import positions_grid, sensor_bank
from skinrender.design.criteria import triplet_false_positive_rates
from skinrender.design.noise_aware import (
    TPR_MIN,
    bank_rates,
    calibration_index,
    noisy_setting,
    triplet_noisy_rates,
)
from skinrender.errors import SkinrenderError
from skinrender.model.imager import Imager
from skinrender.spectra import GRID_DEFAULT

POSITIONS = positions_grid("400:700:10")
CROWDED, SPREAD = [16, 17, 19], [5, 14, 21]  # 560 570 590 nm (the noise-free best) and 450 540 610 nm


@pytest.fixture(scope="module")
def banks():
    return [sensor_bank(9, reflectances(name).on(GRID_DEFAULT), POSITIONS) for name in ("skin", "munsell")]


def rates_of(banks, setting, triplet):
    rates = [bank_rates(bank, setting, 9) for bank in banks]
    return triplet_noisy_rates(*banks, *rates, triplet, setting)


def test_crowded_sensors_lose_the_skin_in_noise(banks):
    """Noise-free, 560/570/590 nm is the best detector; in an office (500 lx) its skin pixels scatter out of the
    locus, while 450/540/610 nm keeps them."""
    setting = noisy_setting("sony-imx174", 500.0)
    assert triplet_false_positive_rates(*banks, CROWDED)[4] < triplet_false_positive_rates(*banks, SPREAD)[4]
    crowded, spread = rates_of(banks, setting, CROWDED), rates_of(banks, setting, SPREAD)
    assert crowded[0] < TPR_MIN <= spread[0]


def test_tends_to_the_noise_free_value_as_light_grows(banks):
    """A sensor that never saturates (a deep well, a fine ADC) at a fixed exposure: more light, less noise."""
    deep = Imager(pixel_um=5.0, f_number=2.8, transmittance=0.9, qe_peak=0.6, full_well_e=1e15, read_noise_e=5.0,
                  dark_current_e_per_s=10.0, gain_dn_per_e=1e-5, bits=32, black_level_dn=0.0)
    free = triplet_false_positive_rates(*banks, SPREAD)[4]  # calibration 3300 K, the setting's default
    gaps = [abs(rates_of(banks, noisy_setting(deep, lux, 0.01, samples=2), SPREAD)[1] - free)
            for lux in (1.0, 1e3, 1e7)]
    assert gaps[2] < gaps[0] and gaps[2] < 2e-3


@pytest.mark.parametrize("calibration", [3000.0, 3299.0, 12345.0])
def test_a_calibration_off_the_illuminants_is_refused_not_rounded(banks, calibration):
    with pytest.raises(SkinrenderError, match="one of the illuminants"):
        calibration_index(banks[0].temperatures, calibration)
    setting = noisy_setting("sony-imx174", 500.0, calibration=calibration)
    rates = [bank_rates(bank, setting, 9) for bank in banks]
    with pytest.raises(SkinrenderError, match="one of the illuminants"):
        triplet_noisy_rates(*banks, *rates, [0, 1, 2], setting)


def test_same_seed_same_value(banks):
    setting = noisy_setting("sony-icx418", 500.0, seed=7)
    assert rates_of(banks, setting, SPREAD) == rates_of(banks, setting, SPREAD)


@pytest.mark.parametrize("argv, names", [
    (["--imager", "sony-imx174", "--illuminance", "0"], "illuminance"),
    (["--imager", "sony-imx174", "--noise-samples", "0"], "samples"),
    (["--imager", "nosuch"], "--imager"),
])
def test_search_refuses_bad_noise_settings(argv, names, capsys):
    status = main(["search", "--sensor", "9", "--positions", "400:700:50", "--quiet", "--workers", "1", *argv])
    err = capsys.readouterr().err
    assert status == 2 and names in err and len(err.strip().splitlines()) == 1


def test_search_ranks_by_the_noisy_criterion(capsys):
    status = main(["search", "--sensor", "9", "--positions", "400:700:50", "--quiet", "--workers", "1",
                   "--imager", "sony-imx174", "--illuminance", "50", "--json"])
    document = json.loads(capsys.readouterr().out)
    assert status == 0 and document["noisy"]["imager"] == "sony-imx174"
    assert document["min_noisy_fpr"] and all(row["tpr"] >= TPR_MIN for row in document["min_noisy_fpr"])


def test_design_with_an_imager_returns_a_defined_camera(capsys):
    status = main(["design", "--evaluations", "6", "--starts", "450,540,610", "--imager", "sony-imx174",
                   "--illuminance", "50", "--json"])
    document = json.loads(capsys.readouterr().out)
    assert status == 0 and document["value"] is not None and document["noisy"]["illuminance_lux"] == 50.0
    assert np.all(np.diff(document["peaks"]) > 0)
