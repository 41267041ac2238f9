"""Sphinx configuration of phasekit's documentation site.

Build (warnings are errors, as in tests/contracts/test_docs_site.py):

    python -m sphinx -W --keep-going -b html docs docs/_build/html

The build runs every example (the gallery) and the CLI commands whose JSON the CLI page
describes; ``-D pk_execute=0`` skips both for a quick look at the prose. Results pages read
their numbers from ``figures/`` and ``docs/data/`` (``-D pk_figures=DIR`` reads another copy).
"""

import os
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS.parent))
sys.path.insert(0, str(DOCS / "_ext"))
os.environ.setdefault("MPLBACKEND", "Agg")

project = "phasekit"
author = "phasekit developers"
extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.napoleon", "pkdocs"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "data", "_ext", "_generated"]
root_doc = "index"
html_theme = "alabaster"
html_static_path = []
html_theme_options = {"page_width": "1240px", "sidebar_width": "230px", "body_max_width": "none"}

# Markdown pages (MyST): headings get anchors for links within and across pages
myst_enable_extensions = ["colon_fence"]
myst_heading_anchors = 3

# numpydoc-style docstrings, read by napoleon
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_custom_sections = [("Required of a subclass", "params_style")]
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_class_signature = "separated"
suppress_warnings = ["ref.python"]  # several modules re-export the same names

# pkdocs (docs/_ext/pkdocs): where the generated pages read their data, and whether the build
# runs the examples and the CLI
pk_figures = ""      # default: figures/
pk_data = ""         # default: docs/data/
pk_execute = True
pk_jobs = 2


# phasekit's docstrings write absolute values as |u|; in reStructuredText |u| would be a
# substitution reference. Escape such bars (outside inline literals) before parsing.
_BARS = re.compile(r"(?<![\\|`])\|(?=[^\s|])([^|`\n]*?[^\s|])\|(?![|_`])")


def _escape_bars(app, what, name, obj, options, lines):
    for i, line in enumerate(lines):
        if line.lstrip().startswith((">>>", "...")):
            continue
        # the pieces between ``inline literals`` (even places after a split on ``) are text
        pieces = line.split("``")
        lines[i] = "``".join(_BARS.sub(lambda m: "\\|" + m.group(1) + "\\|", p) if k % 2 == 0 else p
                             for k, p in enumerate(pieces))


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
