"""Tests for :mod:`skinrender.studies.benchmarks.spectral_figure`: the bench's figure from its JSON document."""

from __future__ import annotations

from skinrender.studies.benchmarks.spectral_figure import figure_spectral


def test_the_figure_draws_a_document(tmp_path):
    rows = [{"cameras": n, "spectral_s": 2.0 + 0.05 * n, "direct_s": 0.5 * n * 8, "speedup": 1.0,
             "speedup_timed": 1.0} for n in (1, 5, 20)]
    result = {"rows": rows, "lights_K": [[2856, 5900]], "skins": ["a"], "levels": ["direct"], "size": 64,
              "spp": 16, "errors": {"spectral": [[0.04, 0.04, 0.05]], "direct": [[0.06, 0.04, 0.05]]},
              "narrow": {"camera": "gbell:3@450,540,610", "error_spectral": [0.14, 0.13, 0.14],
                         "error_direct": [0.04, 0.04, 0.05], "penalty": [10.0, 9.0, 8.0]},
              "basis": [{"camera": "gbell:9", "bands_nm": f"400:700:{s:g}", "max_rel_error": 1e-3 * s}
                        for s in (2.5, 5, 10)]}
    path = figure_spectral(result, tmp_path / "bench.png")
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
