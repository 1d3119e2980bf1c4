"""
A round of bad or extreme inputs through every front door (issue 36's "done when"): each case is run in its own
process and judged as the project's rules ask — exit status 2 (1 for the machine's own errors, such as a full
device), one line on stderr naming the argument, no traceback, stdout one JSON document or nothing, no file left in
the output folder (a read-only folder is tried as the unprivileged user 65534 where this runs as root, who
may write anywhere); for the Python API, a :class:`~skinrender.errors.SkinrenderError` naming the argument.

Usage: ``PYTHONPATH=. python tools/try_bad_inputs.py [--markdown] [CASE …]`` (case numbers; default all). Prints one
row per case (input, expected, got, ok) and exits 1 if any case is not handled as expected. Run from the
repository root; scratch files go to a temporary folder.

Units: none (exit statuses, lines).
"""

from __future__ import annotations

import json
import os
import stat
import subprocess
import sys
import tempfile
from pathlib import Path

CAM = "gbell:9@450,540,610"
CHART = ["render", "macbeth", "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"]
VALIDATE = ["validate", "macbeth", "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"]
FACE = ["--camera", CAM, "--prevailing", "2856", "--calibration", "5900"]
SPECTRAL = ["render", "macbeth", "--prevailing", "3000", "--spectral"]


def _files(root: Path) -> dict[str, str]:
    """Scratch inputs: a read-only folder, a folder, empty and degenerate CSV and TOML files."""
    ro = root / "readonly"
    ro.mkdir()
    (root / "adir").mkdir()
    texts = {
        "empty.csv": "", "header.csv": "nm,r,g,b\n", "onerow.csv": "nm,r,g,b\n550,1,1,1\n",
        "nan.csv": "nm,r,g,b\n400,1,1,1\n550,nan,1,1\n700,1,1,1\n",
        "negative.csv": "nm,a\n400,-0.5\n550,0.5\n700,0.5\n",
        "unsorted.csv": "nm,r,g,b\n550,1,1,1\n400,1,1,1\n700,1,1,1\n",
        "empty.toml": "", "nopatch.toml": "columns = 2\npatch_px = 8\n",
        "badpatch.toml": "columns = 1\npatch_px = 8\n[[patch]]\nname = 'x'\nreflectance = 'grey:7'\n",
        "zeropx.toml": "columns = 1\npatch_px = 0\n[[patch]]\nname = 'x'\nreflectance = 'grey:0.5'\n",
        "imager_empty.toml": "",
        "imager_well.toml": "name='w'\nsource='t'\npixel_um=5\nf_number=2.8\ntransmittance=0.9\nqe_peak=0.6\n"
                            "full_well_e=-1\nread_noise_e=5\ndark_current_e_per_s=1\ngain_dn_per_e=0.1\nbits=12\n"
                            "black_level_dn=10\n",
        "notexr.exr": "this is not an EXR file\n",
    }
    for name, text in texts.items():
        (root / name).write_text(text)
    (root / "afile").write_text("x")
    os.chmod(ro, stat.S_IRUSR | stat.S_IXUSR)
    return {name: str(root / name) for name in [*texts, "readonly", "adir", "afile"]}


def cases(f: dict[str, str]) -> list[tuple[str, list[str] | str, tuple[str, ...], int]]:
    """(label, argv or Python source, names the line must contain, expected exit status)."""
    ro, adir = f["readonly"], f["adir"]
    py = ("import skinrender as sr\n"
          "from skinrender.errors import SkinrenderError\n"
          "try:\n    {call}\n"
          "except SkinrenderError as e:\n    print('SkinrenderError:', e, '| role', e.role, '| flag', e.flag,"
          " file=sys.stderr); raise SystemExit(2)\n"
          "print('accepted'); raise SystemExit(0)\n")
    api = lambda call: "import sys\n" + py.format(call=call)  # noqa: E731
    r = f"sr.render('macbeth', camera='{CAM}', prevailing=3000, calibration=4000, "
    return [
        # bad numbers
        ("render --prevailing nan", [*CHART[:-1], "nan"], ("--prevailing",), 2),
        ("render --calibration -5", [*CHART, "--calibration", "-5"], ("--calibration",), 2),
        ("render --spp 0", [*CHART, "--spp", "0"], ("--spp",), 2),
        ("render --spp 2.5", [*CHART, "--spp", "2.5"], ("--spp",), 2),
        ("validate --tolerance 1", [*VALIDATE, "--tolerance", "1"], ("--tolerance",), 2),
        ("validate --tolerance inf", [*VALIDATE, "--tolerance", "inf"], ("--tolerance",), 2),
        ("render --imager … --illuminance -1", [*CHART, "--imager", "sony-imx174", "--illuminance", "-1"],
         ("--illuminance",), 2),
        ("render --imager … --illuminance inf", [*CHART, "--imager", "sony-imx174", "--illuminance", "inf"],
         ("--illuminance",), 2),
        ("render --imager … --exposure 0", [*CHART, "--imager", "sony-imx174", "--exposure", "0"], ("--exposure",), 2),
        ("render --max-minutes -1", [*CHART, "--max-minutes", "-1"], ("--max-minutes",), 2),
        ("ptc --illuminance 0", ["ptc", "--camera", CAM, "--imager", "sony-imx174", "--illuminance", "0"],
         ("--illuminance",), 2),
        ("ptc --points 3", ["ptc", "--camera", CAM, "--imager", "sony-imx174", "--points", "3"], ("--points",), 2),
        ("render --spectral --bands 700:400:10", [*SPECTRAL, "--bands", "700:400:10"], ("--bands",), 2),
        ("render --spectral --bands 400:700:0", [*SPECTRAL, "--bands", "400:700:0"], ("--bands",), 2),
        ("render --spectral --bands 400:700:nan", [*SPECTRAL, "--bands", "400:700:nan"], ("--bands",), 2),
        ("render --bands without --spectral", [*CHART, "--bands", "400:700:10"], ("--bands",), 2),
        ("render --spectral --bands 1:100000:0.001", [*SPECTRAL, "--bands", "1:100000:0.001"],
         ("--bands",), 2),
        ("ladder --detection-tolerance 1.5", ["ladder", *FACE, "--detection-tolerance", "1.5"], ("--detection-tolerance",), 2),
        ("ladder --detection-tolerance -0.1", ["ladder", *FACE, "--detection-tolerance", "-0.1"],
         ("--detection-tolerance",), 2),
        ("validate face --detection-tolerance nan", ["validate", "face", *FACE, "--detection-tolerance", "nan"],
         ("--detection-tolerance",), 2),
        ("face-sweep --detection-tolerance abc", ["face-sweep", "--camera", CAM, "--detection-tolerance", "abc"],
         ("--detection-tolerance",), 2),
        ("rank --top -1", ["rank", "--top", "-1"], ("--top",), 2),
        ("rank --top 1e9", ["rank", "--top", "1e9"], ("--top",), 2),
        ("rank --size 0", ["rank", "--size", "0"], ("--size",), 2),
        ("rank --lights 2856", ["rank", "--lights", "2856"], ("--lights",), 2),
        ("rank --lights 2856/0", ["rank", "--lights", "2856/0"], ("--lights",), 2),
        ("rank --spp -16", ["rank", "--spp", "-16"], ("--spp",), 2),
        ("render --grid 400:700:-1", [*CHART, "--grid", "400:700:-1"], ("--grid",), 2),
        ("response --prevailing 1e400", ["response", "--camera", CAM, "--reflectances", "skin", "--prevailing",
                                         "1e400", "--calibration", "A"], ("--prevailing",), 2),
        # bad seeds
        ("render --seed -1", [*CHART, "--seed", "-1"], ("--seed",), 2),
        ("render --seed 4294967296", [*CHART, "--seed", "4294967296"], ("--seed",), 2),
        ("render --seed 1.5", [*CHART, "--seed", "1.5"], ("--seed",), 2),
        ("rank --seed -3", ["rank", "--seed", "-3"], ("--seed",), 2),
        ("ptc --seed 99999999999", ["ptc", "--camera", CAM, "--imager", "sony-imx174", "--seed", "99999999999"],
         ("--seed",), 2),
        ("bench calibration --seeds 0", ["bench", "calibration", "--seeds", "0"], ("--seeds",), 2),
        ("bench calibration --seed -1", ["bench", "calibration", "--seed", "-1"], ("--seed",), 2),
        # unknown names
        ("render nosuchchart", ["render", "nosuchchart", "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"], ("SCENE",), 2),
        ("render --camera gbell:99@1,2,3", ["render", "macbeth", "--camera", "gbell:99@1,2,3", "--calibration", "4000",
                                               "--prevailing", "3000"],
         ("--camera",), 2),
        ("render --imager no-such-imager", [*CHART, "--imager", "no-such-imager"], ("--imager",), 2),
        ("rank --skin-set nosuch", ["rank", "--skin-set", "nosuch"], ("--skin-set",), 2),
        ("locus --skin-set nosuch", ["locus", "--camera", CAM, "--skin-set", "nosuch"], ("--skin-set",), 2),
        ("ladder --skin-set ''", ["ladder", *FACE, "--skin-set", ""], ("--skin-set",), 2),
        ("ladder --levels direct,bogus", ["ladder", *FACE, "--levels", "direct,bogus"], ("--levels",), 2),
        ("rank --levels warp", ["rank", "--levels", "warp"], ("--levels",), 2),
        ("render --variant cuda_nope", [*CHART, "--variant", "cuda_nope"], ("--variant",), 2),
        ("render face --physics bogus", ["render", "face", "--camera", CAM, "--calibration", "4000", "--prevailing", "3000", "--physics",
                                         "bogus"], ("--physics",), 2),
        ("rank --skin nosuch:sample", ["rank", "--skin", "nosuch:sample"], ("--skin",), 2),
        ("rank --camera nosuch-camera", ["rank", "--camera", "nosuch-camera"], ("--camera",), 2),
        # paths
        ("render -o read-only folder", [*CHART, "-o", f"{ro}/x.exr"], ("--output",), 2),
        ("render -o an existing folder", [*CHART, "-o", adir], ("--output",), 2),
        ("render -o a file as parent", [*CHART, "-o", f"{f['afile']}/x.exr"], ("--output",), 2),
        ("rank --plot read-only folder", ["rank", "--plot", f"{ro}/p.png"], ("--plot",), 2),
        ("rank --plot an existing folder", ["rank", "--plot", adir], ("--plot",), 2),
        ("render --spectral -o read-only folder", [*SPECTRAL, "-o", f"{ro}/s.exr"], ("--output",), 2),
        ("cameras --json > /dev/full", "cameras --json > /dev/full", ("/dev/full", "standard output"), 1),
        ("skin --json > /dev/full", "skin --grid 400:700:5 --json > /dev/full", ("standard output",), 1),
        ("imagers --json > /dev/full", "imagers --json > /dev/full", ("standard output",), 1),
        # empty and degenerate files
        ("render empty.toml", ["render", f["empty.toml"], "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"], ("SCENE",), 2),
        ("render a chart with no patch", ["render", f["nopatch.toml"], "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"],
         ("SCENE",), 2),
        ("render a patch of grey:7", ["render", f["badpatch.toml"], "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"],
         ("SCENE",), 2),
        ("render patch_px = 0", ["render", f["zeropx.toml"], "--camera", CAM, "--calibration", "4000", "--prevailing", "3000"], ("SCENE",), 2),
        ("response --camera empty.csv", ["response", "--camera", f["empty.csv"], "--reflectances", "skin",
                                         "--prevailing", "A", "--calibration", "A"], ("--camera",), 2),
        ("response --camera header-only.csv", ["response", "--camera", f["header.csv"], "--reflectances", "skin",
                                               "--prevailing", "A", "--calibration", "A"], ("--camera",), 2),
        ("response --camera one-row.csv", ["response", "--camera", f["onerow.csv"], "--reflectances", "skin",
                                           "--prevailing", "A", "--calibration", "A"], ("--camera",), 2),
        ("response --camera with NaN", ["response", "--camera", f["nan.csv"], "--reflectances", "skin",
                                        "--prevailing", "A", "--calibration", "A"], ("--camera",), 2),
        ("response --camera unsorted", ["response", "--camera", f["unsorted.csv"], "--reflectances", "skin",
                                        "--prevailing", "A", "--calibration", "A"], ("--camera",), 2),
        ("response --reflectances negative.csv", ["response", "--camera", CAM, "--reflectances", f["negative.csv"],
                                                  "--prevailing", "A", "--calibration", "A"], ("--reflectances",), 2),
        ("render --imager empty.toml", [*CHART, "--imager", f["imager_empty.toml"]], ("--imager",), 2),
        ("render --imager full_well_e = -1", [*CHART, "--imager", f["imager_well.toml"]], ("--imager", "full_well_e"),
         2),
        ("render --camera a folder", ["render", "macbeth", "--camera", adir, "--calibration", "4000", "--prevailing", "3000"], ("--camera",), 2),
        # the Python API
        ("sr.render(spp=-1)", api(r + "spp=-1)"), ("spp",), 2),
        ("sr.render(seed=-1)", api(r + "seed=-1)"), ("seed",), 2),
        ("sr.render(seed=2**32)", api(r + "seed=2**32)"), ("seed",), 2),
        ("sr.render(prevailing=nan)", api(f"sr.render('macbeth', camera='{CAM}', prevailing=float('nan'), calibration=4000)"),
         ("prevailing",), 2),
        ("sr.render(spectral=True, bands='400:700:0')",
         api("sr.render('macbeth', prevailing=3000, spectral=True, bands='400:700:0')"), ("bands",), 2),
        ("sr.render(imager=…, illuminance=-5)", api(r + "imager='sony-imx174', illuminance=-5)"), ("illuminance",), 2),
        ("sr.render(bogus=1)", api(r + "bogus=1)"), ("bogus",), 2),
        ("sr.validate(tolerance=2)", api(f"sr.validate('macbeth', camera='{CAM}', prevailing=3000, calibration=4000, tolerance=2)"),
         ("tolerance",), 2),
        ("sr.validate(tolerance='x')", api(f"sr.validate('macbeth', camera='{CAM}', prevailing=3000, "
                                           "calibration=4000, tolerance='x')"), ("tolerance",), 2),
        ("sr.validate(scene=42)", api(f"sr.validate(42, camera='{CAM}', prevailing=3000, calibration=4000)"), ("scene",), 2),
        ("sr.detect(None, None)", api("sr.detect(None, None)"), ("rendering",), 2),
        ("sr.detect('macbeth', 'skin')", api("sr.detect('macbeth', 'skin')"), ("rendering",), 2),
        ("sr.read_spectral(missing)", api("sr.read_spectral('/nonexistent/x.exr')"), ("path",), 2),
        ("sr.read_spectral(a folder)", api(f"sr.read_spectral({adir!r})"), ("path",), 2),
        ("sr.read_spectral(not an EXR)", api(f"sr.read_spectral({f['notexr.exr']!r})"), ("path",), 2),
        ("sr.read_spectral(None)", api("sr.read_spectral(None)"), ("path",), 2),
    ]


def _judge(label, what, names, expected, out_dir: Path) -> tuple[str, bool]:
    """Run one case; returns (what happened, as expected)."""
    before = sorted(p.name for p in out_dir.rglob("*"))
    env = {**os.environ, "PYTHONPATH": os.getcwd()}
    if isinstance(what, str) and what.startswith("import"):
        argv = [sys.executable, "-c", what]
    elif isinstance(what, str):
        argv = ["bash", "-c", f"{sys.executable} -m skinrender {what}"]
    else:
        argv = [sys.executable, "-m", "skinrender", *what, "--json"]
    if "read-only" in label and os.geteuid() == 0:  # root writes into any folder: try it as an unprivileged user
        argv = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", *argv]
        env["MPLCONFIGDIR"] = str(out_dir.parent / "mpl")
    try:
        done = subprocess.run(argv, capture_output=True, text=True, timeout=120, cwd=out_dir, env=env)
    except subprocess.TimeoutExpired:
        return "still running after 120 s", False
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    problems = []
    if done.returncode != expected:
        problems.append(f"exit {done.returncode}")
    if "Traceback" in done.stderr or "internal error" in done.stderr:
        problems.append("traceback/internal error")
    if len(lines) != 1:
        problems.append(f"{len(lines)} lines on stderr")
    line = lines[-1] if lines else ""
    missing = [n for n in names if n not in line]
    if missing and not (len(names) > 1 and len(missing) < len(names)):
        problems.append(f"does not name {missing[0]}")
    if done.stdout.strip() and not what.__class__ is str:
        try:
            json.loads(done.stdout)
        except ValueError:
            problems.append("stdout not one JSON document")
    if isinstance(what, str) and what.startswith("import") and "accepted" in done.stdout:
        problems.append("accepted")
    if sorted(p.name for p in out_dir.rglob("*")) != before:
        problems.append("left files behind")
    got = f"exit {done.returncode}: {line[:160]}"
    return (got if not problems else f"{got} [{'; '.join(problems)}]"), not problems


def main(argv: list[str]) -> int:
    markdown = "--markdown" in argv
    wanted = {int(a) for a in argv if a.isdigit()}
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        os.chmod(root, 0o755)  # readable by the unprivileged user the read-only cases run as (under root)
        (root / "mpl").mkdir(mode=0o777)
        os.chmod(root / "mpl", 0o777)
        f = _files(root)
        out_dir = root / "work"
        out_dir.mkdir()
        failures = 0
        if markdown:
            print("| # | input | expected | got | ok |\n|---|---|---|---|---|")
        for number, (label, what, names, expected) in enumerate(cases(f), 1):
            if wanted and number not in wanted:
                continue
            got, ok = _judge(label, what, names, expected, out_dir)
            failures += not ok
            api = isinstance(what, str) and what.startswith("import")
            want = (f"SkinrenderError naming {' / '.join(names)}" if api
                    else f"exit {expected}, one line naming {' / '.join(names)}")
            got = got.replace("exit 2: SkinrenderError:", "SkinrenderError:") if api else got
            got = got.replace(tmp, "$TMP").replace("|", "\\|")
            print(f"| {number} | `{label}` | {want} | {got} | {'yes' if ok else '**no**'} |" if markdown
                  else f"{number:3d} {'ok ' if ok else 'BAD'} {label}: {got}", flush=True)
        os.chmod(f["readonly"], stat.S_IRWXU)
    print(f"{failures} not as expected", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
