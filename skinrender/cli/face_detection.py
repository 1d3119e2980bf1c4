"""
``detect face …``: skin detection on a rendered face (the ``detect`` command hands a face scene here,
:mod:`skinrender.cli.rendering`), scored against the label channel.

Units: temperatures K, images in Eq. 4 output units, rates fractions.
"""

from __future__ import annotations

import argparse
import sys

from ..files import Output, write_outputs
from .common import check_output, emit, flag, settings_of, table
from .face import check_figure, face_request_of

__all__ = ["command_detect_face"]


def command_detect_face(args: argparse.Namespace, scene) -> None:
    """
    ``detect SCENE …`` for a face scene: render it (``--physics`` from the scene's default, ``direct``), classify
    every pixel by the camera's analytic skin locus for the calibration's white balance (trained on ``--skin``'s
    set), and score against the label channel: TPR over skin pixels, FPR over the props' pixels.
    """
    from ..datasets import reflectances
    from ..evaluation.detection import SCORED_MIN_OUTPUT
    from ..evaluation.locus import skin_locus
    from ..rendering.exr import write_png, write_preview
    from ..studies.face.ladder import score_frame

    from ..rendering.kinds import FACE
    from .inputs import check_request_work

    settings = settings_of(args)
    output = check_output(args.output, "--output", (".png",))
    check_output(str(output.with_name(output.stem + "_preview.png")), "--output (its preview)", (".png",))
    figure = check_figure(args, output, output.with_name(output.stem + "_preview.png"))
    request = face_request_of(args, scene, settings)
    cam, scene = request.camera, request.scene
    temperatures = {"prevailing": request.prevailing, "calibration": request.calibration}
    locus_skin = getattr(args, "locus_skin", None) or "skin"
    skin = flag("--locus-skin", reflectances, locus_skin)
    # before the render: a set that does not cover the grid was refused after it (and blamed on --skin)
    locus = flag("--locus-skin", skin_locus, cam, skin, calibration=temperatures["calibration"], boundary=args.boundary)
    check_request_work(args, request)
    print(f"rendering the face ({request.level.name}) at {settings.spp} spp …", file=sys.stderr)
    result = FACE.render(request)
    scores, frame = score_frame(result, locus, clip_negative=True)  # scored as the ladder: too dark has no chromaticity
    mask, scored = frame["inside"], frame["scored"]
    tpr, fpr = scores["tpr"], scores["fpr"]
    undefined = {key: reason for key, reason in scores["undefined"].items() if key in ("tpr", "fpr")}
    preview = output.with_name(output.stem + "_preview.png")
    outputs = [Output(output, "--output", lambda stream: write_png(stream, mask.astype(float))),
               Output(preview, "--output (its preview)", lambda stream: write_preview(stream, result.image))]
    per_label = []
    for name, ident in result.label_names.items():
        seen = scored & (result.labels == ident)
        if ident > 0:
            per_label.append({"name": name, "id": ident, "is_skin": ident == 1,
                              "detected_fraction": float(mask[seen].mean()) if seen.any() else None,
                              **({} if seen.any() else {"undefined": f"no scored pixel of {name} (in view with "
                                                                      f"its brightest channel ≥ {SCORED_MIN_OUTPUT:g})"})})
    document = {"scene": scene.name, "camera": cam.name, "prevailing_K": temperatures["prevailing"],
                "calibration_K": temperatures["calibration"], "tpr": tpr, "fpr": fpr, "undefined": undefined,
                "locus_degenerate": locus.degenerate, "mask_png": str(output), "preview_png": str(preview),
                "per_patch": per_label, "labels": result.label_names, "physics": result.physics,
                "skin": result.skin, "locus_skin": locus_skin,
                "scored_min_output": SCORED_MIN_OUTPUT, "boundary": args.boundary, "spp": result.spp, "spp_requested": settings.spp,
                "variant": result.variant}
    shown = lambda value: "undefined" if value is None else f"{value:.3f}"  # noqa: E731
    if figure is not None:
        from ..studies.figures import figure_face

        title = (f"{scene.name} through {cam.name}, {result.prevailing:g} K balanced to {result.calibration:g} K "
                 f"({result.physics}, {result.spp} spp): TPR {shown(tpr)}, FPR {shown(fpr)}\n"
                 f"detected: inside the analytic skin locus, scored pixels (brightest channel ≥ "
                 f"{SCORED_MIN_OUTPUT:g})")
        outputs.append(Output(figure, "--figure", lambda stream: figure_face(
            result.image, result.labels, result.label_names, title, stream, mask & scored)))
        document["figure"] = str(figure)
    write_outputs(*outputs)  # every file whole, or none of them
    rows = [[row["name"][:30], "skin" if row["is_skin"] else "", shown(row["detected_fraction"])] for row in per_label]
    emit(args, document, table(rows, ["region", "", "detected"]) + f"\nTPR {shown(tpr)}, FPR {shown(fpr)}; mask {output}"
         + (f"; figure {figure}" if figure is not None else ""))
