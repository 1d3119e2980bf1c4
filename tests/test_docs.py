"""
The documentation keeps in step with the code: the Sphinx site (``docs/``) builds without a warning, every
``:cite:`` key has its bibliography entry, the command lists of the README, ``docs/commands.md`` and
``docs/contract.md`` are the parser's, and every console and Python example of the README and of
docs/commands.md runs and prints what it shows.

Examples: a ```` ```console ```` block holds ``$ COMMAND`` lines, each followed by what it prints: its
standard output when it exits 0, its standard error otherwise (a refusal's one line); ``...`` stands for
any text, as in doctests. A command exits 0 unless the next line is ``$ echo $?`` followed by its status.
``skinrender`` is this checkout's command line; each block runs in an empty folder of its own. A
```` ```pycon ```` block is a doctest (run in an empty folder too). Keep them quick: seconds each.
"""

from __future__ import annotations

import argparse
import doctest
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

REPOSITORY = Path(__file__).resolve().parents[1]
DOCS = REPOSITORY / "docs"
README = REPOSITORY / "README.md"


# --------------------------------------------------------------------------------------------------- the site


@pytest.mark.slow
def test_the_site_builds_without_a_warning(tmp_path):
    """``sphinx-build -W`` (warnings are errors) of the whole site, API pages from the docstrings included."""
    for module in ("sphinx", "myst_parser", "numpydoc", "sphinxcontrib.bibtex"):
        pytest.importorskip(module)
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html",
                          "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")],
                         capture_output=True, text=True, cwd=REPOSITORY,
                         env={**os.environ, "MPLBACKEND": "Agg"})
    assert run.returncode == 0, run.stderr[-6000:]
    assert (tmp_path / "html" / "api" / "skinrender.html").exists()


CITE = re.compile(r"(?::cite:[pt]?|\{cite(?::[pt])?\})`([A-Za-z][\w.:-]*(?:\s*,\s*[A-Za-z][\w.:-]*)*)`")
BIB_ENTRY = re.compile(r"^@\w+\{\s*([^,\s]+)\s*,", re.MULTILINE)


def cited_keys() -> dict[str, str]:
    """Every key cited in the package's docstrings and the docs' pages → a file citing it."""
    files = [*(REPOSITORY / "skinrender").rglob("*.py"), *DOCS.glob("*.md")]
    keys = {}
    for path in files:
        for match in CITE.finditer(path.read_text(encoding="utf-8")):
            for key in match.group(1).split(","):
                keys.setdefault(key.strip(), str(path.relative_to(REPOSITORY)))
    return keys


def test_every_cited_key_has_a_bibliography_entry():
    """A ``:cite:`` key without an entry in docs/references.bib: add its full reference there."""
    entries = set(BIB_ENTRY.findall((DOCS / "references.bib").read_text(encoding="utf-8")))
    cited = cited_keys()
    assert len(cited) >= 20
    assert {key: where for key, where in cited.items() if key not in entries} == {}


LINK = re.compile(r"\]\(([^)\s]+)\)")


def test_no_link_leaves_the_repository():
    """Every relative link of the README, CONTRIBUTING, CHANGELOG and docs/ stays inside the repository (the
    JSON contract once lived in ../shared/, outside it)."""
    pages = [README, REPOSITORY / "CONTRIBUTING.md", REPOSITORY / "CHANGELOG.md", *DOCS.glob("*.md")]
    outside = []
    for page in pages:
        for target in LINK.findall(page.read_text(encoding="utf-8")):
            if re.match(r"[a-z]+:|#", target):
                continue
            resolved = (page.parent / target.split("#")[0]).resolve()
            if REPOSITORY.resolve() not in resolved.parents:
                outside.append(f"{page.name}: {target}")
    assert outside == []


# ----------------------------------------------------------------------------------------------- the commands


def parser_commands() -> tuple[set[str], set[str]]:
    """The command line's commands and ``bench``'s benchmarks, from the parser itself."""
    from skinrender.cli import build_parser
    from skinrender.cli import commands as registry

    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    assert set(commands) == set(registry(parser)) and all(callable(run) for run in registry(parser).values())
    bench = commands["bench"]
    benchmarks = next(a.choices for a in bench._actions if not a.option_strings and a.choices)
    return set(commands), set(benchmarks)


def section(path: Path, heading: str) -> str:
    """The text of one ``## heading`` section of a Markdown file."""
    text = path.read_text(encoding="utf-8")
    start = text.index(f"\n{heading}\n")
    end = text.find("\n## ", start + len(heading) + 2)
    return text[start:end if end > 0 else None]


def documented_commands(text: str) -> tuple[set[str], set[str]]:
    """Commands and benchmarks named in the first column of the tables of ``text``: every backticked name
    there (``skinrender`` left off); ``bench X`` and ``bench {X,Y}`` name benchmarks."""
    commands, benchmarks = set(), set()
    for line in text.splitlines():
        if not line.startswith("|") or line.startswith("|---"):
            continue
        cell = re.split(r"(?<!\\)\|", line)[1]  # an escaped \| stays in its cell
        for name in re.findall(r"`([^`]+)`", cell):
            words = name.removeprefix("skinrender ").split()
            if not words or words[0].startswith("-") or not re.fullmatch(r"[a-z][a-z0-9-]*", words[0]):
                continue
            commands.add(words[0])
            if words[0] == "bench" and len(words) > 1:
                benchmarks.update(re.findall(r"[a-z][a-z0-9-]*", words[1]))
    return commands, benchmarks


def test_the_readme_lists_every_command():
    """The README's command table holds exactly the parser's commands."""
    commands, _ = parser_commands()
    listed, _ = documented_commands(section(README, "## Commands"))
    assert listed == commands


def test_the_commands_page_lists_every_command_and_benchmark():
    """docs/commands.md: one row per command and per benchmark of ``bench``."""
    commands, benchmarks = parser_commands()
    listed, benches = documented_commands(section(DOCS / "commands.md", "## Every command"))
    assert (listed, benches) == (commands, benchmarks)


def test_the_contract_lists_every_command_and_benchmark():
    """docs/contract.md promises JSON keys for every command and benchmark."""
    commands, benchmarks = parser_commands()
    listed, benches = documented_commands(section(DOCS / "contract.md", "## Commands"))
    assert (listed, benches) == (commands, benchmarks)


# -------------------------------------------------------------------------------------------- the examples


def fenced_blocks(text: str, language: str) -> list[tuple[int, str]]:
    """(first line number, body) of every ```` ```language ```` block of ``text``."""
    blocks = []
    for match in re.finditer(rf"^```{language}\n(.*?)^```$", text, re.MULTILINE | re.DOTALL):
        blocks.append((text.count("\n", 0, match.start()) + 2, match.group(1)))
    return blocks


def console_steps(body: str) -> list[tuple[str, str, int]]:
    """(command, expected output, expected exit status) of every ``$`` line of a console block."""
    steps: list[list] = []
    for line in body.splitlines():
        if line.startswith("$ echo $?"):
            steps[-1][3] = True
        elif line.startswith("$ "):
            steps.append([line[2:], [], 0, False])
        elif steps and steps[-1][3]:
            steps[-1][2] = int(line)
        else:
            steps[-1][1].append(line)
    return [(command, "\n".join(lines), status) for command, lines, status, _ in steps]


def normalised(text: str) -> str:
    """Trailing spaces and blank lines off (tables pad their last column)."""
    return "\n".join(line.rstrip() for line in text.rstrip().splitlines()) + "\n"


RUN = [README, DOCS / "commands.md"]
"""The pages whose examples are run (other pages show longer runs, measured once)."""
CONSOLE = [(page, line, body) for page in RUN
           for line, body in fenced_blocks(page.read_text(encoding="utf-8"), "console")]
PYCON = [(page, line, body) for page in RUN
         for line, body in fenced_blocks(page.read_text(encoding="utf-8"), "pycon")]


def test_the_readme_has_runnable_examples():
    """The README shows a refusal, the camera designer's commands, a render checked, and Python."""
    readme = [body for page, _, body in CONSOLE if page == README]
    commands = [command for body in readme for command, _, _ in console_steps(body)]
    assert len(commands) >= 4 and any(status == 2 for body in readme for _, _, status in console_steps(body))
    assert any(page == README for page, _, _ in PYCON)


@pytest.fixture
def command_line(tmp_path: Path) -> dict[str, str]:
    """An environment whose ``skinrender`` is this checkout's command line."""
    bin_folder = tmp_path / "bin"
    bin_folder.mkdir()
    script = bin_folder / "skinrender"
    script.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m skinrender "$@"\n', encoding="utf-8")
    script.chmod(0o755)
    python_path = os.pathsep.join(p for p in (str(REPOSITORY), os.environ.get("PYTHONPATH")) if p)
    return {**os.environ, "PATH": f"{bin_folder}{os.pathsep}{os.environ['PATH']}", "PYTHONPATH": python_path,
            "MPLBACKEND": "Agg"}


SHELL = re.compile(r"[|&;<>()`$*?~\\]")
"""What makes a command need the shell (a pipe, a redirection, a variable, a glob…)."""


def run_command(command: str, work: Path, env: dict[str, str], capfd, monkeypatch) -> tuple[int, str, str]:
    """``(status, stdout, stderr)`` of one console command run in ``work``. A plain ``skinrender …`` line (no shell
    syntax) runs in this process, its standard output and error captured at the file descriptors (so that a native
    library's writes count, as in a terminal): the same command line without starting Python and importing
    Mitsuba again for every line (``tests/test_cli.py`` runs the installed command in a child process); any other
    line runs in ``bash``."""
    words = shlex.split(command)
    if words[0] != "skinrender" or SHELL.search(command):
        run = subprocess.run(["bash", "-c", command], capture_output=True, text=True, cwd=work, env=env)
        return run.returncode, run.stdout, run.stderr
    from skinrender.cli import main

    with monkeypatch.context() as patch:
        patch.chdir(work)
        patch.setenv("MPLBACKEND", "Agg")
        capfd.readouterr()
        try:
            status = main(words[1:])
        except SystemExit as exit_:  # argparse's own refusals
            status = exit_.code
        out, err = capfd.readouterr()
    return (0 if status is None else status), out, err


@pytest.mark.parametrize("page, line, body", CONSOLE, ids=[f"{p.name}:{line}" for p, line, _ in CONSOLE])
def test_console_example(page, line, body, command_line, tmp_path, capfd, monkeypatch):
    """Each command of the block exits with the status shown and prints what is shown."""
    where = f"{page.name}:{line}"
    work = tmp_path / "work"
    work.mkdir()
    checker = doctest.OutputChecker()
    for command, expected, status in console_steps(body):
        returncode, stdout, stderr = run_command(command, work, command_line, capfd, monkeypatch)
        got = stdout if returncode == 0 else stderr
        assert returncode == status, f"{where}: `{command}` exited {returncode}:\n{stderr}"
        assert checker.check_output(normalised(expected), normalised(got), doctest.ELLIPSIS), (
            f"{where}: `{command}` printed\n{got}\ninstead of\n{expected}")


@pytest.mark.parametrize("page, line, body", PYCON, ids=[f"{page.name}:{line}" for page, line, _ in PYCON])
def test_python_example(page, line, body, tmp_path, monkeypatch):
    """The block as a doctest, in an empty folder."""
    monkeypatch.chdir(tmp_path)
    test = doctest.DocTestParser().get_doctest(body, {}, f"{page.name}:{line}", str(page), line - 1)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0, f"{page.name}:{line}: the output differs (the doctest report is above)"
