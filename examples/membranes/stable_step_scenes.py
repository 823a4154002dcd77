#!/usr/bin/env python3
"""fix nve at 0.9 times the stable-step estimate on every bending scene of examples/:

    python3 stable_step_scenes.py [--lmp ../../build/lmp] [--steps 2000] [--factor 0.9]
        [--only WORD ...]

Each scene's deck runs as shipped up to its first `run` command (meshes, pair, contact, walls,
gravity, held groups), in a copy of its folder. Then its integrator (the fix with ID
`integrate`) is replaced by fix nve on the same group, the time step set to 0.9 times the
smallest column 11 of compute nosb/atom over that group (the pair's estimate, with the bending
stiffness; doc/compute_nosb_atom.rst), and the scene runs that many steps. A run is stable when
it ends without an error (peri/nosb's blow-up guard stops runs whose particles run away) and no
particle of the group moved faster than 100 m/s (the scenes' own motions reach 21 m/s: the
twisted strip snaps through at 0.13 s, as fast with a step three times shorter; an unstable
explicit run grows exponentially, by many decades within a few hundred steps). A deck with fix move (the twisting cloth) cannot change its time step after the fix is
defined: it runs twice, the second time with its own `dt` variable set to the step.

The estimate is the pair's: it does not hold the contact barrier of fix nosb/contact, whose
stiffness grows without bound as two primitives approach dmin. A run that fix nosb/contact stops
because primitives came through its barrier (explicit steps have no continuous collision
detection) is reported as such ("contact"), not as unstable.

Prints one row per scene: the estimate, the largest speed, and whether peri/nosb warned about
the time step (it must not: the step is below its own estimate).
"""
import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
EXAMPLES = HERE.parent

# (name, folder, deck, extra -var pairs[, most steps])
SCENES = [
    ("tablecloth D 1e-3", "tablecloth", "in.tablecloth", ["bend", "1e-3"]),
    ("tablecloth D 1e-4", "tablecloth", "in.tablecloth", ["bend", "1e-4"]),
    ("tablecloth D 1e-5", "tablecloth", "in.tablecloth", ["bend", "1e-5"]),
    ("tablecloth no bend", "tablecloth", "in.tablecloth", ["bend", "no"]),
    ("hanging cloth", "hanging-cloth", "in.hanging", []),
    ("cloth on a ball", "cloth-on-ball", "in.cloth-on-ball", []),
    # (kappa 100: the deck's own advice for explicit steps, whose barrier has no CCD)
    ("twisting cloth", "twisting-cloth", "in.twisting-cloth", ["dt", None, "kappa", "100"]),
    ("two cloths", "contact", "in.two-cloths", []),
    # (the deck's 0.03 s: later the cloth leaves the box; kappa 10: explicit steps have no CCD)
    ("thrown cloth", "contact", "in.thrown-cloth", ["kappa", "10"], 430),
    ("viewing", "viewing", "in.view", []),
    ("plate (hinge)", "membranes", "in.plate", []),
    ("plate, alternate", "membranes", "in.plate-alternate", []),
]

TAIL = """
unfix           integrate
fix             integrate {group} nve
compute         ssn {group} nosb/atom
compute         ssmin {group} reduce min c_ssn[11]
variable        ssspeed atom sqrt(vx*vx+vy*vy+vz*vz)
compute         ssv {group} reduce max v_ssspeed
thermo_style    custom step pe ke c_ssmin
thermo          0
{tiny}
run             0 post no
variable        ssdt equal {factor}*$(c_ssmin:%.10g)
print           "ESTIMATE $(c_ssmin:%.10g)"
{timestep}
thermo_style    custom step pe ke c_ssv
thermo_modify   norm no
thermo          {every}
run             {steps} post no
print           "DONE"
"""


def cut_at_first_run(text):
    lines = text.splitlines()
    for k, line in enumerate(lines):
        if re.match(r"^\s*run\s", line):
            return "\n".join(lines[:k]) + "\n"
    raise ValueError("no run command")


def integrate_group(text):
    m = re.search(r"fix\s+integrate\s+(\S+)\s", text)
    if not m:
        raise ValueError("no fix with ID integrate")
    return m.group(1)


def run_scene(lmp, folder, deck, variables, steps, factor, workdir):
    src = EXAMPLES / folder
    dst = Path(workdir) / folder
    shutil.copytree(src, dst, ignore=shutil.ignore_patterns("*.png", "*.gif", "*.svg", "log.*"))
    text = (src / deck).read_text()
    group = integrate_group(text)

    def run(variables, fixed_step, steps):
        body = cut_at_first_run(text) + TAIL.format(
            group=group, steps=steps, factor=factor, every=max(1, steps // 20),
            tiny="" if fixed_step else "timestep        1e-12",
            timestep="" if fixed_step else "timestep        ${ssdt}")
        (dst / "in.stable").write_text(body)
        args = [str(lmp), "-in", "in.stable", "-log", "log.stable"]
        for k in range(0, len(variables), 2):
            args += ["-var", variables[k], variables[k + 1]]
        return subprocess.run(args, cwd=dst, capture_output=True, text=True)

    if "dt" in variables[::2]:
        # the deck's own dt: the estimate from a first run of zero steps (fix move's deck
        # allows its time step to be set before the fix only)
        k = variables.index("dt")
        first = run(variables[:k] + variables[k + 2:], True, 0)
        est = float(re.search(r"^ESTIMATE (\S+)", first.stdout, re.M).group(1))
        variables = variables[:k] + ["dt", f"{factor * est:.10g}"] + variables[k + 2:]
        out = run(variables, True, steps)
    else:
        out = run(variables, False, steps)
    log = out.stdout
    est = re.search(r"^ESTIMATE (\S+)", log, re.M)
    ratios = []
    reading = False
    for line in log.splitlines():
        words = line.split()
        if words[:1] == ["Step"] and "c_ssv" in words:
            reading, col = True, words.index("c_ssv")
            continue
        if reading:
            if len(words) > col and re.match(r"^\d+$", words[0]):
                ratios.append(float(words[col]))
            elif line.startswith("Loop time") or line.startswith("ERROR"):
                reading = False
    error = next((ln for ln in log.splitlines() if ln.startswith("ERROR")), "")
    warned = any("peri/nosb: timestep" in ln for ln in log.splitlines())
    done = "DONE" in log and out.returncode == 0
    contact = "came through the barrier" in error or "came through its barrier" in error
    return {"estimate": float(est.group(1)) if est else float("nan"), "contact": contact,
            "worst": max(ratios) if ratios else float("nan"), "done": done,
            "error": error or (out.stderr.strip()[-300:] if not done else ""), "warned": warned}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--lmp", default=str(EXAMPLES.parent / "build" / "lmp"))
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--factor", type=float, default=0.9,
                    help="the time step over the estimate (above 1 shows the check can fail)")
    ap.add_argument("--only", nargs="+", help="scene names containing any of these words")
    args = ap.parse_args()
    scenes = [s for s in SCENES if not args.only or any(w in s[0] for w in args.only)]
    print(f"{'scene':22s} {'estimate (s)':>13s} {'max speed':>13s}  stable   warned")
    bad = 0
    with tempfile.TemporaryDirectory() as tmp:
        for k, (name, folder, deck, variables, *most) in enumerate(scenes):
            steps = min([args.steps] + most)
            r = run_scene(args.lmp, folder, deck, variables, steps, args.factor,
                          Path(tmp) / str(k))
            stable = r["done"] and r["worst"] < 100.0
            verdict = "yes" if stable else ("contact" if r["contact"] else "NO")
            bad += verdict == "NO" or r["warned"]
            print(f"{name:22s} {r['estimate']:13.4g} {r['worst']:13.3g}  "
                  f"{verdict:7s}  {'yes' if r['warned'] else 'no'}", flush=True)
            if r["error"]:
                print(f"    {r['error']}", flush=True)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
