#!/usr/bin/env bash
# Create .venv (Python >= 3.11) and install skinrender with its test extras.
# Needs: python3 with venv (Debian: apt-get install python3 python3-venv).
set -euo pipefail
cd "$(dirname "$0")/.."
PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv || {
        echo "could not create a virtual environment; on Debian: apt-get install python3-venv" >&2
        exit 1
    }
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet -e ".[test]"
