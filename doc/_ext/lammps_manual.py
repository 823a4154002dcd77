"""Sphinx support for pages written in the format of the LAMMPS manual.

- ``:doc:`` links to pages of the LAMMPS manual (``:doc:`fix nve <fix_nve>```) that are not
  pages of this project become links to https://docs.lammps.org/<target>.html;
- ``.. code-block:: LAMMPS`` gets a small lexer for input scripts (commands, comments,
  variables, numbers).
"""
from docutils import nodes
from pygments.lexer import RegexLexer, bygroups
from pygments.token import Comment, Keyword, Name, Number, Text

LAMMPS_MANUAL = "https://docs.lammps.org/"


class LammpsLexer(RegexLexer):
    name = "LAMMPS"
    aliases = ["lammps"]
    tokens = {
        "root": [
            (r"#.*?$", Comment.Single),
            (r"^(\s*)([a-z_/]+)", bygroups(Text, Keyword)),
            (r"\$\{[^}]*\}|\$\([^)]*\)|v_\w+|c_\w+|f_\w+", Name.Variable),
            (r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?\b", Number),
            (r"\s+", Text),
            (r"[^\s#$]+", Text),
            (r"\$", Text),
        ]
    }


def lammps_manual_link(app, env, node, contnode):
    """A :doc: target that is not one of our pages: a link into the LAMMPS manual."""
    if node.get("refdomain") != "std" or node.get("reftype") != "doc":
        return None
    target = node["reftarget"]
    if target in env.found_docs:
        return None
    ref = nodes.reference("", "", internal=False, refuri=f"{LAMMPS_MANUAL}{target}.html",
                          reftitle=f"LAMMPS manual: {target}")
    ref += contnode
    return ref


def setup(app):
    app.add_lexer("LAMMPS", LammpsLexer)
    app.connect("missing-reference", lammps_manual_link)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
