"""One adb-demo run of the budget sweep: its command, running it, and its summary.

A run writes DIR/steps.csv (adb-demo --out), DIR/stdout.txt, DIR/command.txt and, once it
has finished, DIR/run.json (wall time, load average). A run whose directory already holds
the same command and a run.json is reused, not repeated (`reuse=False` repeats it).
"""

import csv
import json
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from typing import List, Optional

# Steps from which the pile has formed (bodies dropped from up to 5.5 m have landed): the
# window over which the need and exact mode's time are averaged.
SETTLED_FROM = 100
# Frames at the end over which settling is judged (1 s at 1/60 s): one step's kinetic energy
# is one body's bounce.
LAST_SECOND = 60


@dataclass
class RunSpec:
    scene: str            # scene key (budget_sweep.SCENES)
    scene_args: List[str]  # adb-demo flags that make the scene
    backend: str          # adb, gimpact, convex
    kind: str             # exact, pairs, time, gimpact, convex
    seed: int
    steps: int
    probe_every: int
    fraction: Optional[float] = None  # budget as a fraction of the need / of exact time
    budget: Optional[float] = None    # node pairs or microseconds per step

    @property
    def name(self) -> str:
        parts = [self.scene, self.kind]
        if self.fraction is not None:
            parts.append("1-%d" % round(1 / self.fraction))
        parts.append("s%d" % self.seed)
        return "-".join(parts)

    def command(self, demo: str, out_dir: str) -> List[str]:
        # --no-sleep: the sweep measures what a budget costs a pile in motion, as its tables
        # always have; since issue 35 piles sleep as Bullet decides unless told not to.
        cmd = [demo, *self.scene_args, "--backend", self.backend, "--seed", str(self.seed),
               "--steps", str(self.steps), "--every", "1000000", "--no-sleep",
               "--probe-every", str(self.probe_every), "--out", out_dir]
        if self.kind == "pairs":
            cmd += ["--budget-pairs", str(int(self.budget))]
        elif self.kind == "time":
            cmd += ["--budget-us", "%.0f" % self.budget]
        return cmd


@dataclass
class Summary:
    spec: RunSpec
    wall_seconds: float
    load_before: float
    load_after: float
    prep_seconds: Optional[float]  # convex: the decomposition
    hulls: Optional[int]
    hull_volume_ratio: Optional[str]
    reused: bool  # read back from an earlier sweep, not run now
    rows: List[dict] = field(repr=False)

    # --- windows -----------------------------------------------------------------------
    def _col(self, name, first=1, last=None):
        """A steps.csv column over steps first..last; the probe's columns are -1 where the
        step was not probed, and those steps are left out."""
        last = last or len(self.rows)
        values = [float(r[name]) for r in self.rows[first - 1:last] if r[name] != ""]
        return [v for v in values if v >= 0] if name.startswith("probed_") else values

    @staticmethod
    def _mean(v):
        return sum(v) / len(v) if v else float("nan")

    def ms_per_step(self, last=None):
        return 1e3 * self._mean(self._col("seconds", 1, last))

    def frame_ms(self, last=None):
        """adb's pair work per step (0 for the other backends)."""
        return 1e-3 * self._mean(self._col("frame_us", 1, last))

    def settled_frame_us(self):
        return self._mean(self._col("frame_us", SETTLED_FROM))

    def settled_need(self):
        return self._mean(self._col("needed_node_pairs", SETTLED_FROM))

    def settled_node_pairs(self):
        return self._mean(self._col("node_pairs", SETTLED_FROM))

    def cut_share(self):
        pairs = sum(self._col("mesh_pairs"))
        return sum(self._col("cut_pairs")) / pairs if pairs else 0.0

    def lost(self):
        return int(max(self._col("lost")))

    def first_lost_step(self):
        for r in self.rows:
            if int(r["lost"]) > 0:
                return int(r["step"])
        return None

    def probed_max(self, last=None):
        # NaN, like _mean, where the window holds no probe (--gimpact-steps < --probe-every).
        return max(self._col("probed_penetration", 1, last), default=float("nan"))

    def probed_mean(self, last=None):
        """Each body's deepest penetration, averaged over bodies and probes."""
        return self._mean(self._col("probed_mean", 1, last))

    def probed_mean_end(self):
        """The last probe's mean: where the pile ended, not how it got there."""
        return self._col("probed_mean")[-1]

    def at_rest_end(self):
        return int(self.rows[-1]["at_rest"])

    def kinetic_end(self):
        return float(self.rows[-1]["kinetic"])

    def kinetic_last_second(self):
        return self._mean(self._col("kinetic", max(1, len(self.rows) - LAST_SECOND + 1)))

    def at_rest_last_second(self):
        return self._mean(self._col("at_rest", max(1, len(self.rows) - LAST_SECOND + 1)))


def _read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def _parse_decomposition(stdout):
    m = re.search(r"convex decomposition \(HACD\): (\d+) hulls .* prepared in ([0-9.]+) s; "
                  r"hulls' volume / mesh volume: (.*)", stdout)
    if not m:
        return None, None, None
    return float(m.group(2)), int(m.group(1)), m.group(3).strip()


def run(spec: RunSpec, demo: str, root: str, reuse: bool = True) -> Summary:
    out = os.path.join(root, "runs", spec.name)
    cmd = spec.command(demo, out)
    text = " ".join(cmd)
    done = os.path.join(out, "run.json")
    same = (os.path.exists(done) and os.path.exists(os.path.join(out, "command.txt"))
            and open(os.path.join(out, "command.txt")).read().strip() == text)
    reused = reuse and same
    if not reused:
        os.makedirs(out, exist_ok=True)
        with open(os.path.join(out, "command.txt"), "w") as f:
            f.write(text + "\n")
        if os.path.exists(done):
            os.remove(done)
        load_before = os.getloadavg()[0]
        t0 = time.monotonic()
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        wall = time.monotonic() - t0
        with open(os.path.join(out, "stdout.txt"), "w") as f:
            f.write(proc.stdout)
        # adb-demo exits 1 when a body left the bin: a result, not a failure.
        if proc.returncode not in (0, 1):
            sys.exit("budget_sweep: %s failed (exit %d), see %s/stdout.txt"
                     % (text, proc.returncode, out))
        with open(done, "w") as f:
            json.dump({"wall_seconds": wall, "load_before": load_before,
                       "load_after": os.getloadavg()[0], "exit": proc.returncode}, f)
    meta = json.load(open(done))
    rows = _read_rows(os.path.join(out, "steps.csv"))
    if len(rows) != spec.steps:
        sys.exit("budget_sweep: %s has %d steps, expected %d" % (out, len(rows), spec.steps))
    prep, hulls, ratio = _parse_decomposition(open(os.path.join(out, "stdout.txt")).read())
    return Summary(spec, meta["wall_seconds"], meta["load_before"], meta["load_after"], prep,
                   hulls, ratio, reused, rows)
