"""Sphinx configuration of skinrender's documentation (MyST markdown pages, numpydoc, a bibliography).

Build it with ``sphinx-build -W -b html docs docs/_build/html`` (``pip install -e ".[docs]"``);
``tests/test_docs.py`` builds it warning-free in the test suite.
"""

from __future__ import annotations

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
REPOSITORY = DOCS.parent
sys.path.insert(0, str(REPOSITORY))

import skinrender  # noqa: E402  (the package of this checkout, for autodoc and the version)

project = "skinrender"
author = "skinrender developers"
copyright = "skinrender developers, BSD-3-Clause"
release = version = skinrender.__version__

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinxcontrib.bibtex",
]

source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3

# The API reference: one page per module, written at every build from the package itself
# (docs/_ext/api_pages.py; docs/api/ is not tracked), so that a new module appears without editing the docs.
sys.path.insert(0, str(DOCS / "_ext"))
from api_pages import write_api_pages  # noqa: E402

write_api_pages(DOCS / "api")
autodoc_default_options = {"members": True, "show-inheritance": False}
# Functions and classes stay out of the pages' tables of contents: no page shows them (every toctree has
# ``:maxdepth: 1``, the theme's sidebar shows no page-local contents; the HTML is the same either way), and the
# sidebar's navigation, resolved for every page, otherwise copies every API page's objects each time (~5 % of the
# build).
toc_object_entries = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"
# The package has no ``# type:`` comments (and shows no type hints): without this, autodoc reads every function's
# source again looking for them (~6 % of the build).
autodoc_use_type_comments = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_validation_checks: set[str] = set()

bibtex_bibfiles = ["references.bib"]
bibtex_default_style = "plain"
bibtex_reference_style = "author_year"

html_theme = "alabaster"
html_title = f"skinrender {release}"
html_static_path: list[str] = []

# Docstring markup in modules that other work was rewriting when the site was built
# (rendering/face_validation.py, rendering/validation.py, rendering/imaging.py, studies/benchmarks/bench_face.py) is
# mended here, at build time, rather than in the modules: each entry is (object's full name, text in its
# docstring, what the docs show instead). An entry whose text is no longer there does nothing; fix the module
# and remove the entry.
DOCSTRING_MENDS = [
    # |z| and |ΔNCC| read as substitution references
    ("skinrender.rendering.validation.Validation.worst", "|z|", r"\|z\|"),
    ("skinrender.studies.benchmarks.bench_face.PRESET_THRESHOLDS", "|ΔNCC|", r"\|ΔNCC\|"),
    # a numpydoc-style citation: the bibliography is cited with :cite:
    ("skinrender.rendering.imaging", "[EMVA1288]_", ":cite:`EMVA1288`"),
]


def mend_docstring(app, what, name, obj, options, lines):
    """Apply :data:`DOCSTRING_MENDS` to one docstring (autodoc-process-docstring)."""
    for target, old, new in DOCSTRING_MENDS:
        if name == target:
            lines[:] = [line.replace(old, new) for line in lines]


def numpydoc_with_one_template():
    """
    numpydoc compiles its Jinja template anew for every docstring it renders (``get_doc_object``): about a
    third of this build's time. Compile it once per builder and hand numpydoc the same template (the pages are
    the same).
    """
    import numpydoc.docscrape_sphinx as sphinx_docs
    import numpydoc.numpydoc

    templates = {}

    def get_doc_object(obj, what=None, doc=None, config=None, builder=None):
        config = {} if config is None else config
        if id(builder) not in templates:  # as numpydoc's own get_doc_object makes it
            folders = [str(Path(sphinx_docs.__file__).parent / "templates")]
            if builder is None:
                loader = sphinx_docs.FileSystemLoader(folders)
            else:
                loader = sphinx_docs.BuiltinTemplateLoader()
                loader.init(builder, dirs=folders)
            environment = sphinx_docs.SandboxedEnvironment(loader=loader)
            templates[id(builder)] = environment.get_template("numpydoc_docstring.rst")
        config["template"] = templates[id(builder)]
        return sphinx_docs.get_doc_object_orig(obj, what=what, doc=doc, config=config,
                                               class_doc=sphinx_docs.SphinxClassDoc,
                                               func_doc=sphinx_docs.SphinxFunctionDoc,
                                               obj_doc=sphinx_docs.SphinxObjDoc)

    numpydoc.numpydoc.get_doc_object = get_doc_object


def pybtex_plugins_found_once():
    """
    sphinxcontrib-bibtex looks its pybtex plugins up by name for every citation it resolves
    (``pybtex.plugin.find_plugin``), and each look-up reads every installed package's entry points (~3 ms). The
    plugins installed do not change during a build: look each up once.
    """
    import functools

    import pybtex.plugin

    if not hasattr(pybtex.plugin.find_plugin, "cache_info"):
        pybtex.plugin.find_plugin = functools.lru_cache(maxsize=None)(pybtex.plugin.find_plugin)


def search_words_stemmed_once():
    """
    The HTML search index stems every word of every page (``SearchEnglish.stem``, the Python Snowball stemmer):
    ~60 000 calls for a few thousand distinct words, ~9 % of the build under cProfile. A word's stem depends on the word
    alone: stem each distinct word once (the index is the same).
    """
    import functools

    from sphinx.search import en

    if getattr(en.SearchEnglish.stem, "stems_once", False):
        return
    stem = en.SearchEnglish.stem

    @functools.lru_cache(maxsize=None)
    def stem_of(language_stem, word):
        return stem(language_stem, word)

    def stem_once(self, word: str) -> str:
        return stem_of(self, word)

    stem_once.stems_once = True
    en.SearchEnglish.stem = stem_once


def log_records_only_when_shown(app):
    """
    Sphinx sets its logger to DEBUG whatever the verbosity and leaves the level to its handlers, so every debug
    message (one per event emitted, one per object autodoc imports: ~40 000 a build) becomes a log record that
    every handler then drops, ~3 % of the build under cProfile. Set the logger to the lowest level a handler
    shows at this verbosity (``sphinx.util.logging.setup``'s own map): the messages shown, warnings included, are
    the same.
    """
    import logging

    from sphinx.util.logging import NAMESPACE, VERBOSITY_MAP

    logging.getLogger(NAMESPACE).setLevel(VERBOSITY_MAP[max(app.verbosity, 0)])


GC_FIRST_GENERATION = 100_000
"""Allocations between two collections of the youngest objects in the build's process (Python's default: 700)."""


def fewer_garbage_collections():
    """
    A build makes millions of long-lived objects (docutils nodes, the environment) and few cycles to free: at
    Python's default threshold the cyclic collector runs every 700 allocations and keeps walking the growing
    older generations, ~16 % of the build's CPU (measured without a profiler). Collect the youngest generation every
    :data:`GC_FIRST_GENERATION` allocations instead (the pages are the same; the process holds a little more
    memory between collections).
    """
    import gc

    youngest, older, oldest = gc.get_threshold()
    gc.set_threshold(max(GC_FIRST_GENERATION, youngest), older, oldest)


OTHER_PAGES = "OTHER_PAGES"
"""The line of ``index.md``'s "Guides" toctree that stands for every page no toctree of ``index.md`` names."""


def other_pages(index_source: str) -> list[str]:
    """The pages of ``docs/*.md`` that ``index.md`` does not name (the guides features add), sorted."""
    named = {line.strip() for line in index_source.splitlines()}
    return sorted(p.stem for p in DOCS.glob("*.md") if p.stem != "index" and p.stem not in named)


def list_other_pages(app, docname, source):
    """Put the other pages in place of :data:`OTHER_PAGES` (source-read); with none, no caption shows."""
    if docname == "index":
        source[0] = source[0].replace(OTHER_PAGES, "\n".join(other_pages(source[0])))


def reread_index(app, env, added, changed, removed):
    """Read ``index.md`` at every build, so that a page added since the last is listed (env-get-outdated)."""
    return ["index"]


def setup(app):
    app.connect("autodoc-process-docstring", mend_docstring)
    app.connect("source-read", list_other_pages)
    app.connect("env-get-outdated", reread_index)
    numpydoc_with_one_template()
    pybtex_plugins_found_once()
    search_words_stemmed_once()
    log_records_only_when_shown(app)
    fewer_garbage_collections()
