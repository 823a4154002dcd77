# Sphinx configuration of the PERI-SISSM manual: the style pages (in the format of the LAMMPS
# manual), the theory page and the reports. Build with  bash tools/docs.sh  (Debian's
# python3-sphinx and python3-myst-parser; tools/setup.sh installs them).
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "_ext"))

project = "PERI-SISSM"
author = "PERI-SISSM developers"
copyright = "2026, PERI-SISSM developers (GPL-2.0)"

extensions = ["lammps_manual", "sphinx.ext.mathjax", "myst_parser"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "_ext"]

# math: Debian's MathJax (libjs-mathjax) from the local disk, so pages read offline
mathjax_path = "file:///usr/share/javascript/mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML"
myst_heading_anchors = 3

html_theme = "alabaster"
html_title = "PERI-SISSM manual"
html_theme_options = {"description": "Peridynamics with SISSM for LAMMPS", "fixed_sidebar": True}
