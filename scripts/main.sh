#!/usr/bin/env bash
# Set up (scripts/setup.sh) and run the main job: Stage 1 illuminant selection
# for a candidate camera, then its Eq. 4 responses to the Macbeth chart under
# a prevailing light (A, 2856 K) with another calibration (Horizon, 2300 K).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
CAMERA=${CAMERA:-gbell:9@450,540,610}
.venv/bin/skinrender illuminants --camera "$CAMERA"
echo
.venv/bin/skinrender response --camera "$CAMERA" --reflectances macbeth --prevailing A --calibration H
