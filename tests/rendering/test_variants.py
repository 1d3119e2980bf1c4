"""Tests for :mod:`skinrender.rendering.variants`: a probe's verdict serves the processes started after it, only
under the same fingerprint (choosing a variant itself is tested in tests/rendering/test_renderer.py)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from skinrender.rendering import variants
from skinrender.rendering.variants import VERDICTS_VARIABLE, fingerprint, variant_works


@pytest.fixture
def probes(monkeypatch):
    """The probe replaced by a counter that answers ``probes.code`` (0: the variant works); no verdict in the
    environment at the start (the test's changes to it are undone after)."""

    class Probe:
        code, calls = 0, []

        def __call__(self, argv, **kwargs):
            self.calls.append(argv[-1])
            return subprocess.CompletedProcess(argv, self.code, "", "")

    probe = Probe()
    probe.calls = []
    monkeypatch.setenv(VERDICTS_VARIABLE, "")  # so that the variable as it was comes back after the test
    monkeypatch.delenv(VERDICTS_VARIABLE)
    monkeypatch.setattr(variants.subprocess, "run", probe)
    return probe


def test_a_verdict_is_left_for_child_processes_and_taken_from_there(probes):
    assert variant_works("scalar_spectral") and variant_works("scalar_spectral")
    assert probes.calls == ["scalar_spectral"]  # probed once
    assert os.environ[VERDICTS_VARIABLE] == f"{fingerprint()} scalar_spectral=1"
    probes.code = -6  # drjit's abort: the failing verdict is kept too, beside the other
    os.environ[VERDICTS_VARIABLE] = os.environ[VERDICTS_VARIABLE].replace("scalar_spectral=1", "x=1")
    assert not variant_works("scalar_spectral") and not variant_works("scalar_spectral")
    assert probes.calls == ["scalar_spectral"] * 2
    assert os.environ[VERDICTS_VARIABLE] == f"{fingerprint()} scalar_spectral=0 x=1"


def test_a_verdict_under_another_fingerprint_is_not_trusted(probes):
    os.environ[VERDICTS_VARIABLE] = "0" * 32 + " scalar_spectral=1"  # another machine, interpreter or install
    probes.code = 1
    assert not variant_works("scalar_spectral")
    assert probes.calls == ["scalar_spectral"]
    assert os.environ[VERDICTS_VARIABLE] == f"{fingerprint()} scalar_spectral=0"


def test_a_timed_out_probe_is_not_recorded(probes, monkeypatch):
    def slow(argv, **kwargs):
        raise subprocess.TimeoutExpired(argv, 180)

    monkeypatch.setattr(variants.subprocess, "run", slow)
    assert not variant_works("scalar_spectral")
    assert VERDICTS_VARIABLE not in os.environ


def test_the_fingerprint_follows_what_decides_the_verdict(monkeypatch, tmp_path):
    """drjit's and CUDA's environment variables and the libLLVM file itself (replaced in place: a new fingerprint)."""
    library = tmp_path / "libLLVM.so.19"
    library.write_bytes(b"one")
    monkeypatch.setenv("DRJIT_LIBLLVM_PATH", str(library))
    first = fingerprint()
    assert fingerprint() == first
    library.write_bytes(b"other")
    second = fingerprint()
    assert second != first
    monkeypatch.setenv("CUDA_VISIBLE_DEVICES", "")
    third = fingerprint()
    assert third != second
    monkeypatch.setenv("SOMETHING_ELSE", "1")  # what drjit does not read changes nothing
    assert fingerprint() == third


def test_a_child_process_computes_the_same_fingerprint():
    """Nothing of one process (its id, its imports, the __pycache__ the probe writes) enters the fingerprint."""
    code = "from skinrender.rendering.variants import fingerprint; print(fingerprint())"
    child = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                           env=os.environ.copy())
    assert child.stdout.strip() == fingerprint()
