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
if [ -z "${SKINRENDER_NO_APT:-}" ] && ! ls /usr/lib/*/libLLVM.so.1[6-9]* /usr/lib/*/libLLVM.so.2[0-9]* >/dev/null 2>&1; then
    if command -v apt-get >/dev/null 2>&1 && [ "$(id -u)" = 0 ]; then
        echo "installing libllvm19 for Mitsuba's llvm_ad_spectral variant" >&2
        (apt-get install -y -q libllvm19 >/dev/null 2>&1 || { apt-get update -q >/dev/null 2>&1 && apt-get install -y -q libllvm19 >/dev/null 2>&1; }) \
            || echo "could not install libllvm19: rendering will use scalar_spectral (slower)" >&2
    else
        echo "note: no libLLVM >= 16 found; for fast rendering: sudo apt-get install libllvm19" >&2
    fi
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[all,test]"
