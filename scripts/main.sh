#!/usr/bin/env bash
# Set up (scripts/setup.sh) and run the main job: Stage 1 illuminant selection
# for a candidate camera, its Eq. 4 responses to the Macbeth chart under a
# prevailing light (A, 2856 K) with another calibration (Horizon, 2300 K), then
# a Mitsuba render of the face chart under 2000 K white-balanced to 5900 K,
# validated patch by patch against Eq. 4 (EXR + PNG in out/, and
# out/face_chart_labelled.png: the chart with each patch's name), skin detection
# on the chart (out/face_chart_mask.png, and out/face_chart_detect.png: the
# mask with each patch's name and detected fraction), the scanned head rendered
# with sheen (out/face.exr with a label channel, out/face.png, and
# out/face_labelled.png with the labels outlined), skin detection on the head
# (out/face_detect.png: the detected skin over the face, its labels outlined,
# TPR and FPR in the title) and a small physics ladder (out/ladder.png: per
# level the render, labels, detected mask and skin NCC over the analytic locus).
# The face detection and the ladder use few samples and a small image (see
# their lines) so that the whole job stays within a few minutes on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
CAMERA=${CAMERA:-gbell:9@450,540,610}
.venv/bin/skinrender illuminants --camera "$CAMERA"
echo
.venv/bin/skinrender response --camera "$CAMERA" --reflectances macbeth --prevailing A --calibration H
echo
.venv/bin/skinrender render face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900 -o out/face_chart.exr \
    --figure out/face_chart_labelled.png
echo
.venv/bin/skinrender validate face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900
echo
# the scanned head in skin beside skin-like props, with a label channel and a preview (out/face.png)
.venv/bin/skinrender render face --camera "$CAMERA" --prevailing 2856 --calibration 5900 --physics sheen -o out/face.exr \
    --figure out/face_labelled.png
echo
.venv/bin/skinrender detect face_chart --camera "$CAMERA" --prevailing 2000 --calibration 5900 -o out/face_chart_mask.png \
    --figure out/face_chart_detect.png
echo
# the head at the scene's size, 64 spp (about 10 s here): the detected skin over the face, TPR/FPR in the title
.venv/bin/skinrender detect face --camera "$CAMERA" --prevailing 2856 --calibration 5900 --spp 64 \
    -o out/face_mask.png --figure out/face_detect.png
echo
# the ladder of physics, small (64 x 64 px, 16 spp: about 20 s on 2 cores; the README's table is the full size).
# Its last lines are a finding, not a failure of the job: "finding:" says at which levels of physics Eq. 4
# mispredicts the skin locus's detection rates (by more than 0.02), and the verdict line "FAIL (exit status 1)"
# means Eq. 4 was shown wrong there (mixed light, sensor noise), which is what the ladder measures. Exit 3 means
# some level could not be decided at this size; only 2 (a refused input) stops the job.
status=0
.venv/bin/skinrender ladder --camera "$CAMERA" --prevailing 2856 --calibration 5900 --size 64 --spp 16 \
    --plot out/ladder.png || status=$?
if [ "$status" -eq 2 ]; then exit 2; fi
echo
case "$status" in
    0) echo "main job done: Eq. 4 predicts skin detection at every level of the ladder (out/ladder.png)." ;;
    1) echo "main job done. The ladder's FAIL above is its finding, not an error: Eq. 4 mispredicts skin detection" \
            "at the levels its 'finding:' line names (out/ladder.png shows them); the job itself succeeded." ;;
    *) echo "main job done. The ladder could not decide every level at 64 px, 16 spp (exit $status): raise its" \
            "--spp or --size to decide them; the job itself succeeded." ;;
esac
