#!/usr/bin/env bash
# Set up (scripts/setup.sh) and run the whole test suite, one pytest-xdist worker per core (-n auto), each test
# file on one worker (--dist loadfile: a file's module fixtures, renders shared by its tests, are made once), the
# longest files first (tests/conftest.py LONGEST_FIRST; --no-loadscope-reorder keeps that order).
# Arguments go to pytest after these, so `-n 0` runs in this process.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
.venv/bin/python -m pytest -n auto --dist loadfile --no-loadscope-reorder "$@"
