"""Sphinx configuration: the API reference generated from phasekit's numpydoc docstrings.

Build (warnings are errors, as in tests/test_docs.py):

    python -m sphinx -W --keep-going -b html docs docs/_build/html
"""

import os
import re
import sys

sys.path.insert(0, os.path.abspath(".."))
os.environ.setdefault("MPLBACKEND", "Agg")

project = "phasekit"
author = "phasekit developers"
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon"]
exclude_patterns = ["_build", "physics.md"]  # the physics notes are Markdown, read on their own
root_doc = "index"
html_theme = "alabaster"
html_static_path = []

# numpydoc-style docstrings, read by napoleon
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_custom_sections = [("Required of a subclass", "params_style")]
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "description"
autodoc_class_signature = "separated"
suppress_warnings = ["ref.python"]  # several modules re-export the same names


# phasekit's docstrings write absolute values as |u|; in reStructuredText |u| would be a
# substitution reference. Escape such bars (outside inline literals) before parsing.
_BARS = re.compile(r"(?<![\\|`])\|(?=[^\s|])([^|`\n]*?[^\s|])\|(?![|_`])")


def _escape_bars(app, what, name, obj, options, lines):
    for i, line in enumerate(lines):
        if "``" in line or line.lstrip().startswith((">>>", "...")):
            continue
        lines[i] = _BARS.sub(lambda m: "\\|" + m.group(1) + "\\|", line)


def setup(app):
    app.connect("autodoc-process-docstring", _escape_bars)
