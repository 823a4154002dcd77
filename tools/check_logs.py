#!/usr/bin/env python3
"""Rerun the example decks that have reference logs and compare their thermo output.

Each examples/<scene>/log.<date>.<name>.g++.<N> was written by `lmp -in in.<name>` on N MPI
ranks in that folder. This reruns every such deck of peri/nosb or fix sissm (decks that use
only LAMMPS's built-in styles are skipped: this package cannot change them) with build/lmp and
compares every thermo row with the log's, column by column, as printed; the cpu column
(wall time) is ignored. Exit status 0 when every compared deck reproduces its log.

    python3 tools/check_logs.py [--lmp build/lmp] [--only SUBSTRING] [--update]

--update replaces each log that did not reproduce by its rerun, named with today's date
(log.<ddMonyy>.<name>.g++.<N>, as LAMMPS's own examples are), removes the old one and rewrites
the references to its name in the repository's text files; it prints each rename. Whether the
differences are round-off is for the one who runs it to judge (compare the two logs first).
"""
import argparse
import datetime
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
from progress import Progress  # noqa: E402
IGNORED = {"cpu", "cpuremain", "spcpu"}


def thermo_rows(text):
    """(header, rows) of every thermo table, rows as lists of printed strings."""
    tables = []
    header = None
    for line in text.splitlines():
        words = line.split()
        if words and words[0] == "Step":
            header = words
            tables.append((header, []))
            continue
        if header is not None:
            if len(words) == len(header) and re.match(r"^-?\d+$", words[0]):
                tables[-1][1].append(words)
            elif line.startswith("Loop time"):
                header = None
    return tables


def compare(ref, new):
    if len(ref) != len(new):
        return f"{len(ref)} thermo tables in the log, {len(new)} in the rerun"
    for t, ((h1, r1), (h2, r2)) in enumerate(zip(ref, new)):
        if h1 != h2:
            return f"table {t}: header {h1} != {h2}"
        if len(r1) != len(r2):
            return f"table {t}: {len(r1)} rows in the log, {len(r2)} in the rerun"
        keep = [k for k, name in enumerate(h1) if name.lower() not in IGNORED]
        for a, b in zip(r1, r2):
            for k in keep:
                if a[k] != b[k]:
                    return f"table {t} step {a[0]}: {h1[k]} {a[k]} (log) != {b[k]} (rerun)"
    return None


def uses_package(deck):
    text = deck.read_text()
    return "peri/nosb" in text or "sissm" in text or "include" in text and any(
        "peri/nosb" in (deck.parent / m).read_text() or "sissm" in (deck.parent / m).read_text()
        for m in re.findall(r"^include\s+(\S+)", text, re.M)
        if (deck.parent / m).exists())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lmp", default=str(ROOT / "build" / "lmp"))
    ap.add_argument("--only", default="", help="only logs whose path contains this")
    ap.add_argument("--update", action="store_true",
                    help="replace the logs that did not reproduce by their reruns")
    args = ap.parse_args()
    renames = []
    runs = []
    for log in sorted(ROOT.glob("examples/*/log.*.g++.*")):
        m = re.match(r"log\.[^.]+\.(.+)\.g\+\+\.(\d+)$", log.name)
        if args.only not in str(log) or not m:
            continue
        deck = log.parent / f"in.{m.group(1)}"
        if deck.exists() and uses_package(deck):
            runs.append((log, deck, int(m.group(2))))
    failed = 0
    done = 0
    progress = Progress(len(runs), "check_logs")
    for log, deck, ranks in runs:
        with tempfile.TemporaryDirectory() as tmp:
            work = pathlib.Path(tmp) / log.parent.name
            shutil.copytree(log.parent, work)
            cmd = [args.lmp, "-in", deck.name, "-log", "log.rerun", "-screen", "none"]
            if ranks > 1:
                cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + cmd
            proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True)
            rerun = (work / "log.rerun").read_text() if (work / "log.rerun").exists() else ""
        done += 1
        problem = (f"exit {proc.returncode}: {proc.stderr.strip()[-300:]}" if proc.returncode
                   else compare(thermo_rows(log.read_text()), thermo_rows(rerun)))
        if problem is not None and args.update and not proc.returncode:
            renames.append((log, update(log, rerun)))
        status = "SAME" if problem is None else "DIFFERENT"
        failed += problem is not None
        print(f"{status:9s} {log.relative_to(ROOT)}" + ("" if problem is None else f": {problem}"),
              flush=True)
        progress.step(log.name)
    print(f"{done - failed} of {done} logs reproduced")
    if renames:
        rewrite_references(renames)
        for old, new in renames:
            print(f"updated {old.relative_to(ROOT)} -> {new.name}")
    # with --update only the reruns that could not replace their log (a deck that failed) count
    return 1 if failed > len(renames) else 0


def update(log, rerun):
    """Write rerun as today's log of the same deck and rank count; remove the old log."""
    m = re.match(r"log\.[^.]+\.(.+\.g\+\+\.\d+)$", log.name)
    new = log.parent / f"log.{datetime.date.today().strftime('%d%b%y')}.{m.group(1)}"
    log.unlink()
    new.write_text(rerun)
    return new


def rewrite_references(renames):
    """Old log names replaced by the new ones in the repository's tracked text files."""
    tracked = subprocess.run(["git", "ls-files"], cwd=ROOT, capture_output=True,
                             text=True).stdout.split()
    for name in tracked:
        path = ROOT / name
        if path.suffix not in (".md", ".rst", ".py", ".sh", ".txt") and path.name != "README":
            continue
        if not path.exists():
            continue
        text = path.read_text(errors="replace")
        new_text = text
        for old, new in renames:
            new_text = new_text.replace(old.name, new.name)
        if new_text != text:
            path.write_text(new_text)


if __name__ == "__main__":
    sys.exit(main())
