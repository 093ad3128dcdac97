"""Side by side: closurelab's direct SPH against PySPH, interleaved A, B, A, B ... per size and thread count,
printing each pair's ratio (PySPH seconds per step / closurelab seconds per step) and their spread. Two scenes:
  poiseuille  (the default) the PySPH peer model (tests/peer/poiseuille_pysph.py) on the same square box of the
              poiseuille-uniform scene (n_x = n_y), standard WCSPH;
  cavity      PySPH's own lid-driven cavity (pysph/examples/cavity.py: TVFScheme, the generalized wall condition)
              against closurelab's lid-driven-cavity scene under the transport-velocity formulation, n fluid
              particles per side; the two engines give the same particles to round-off (tests/peer/
              test_cavity_peer.cpp).

  /usr/bin/python3 scripts/peer_bench.py [--closurelab build/experiments/closurelab] [--scene poiseuille|cavity]
                                         [--sizes 48 96] [--threads 1 2] [--pairs 3] [--steps 200] [--out FILE]
                                         [--control OTHER_CLOSURELAB]

--control runs a second closurelab build (e.g. of the commit before an engine change) in every pair as well,
right after the first (A, A', B), and prints its ratio and the speed-up A'/A beside the first's: an engine
change measured against its predecessor under the same load.

What is timed: closurelab's SPH run (the row's cost.wall_seconds: the time loop, not the process start, the
scene set-up or the averaging), and PySPH's "Run took" (its solver loop with the first and last dump, not the
start of Python, the particle set-up or the compile of the equations, which is cached after the first run).
Both run the same steps on the same particles: t = steps x 0.25 eps'^2 (poiseuille), steps x the cavity's acoustic
step 0.25 h / (c0 + U) (cavity, h = eps' = L/n, c0 = 10 U: PySPH's and closurelab's step there). PySPH runs serial on one thread (its
fastest there) and --openmp with OMP_NUM_THREADS on more, with --cache-nnps (its neighbours found once per
evaluation and reused by the three equation groups: PySPH's best case); closurelab with OMP_NUM_THREADS.
The machine is shared: record `uptime` with the results, and read the ratios of one pair, A and B seconds
apart, rather than either time alone.
"""

import argparse
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
peer = os.path.join(root, "tests", "peer", "poiseuille_pysph.py")


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "(uptime not available)"


def step_size(scene, n):
    if scene == "cavity":  # PySPH's cavity.py: dt = 0.25 h / (c0 + Umax), h = dx = L / n, c0 = 10, Umax = 1
        return 0.25 * (1.0 / n) / 11.0
    return 0.25 * (1.0 / n) ** 2


def run_closurelab(exe, scene, ny, steps, threads, work):
    t = steps * step_size(scene, ny)
    solver = {"mode": "target_time", "target_time": t, "max_time": t}
    if scene == "cavity":
        solver["formulation"] = "transport_velocity"
        scene_section = {"name": "lid-driven-cavity", "n": ny}
    else:
        scene_section = {"name": "poiseuille-uniform", "n_y": ny, "n_x": ny}
    spec = {"name": "bench", "kind": "direct_sph_validation",
            "base": {"scene": scene_section, "kernel": {"name": "gaussian"}, "solver": solver}}
    d = tempfile.mkdtemp(dir=work)
    with open(os.path.join(d, "spec.json"), "w") as f:
        json.dump(spec, f)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    p = subprocess.run([exe, "run", os.path.join(d, "spec.json"), "--out", os.path.join(d, "out"), "--store",
                        os.path.join(d, "store"), "--force"], capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise SystemExit("closurelab failed:\n" + p.stderr[-3000:])
    with open(os.path.join(d, "out", "bench.json")) as f:
        row = json.load(f)["rows"][0]
    shutil.rmtree(d, ignore_errors=True)
    cost = row["cost"]
    sph = cost.get("direct_sph", cost)
    return float(sph["wall_seconds"]), int(sph["steps"]), float(sph["particle_steps"])


def run_pysph(scene, ny, steps, threads, work):
    d = tempfile.mkdtemp(dir=work)
    tf = repr(steps * step_size(scene, ny))
    if scene == "cavity":
        # cavity.py's application run as written, without its post-processing (outside the timing anyway).
        cmd = [sys.executable, "-c", "from pysph.examples.cavity import LidDrivenCavity as A; A().run()", "--nx",
               str(ny), "--tf", tf, "-d", d, "--cache-nnps"]
    else:
        cmd = [sys.executable, peer, "--ny", str(ny), "--nx", str(ny), "--tf", tf, "-d", d, "--cache-nnps"]
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    if threads > 1:
        cmd.append("--openmp")
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=work)
    if p.returncode != 0:
        raise SystemExit("PySPH failed:\n" + p.stdout[-3000:] + p.stderr[-3000:])
    m = re.search(r"Run took: ([0-9.eE+-]+) secs", p.stdout)
    last = max(int(f.rsplit("_", 1)[1].split(".")[0]) for f in os.listdir(d) if f.endswith((".hdf5", ".npz")))
    shutil.rmtree(d, ignore_errors=True)
    return float(m.group(1)), last  # the last dump is named by its iteration: the steps run


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--closurelab", default=os.path.join(root, "build", "experiments", "closurelab"))
    ap.add_argument("--scene", choices=["poiseuille", "cavity"], default="poiseuille")
    ap.add_argument("--sizes", type=int, nargs="+", default=[48, 96])
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--out", help="also write the report to this file")
    ap.add_argument("--control", help="a second closurelab build, run in every pair right after the first")
    a = ap.parse_args()

    lines = []

    def say(s):
        print(s, flush=True)
        lines.append(s)

    commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                           text=True).stdout.strip()
    say("# peer benchmark: closurelab (A) against PySPH (B), %s" % (
        "the lid-driven cavity (transport velocity; PySPH's cavity.py)" if a.scene == "cavity"
        else "the PySPH peer model on a square box of poiseuille-uniform"))
    say("# command: %s %s" % (sys.executable, " ".join(sys.argv)))
    say("# commit %s%s; %s; python %s; %s" % (commit, " (dirty)" if dirty else "", platform.node(),
                                              platform.python_version(), date()))
    say("# cpu: %s, %d logical cores" % (cpu_model(), os.cpu_count()))
    if a.control:
        say("# control (A'): %s" % os.path.abspath(a.control))
    say("# load before: %s" % uptime())
    work = tempfile.mkdtemp(prefix="closurelab_peer_bench_")
    try:
        # PySPH's compile (cached afterwards) outside the timings.
        for t in sorted(set(a.threads)):
            run_pysph(a.scene, a.sizes[0], 2, t, work)
        summary = []
        for ny in a.sizes:
            for t in a.threads:
                ratios, control_ratios, speed_ups = [], [], []
                say("n_y = n_x = %d (%d fluid particles), %d thread(s), %d steps:" % (ny, ny * ny, t, a.steps))
                for k in range(a.pairs):
                    ca, steps, particle_steps = run_closurelab(a.closurelab, a.scene, ny, a.steps, t, work)
                    cc = run_closurelab(a.control, a.scene, ny, a.steps, t, work)[0] if a.control else None
                    pb, pysph_steps = run_pysph(a.scene, ny, a.steps, t, work)
                    if pysph_steps != steps:
                        raise SystemExit("step counts differ: closurelab %d, PySPH %d" % (steps, pysph_steps))
                    r = pb / ca
                    ratios.append(r)
                    say("  pair %d: closurelab %.4f s (%.3g particle-steps/s), PySPH %.4f s: ratio %.2f"
                        % (k + 1, ca, particle_steps / ca, pb, r))
                    if cc is not None:
                        control_ratios.append(pb / cc)
                        speed_ups.append(cc / ca)
                        say("          control %.4f s (%.3g particle-steps/s): ratio %.2f; A'/A %.2f"
                            % (cc, particle_steps / cc, pb / cc, cc / ca))
                med = statistics.median(ratios)
                say("  ratio median %.2f, range %.2f-%.2f (%d pairs)" % (med, min(ratios), max(ratios), len(ratios)))
                if control_ratios:
                    say("  control ratio median %.2f, range %.2f-%.2f; A'/A median %.2f, range %.2f-%.2f"
                        % (statistics.median(control_ratios), min(control_ratios), max(control_ratios),
                           statistics.median(speed_ups), min(speed_ups), max(speed_ups)))
                summary.append((ny, t, med, min(ratios), max(ratios)))
        say("# summary (PySPH time / closurelab time per step, same particles and steps):")
        for ny, t, med, lo, hi in summary:
            say("#   n_y = %d, %d thread(s): %.2f (%.2f-%.2f)" % (ny, t, med, lo, hi))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    say("# load after: %s" % uptime())
    if a.out:
        with open(a.out, "w") as f:
            f.write("\n".join(lines) + "\n")


def date():
    return time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime())


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


if __name__ == "__main__":
    main()
