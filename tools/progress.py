"""Progress of long scripts (benchmarks, report generators, log checks) on standard error.

    progress = Progress(total=48, label="stability")
    for case in cases:
        run(case)
        progress.step(case.name)          # [stability] 7/48 done (E=1e9 10x), 1m12s elapsed, about 6m40s left
    progress.done()

The estimate of the time left is the mean time per finished unit times the units left; a caller
whose jobs differ much in size passes each job's weight (say, its number of steps) to step()
and the total weight to Progress. When the total is only approximate (a script whose number of
runs depends on its results), pass approximate=True: the line then says "of about N". Standard
output is never touched, so scripts whose stdout is parsed keep it; PERI_SISSM_QUIET=1 silences
the lines.
"""
from __future__ import annotations

import os
import sys
import time


def duration(seconds: float) -> str:
    """1h02m, 3m05s or 12s."""
    seconds = max(0, int(round(seconds)))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    if h:
        return f"{h}h{m:02d}m"
    if m:
        return f"{m}m{s:02d}s"
    return f"{s}s"


class Progress:
    def __init__(self, total: float | None, label: str, stream=None, clock=time.monotonic,
                 approximate: bool = False):
        self.total, self.label, self.approximate = total, label, approximate
        self.stream = stream if stream is not None else sys.stderr
        self.clock = clock
        self.start = clock()
        self.count = 0            # units finished
        self.weight = 0.0         # their weight
        self.weighted = False     # a weight other than 1 was given
        self.quiet = os.environ.get("PERI_SISSM_QUIET", "") not in ("", "0")

    def line(self, what: str = "") -> str:
        elapsed = self.clock() - self.start
        about = "~" if self.approximate else ""
        if self.total is None:
            text = f"[{self.label}] {self.count} done"
        elif self.weighted:    # jobs of different sizes: the share of the total weight
            text = (f"[{self.label}] {self.count} done, {about}"
                    f"{100.0 * min(self.weight / self.total, 1.0):.0f}%")
        else:
            text = f"[{self.label}] {self.count}/{about}{self.total:g} done"
        if what:
            text += f" ({what})"
        text += f", {duration(elapsed)} elapsed"
        if self.total is not None and self.weight > 0:
            left = max(self.total - self.weight, 0.0) * elapsed / self.weight
            if self.weight < self.total:
                text += f", about {duration(left)} left"
        return text

    def step(self, what: str = "", weight: float = 1.0) -> None:
        self.count += 1
        self.weight += weight
        self.weighted = self.weighted or weight != 1.0
        if not self.quiet:
            print(self.line(what), file=self.stream, flush=True)

    def done(self) -> None:
        if not self.quiet:
            elapsed = self.clock() - self.start
            print(f"[{self.label}] finished {self.count} in {duration(elapsed)}",
                  file=self.stream, flush=True)
