"""tools/progress.py: the estimate of the time left (mean time per unit of weight times the
weight left), its format, and PERI_SISSM_QUIET. A fake clock: no sleeping, no wall time."""
import io
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
from progress import Progress, duration  # noqa: E402


class Clock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_estimate_is_mean_time_per_unit_times_what_is_left(monkeypatch):
    monkeypatch.delenv("PERI_SISSM_QUIET", raising=False)
    clock, out = Clock(), io.StringIO()
    p = Progress(total=4, label="bench", stream=out, clock=clock)
    clock.now += 30
    p.step("first")
    clock.now += 90                  # 2 done in 120 s: 60 s each, 2 left
    p.step("second")
    p.done()
    lines = out.getvalue().splitlines()
    assert lines[0] == "[bench] 1/4 done (first), 30s elapsed, about 1m30s left"
    assert lines[1] == "[bench] 2/4 done (second), 2m00s elapsed, about 2m00s left"
    assert lines[2] == "[bench] finished 2 in 2m00s"


def test_weights_and_approximate_totals(monkeypatch):
    monkeypatch.delenv("PERI_SISSM_QUIET", raising=False)
    clock, out = Clock(), io.StringIO()
    p = Progress(total=1000, label="runs", stream=out, clock=clock, approximate=True)
    clock.now += 100
    p.step("short", weight=250)      # 100 s for 250 of 1000: 300 s left
    assert out.getvalue().splitlines()[-1] == \
        "[runs] 1 done, ~25% (short), 1m40s elapsed, about 5m00s left"
    clock.now += 3700
    p.step(weight=750)                # all the weight done: no estimate
    assert out.getvalue().splitlines()[-1] == "[runs] 2 done, ~100%, 1h03m elapsed"
    counted = Progress(total=10, label="c", stream=out, clock=clock, approximate=True)
    counted.step()
    assert out.getvalue().splitlines()[-1] == "[c] 1/~10 done, 0s elapsed, about 0s left"
    unknown = Progress(total=None, label="x", stream=out, clock=clock)
    unknown.step("y")
    assert out.getvalue().splitlines()[-1] == "[x] 1 done (y), 0s elapsed"


def test_quiet_switch(monkeypatch):
    monkeypatch.setenv("PERI_SISSM_QUIET", "1")
    out = io.StringIO()
    p = Progress(total=2, label="q", stream=out, clock=Clock())
    p.step("a")
    p.done()
    assert out.getvalue() == ""


def test_duration_format():
    assert [duration(s) for s in (0, 59.6, 61, 3599, 3600, 7384)] == \
        ["0s", "1m00s", "1m01s", "59m59s", "1h00m", "2h03m"]
