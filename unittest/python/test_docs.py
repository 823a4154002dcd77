"""The HTML manual builds with Sphinx (Debian's python3-sphinx and python3-myst-parser, which
tools/setup.sh installs) with warnings as errors, and no internal link of it is broken: every
relative href or src points to a file of the build, and every #fragment to an id in its page
(the Sphinx build runs in the full tier, bash tools/test.sh --full). The project's docs state
what the code does and what was measured, not the story of the work."""
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import pytest

REPO = Path(__file__).resolve().parents[2]
PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable


class Links(HTMLParser):
    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        for key in ("id", "name"):
            if attrs.get(key):
                self.ids.add(attrs[key])
        for key in ("href", "src"):
            if attrs.get(key) is not None:
                self.links.append(attrs[key])


def parse(page: Path) -> Links:
    links = Links()
    links.feed(page.read_text(errors="replace"))
    return links


# Narration of the work's history (its numbered sessions and issues), which belongs in commit
# messages, not in the docs
NARRATION = [r"\bsessions? \d+", r"\bissues? \d+", r"\bsince (session|issue)", r"\bpreviously\b",
             r"\bsince then\b"]


def project_docs():
    """README.md, doc/ (pages and reports) and every README.md under examples/."""
    return ([REPO / "README.md"] + sorted((REPO / "doc").rglob("*.rst"))
            + sorted((REPO / "doc").rglob("*.md")) + sorted((REPO / "examples").rglob("README.md")))


def narration(text: str) -> list:
    return [f"{n}: {line.strip()}" for n, line in enumerate(text.splitlines(), 1)
            if any(re.search(p, line, re.IGNORECASE) for p in NARRATION)]


def test_the_narration_patterns_find_narration():
    assert narration("Since session 17 the fused passes\nissue 13 acceptance\nok\n") == \
        ["1: Since session 17 the fused passes", "2: issue 13 acceptance"]
    assert narration("as previously measured") and narration("Since then the loops")
    assert not narration("at step 20 the run stops; since the step is implicit, ...")


def test_docs_hold_no_numbered_history():
    docs = project_docs()
    assert len(docs) > 10 and REPO / "examples" / "benchmarks" / "speed" / "README.md" in docs
    hits = [f"{path.relative_to(REPO)}:{hit}" for path in docs
            for hit in narration(path.read_text(errors="replace"))]
    assert not hits, "\n".join(hits)


@pytest.fixture(scope="module")
def html(tmp_path_factory):
    probe = subprocess.run([PYTHON, "-c", "import sphinx, myst_parser"], capture_output=True)
    if probe.returncode != 0:
        # not a skip: tools/setup.sh installs them, and a missing install step must show
        pytest.fail("python3-sphinx / python3-myst-parser not installed: run bash tools/setup.sh")
    out = tmp_path_factory.mktemp("html")
    proc = subprocess.run(["bash", str(REPO / "tools" / "docs.sh"), str(out)],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stderr == "", proc.stderr    # -W: any warning would have failed the build
    yield out
    shutil.rmtree(out, ignore_errors=True)


@pytest.mark.full
def test_every_page_is_built(html):
    for page in ["index", "pair_peri_nosb", "fix_sissm", "compute_nosb_atom", "read_mesh", "theory",
                 "reports/error-vs-time", "reports/stability"]:
        assert (html / f"{page}.html").is_file(), page


@pytest.mark.full
def test_links_to_the_lammps_manual_resolve_to_it(html):
    links = parse(html / "pair_peri_nosb.html").links
    assert "https://docs.lammps.org/pair_peri.html" in links    # :doc:`peri/lps <pair_peri>`
    assert "compute_nosb_atom.html" in links                   # our own pages stay internal


@pytest.mark.full
def test_no_broken_internal_link(html):
    pages = {page: parse(page) for page in html.rglob("*.html")}
    broken = []
    for page, links in pages.items():
        for link in links.links:
            parts = urlsplit(link)
            if parts.scheme or parts.netloc or link.startswith("//"):
                continue    # http(s), mailto, the local MathJax (file:)
            target = page if not parts.path else (page.parent / unquote(parts.path)).resolve()
            if not target.exists():
                broken.append(f"{page.relative_to(html)}: {link}")
                continue
            if parts.fragment and target.suffix == ".html":
                ids = pages[target].ids if target in pages else parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append(f"{page.relative_to(html)}: {link} (no such anchor)")
    assert not broken, "\n".join(broken)
