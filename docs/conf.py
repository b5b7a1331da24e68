"""Sphinx configuration of the API reference (``docs/index.rst``, ``docs/api/``).

Build (the ``docs`` extra installs Sphinx and numpydoc)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

Only the reStructuredText pages are sources; the Markdown guides beside them are
read on their own (GitHub renders them) and are not part of this build.
"""

import os
import sys

# the package from this checkout, also when it is not installed
sys.path.insert(0, os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "src")))
os.environ.setdefault("MPLBACKEND", "Agg")

project = "rotorkin"
author = "rotorkin developers"
copyright = "rotorkin developers"  # noqa: A001

extensions = ["sphinx.ext.autodoc", "numpydoc"]

source_suffix = {".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "img", "**/*.md"]

# autodoc: members in the order of the source, the signature's annotations shown once
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "signature"
autodoc_class_signature = "mixed"
add_module_names = False

# numpydoc renders the Parameters / Returns / Attributes sections; the class member
# tables it can add would need autosummary stubs written into the source tree
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

html_theme = "alabaster"
html_title = "rotorkin API reference"
html_static_path: list[str] = []
html_show_sourcelink = False
