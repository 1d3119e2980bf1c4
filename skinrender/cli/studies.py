"""
The paper's studies and benchmarks: ``reproduce``, ``table1``, ``bench``.
"""

from __future__ import annotations

import argparse
import sys

from ..errors import SkinrenderError
from .common import (HELP_CAMERA, add_common, add_search,
                     emit, table)


def add_parsers(commands) -> None:
    """Add the parsers of reproduce, table1, bench."""
    p = commands.add_parser("reproduce", help="the paper's Figs. 3–7 (PNG) and Tables 2–5 (Markdown, CSV)")
    p.add_argument("-o", "--output", required=True, help="output folder")
    p.add_argument("--sensors", default="1,3,5,7,9,11,13,15", help="sensor numbers (default 1,3,…,15)")
    p.add_argument("--positions", default="400:700:10", help="peak positions START:END:STEP in nm (default 400:700:10)")
    p.add_argument("--camera", default="Nikon 5100 (NPL)",
                   help="Stage 2 camera for Figs. 3–7 (the paper's Sony is not public); " + HELP_CAMERA)
    p.add_argument("--slope", type=float, default=2.0, help="gbell slope b (default 2)")
    add_search(p)
    add_common(p)

    p = commands.add_parser("table1", help="the paper's Table 1: NCC differences, render vs model, Macbeth under A and H")
    p.add_argument("--camera", default="gbell:9@450,540,610", help=HELP_CAMERA)
    p.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    p.add_argument("--seed", type=int, default=0, help="sampler seed (default 0)")
    add_common(p)

    p = commands.add_parser("bench", help="speed and accuracy figures")
    p.add_argument("what", choices=["analytic", "search", "render"], help="which benchmark")
    p.add_argument("--quick", action="store_true", help="render: a short curve (spp 4…256, one variant)")
    p.add_argument("--plot", help="render: write the error-against-time plot (log–log) to this PNG")
    p.add_argument("--repeat", type=int, default=3, help="analytic: timed repetitions, best kept (default 3)")
    p.add_argument("--sensor", type=float, default=9, help="search: sensor number (default 9)")
    p.add_argument("--sample", type=int, default=20, help="search: triplets timed per method (default 20)")
    p.add_argument("--workers", type=int, help="search: processes (default: every core)")
    add_common(p)


def command_reproduce(args: argparse.Namespace) -> None:
    from ..studies.reproduce import reproduce

    try:
        sensors = [float(v) for v in args.sensors.split(",")]
    except ValueError:
        raise SkinrenderError(f"--sensors must be comma-separated numbers, got {args.sensors!r}") from None
    result = reproduce(
        args.output, sensors, args.positions, args.camera, args.skin, args.munsell, args.slope,
        workers=args.workers, dask=args.dask, progress=None if args.quiet else sys.stderr,
    )
    searches = ", ".join(f"sensor {k}: {v:.1f} s" for k, v in result["search_s"].items())
    text = "\n".join(["wrote:"] + [f"  {p}" for p in result["artifacts"]]
                     + [f"searches: {sum(result['search_s'].values()):.1f} s ({searches})"])
    emit(args, result, text)


def command_table1(args: argparse.Namespace) -> None:
    from ..studies.tables import table1

    result = table1(args.camera, spp=args.spp, seed=args.seed)
    rows = [[r["model"], r["case"], f"{r['mean']:.5f}", f"{r['std']:.5f}"] for r in result["rows"]]
    text = (f"Table 1 for {result['camera']} ({len(result['patches'])} Macbeth patches with 90 % of values in "
            f"10–245; render at {result['spp']} spp as the real camera):\n"
            + table(rows, ["model", "case", "mean |ΔNCC|", "std"]))
    emit(args, result, text)


def command_bench(args: argparse.Namespace) -> None:
    from ..studies.bench import bench_analytic, bench_search

    if args.what == "render":
        from ..studies.bench import bench_render

        result = bench_render(quick=args.quick)
        if args.plot:
            from ..studies.figures import figure_render_curve

            result["plot"] = str(figure_render_curve(result, args.plot))
    elif args.what == "search":
        result = bench_search(args.sensor, args.sample, workers=args.workers)
    else:
        result = bench_analytic(repeat=args.repeat)
    text = "\n".join(f"{key}: {value}" for key, value in result.items())
    emit(args, result, text)
