#!/usr/bin/env bash
# Set up (scripts/setup.sh) and run the main job: Stage 1 illuminant selection
# for a candidate camera, its Eq. 4 responses to the Macbeth chart under a
# prevailing light (A, 2856 K) with another calibration (Horizon, 2300 K), then
# a Mitsuba render of the face chart under 2000 K white-balanced to 5900 K,
# validated patch by patch against Eq. 4 (EXR + PNG in out/), the scanned head rendered with sheen
# (out/face.exr with a label channel, out/face.png) and skin detection on the chart (out/face_chart_mask.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
CAMERA=${CAMERA:-gbell:9@450,540,610}
.venv/bin/skinrender illuminants --camera "$CAMERA"
echo
.venv/bin/skinrender response --camera "$CAMERA" --reflectances macbeth --prevailing A --calibration H
echo
.venv/bin/skinrender render face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900 -o out/face_chart.exr
echo
.venv/bin/skinrender validate face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900
echo
# the scanned head in skin beside skin-like props, with a label channel and a preview (out/face.png)
.venv/bin/skinrender render face --camera "$CAMERA" --prevailing 2856 --calibration 5900 --physics sheen -o out/face.exr
echo
.venv/bin/skinrender detect face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900 -o out/face_chart_mask.png
