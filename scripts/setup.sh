#!/usr/bin/env bash
# Create .venv (Python >= 3.11) and install skinrender with every extra and the test tools.
# Needs: python3 with venv (Debian: apt-get install python3 python3-venv).
# Rendering is fastest with Mitsuba's llvm_ad_spectral, which needs libLLVM >= 16
# (Debian 12 ships 15, which makes drjit abort): when none is found and apt-get
# can be used (root), libllvm19 is installed; otherwise skinrender falls back to
# scalar_spectral (about 7x slower) and says so. SKINRENDER_NO_APT=1 skips this.
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv || {
        echo "could not create a virtual environment; on Debian: apt-get install python3-venv" >&2
        exit 1
    }
fi
# (one pattern at a time: `ls A B` fails when either matches nothing, which re-ran apt-get on every call)
if [ -z "${SKINRENDER_NO_APT:-}" ] && ! compgen -G "/usr/lib/*/libLLVM.so.1[6-9]*" >/dev/null \
        && ! compgen -G "/usr/lib/*/libLLVM.so.[2-9][0-9]*" >/dev/null; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        echo "installing libllvm19 for Mitsuba's llvm_ad_spectral variant" >&2
        (apt-get install -y -q libllvm19 >/dev/null 2>&1 || { apt-get update -q >/dev/null 2>&1 && apt-get install -y -q libllvm19 >/dev/null 2>&1; }) \
            || echo "could not install libllvm19: rendering will use scalar_spectral (slower)" >&2
    else
        echo "note: no libLLVM >= 16 found; for fast rendering: sudo apt-get install libllvm19" >&2
    fi
fi
# pip runs when pyproject.toml differs from the one last installed (its SHA-256 in .venv/skinrender-setup.sha256)
# or the package does not import: ~5 s saved on every test run of an unchanged checkout.
stamp=.venv/skinrender-setup.sha256
wanted=$(sha256sum pyproject.toml | cut -d' ' -f1)
if [ "$(cat "$stamp" 2>/dev/null)" != "$wanted" ] \
        || ! .venv/bin/python -c "import importlib.metadata as m; m.version('skinrender'); import pytest, xdist" \
            >/dev/null 2>&1; then
    rm -f "$stamp"
    .venv/bin/python -m pip install --quiet --upgrade pip
    .venv/bin/python -m pip install --quiet -e ".[all,test]"
    echo "$wanted" > "$stamp"
fi
