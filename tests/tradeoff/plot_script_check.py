#!/usr/bin/env python3
"""The trade-off study's plot script (studies/tradeoff/plot_tradeoff.py) on synthetic output
directories: every figure of a full run, older and partial runs drawn with notes for what is
missing, the tool's numbers read as written, and one clear error for a missing or malformed
input. Run by ctest (Tradeoff.PlotScript); needs /usr/bin/python3 with matplotlib.

The synthetic runs are made here with the arithmetic adb-tradeoff uses (error among the
queries whose root boxes overlap, per distance and per setting): the fixture, not the code
under test, which only draws.
"""

import contextlib
import csv
import io
import math
import os
import random
import subprocess
import sys
import tempfile
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
STUDY = os.path.join(HERE, "..", "..", "studies", "tradeoff")
SCRIPT = os.path.join(STUDY, "plot_tradeoff.py")
sys.path.insert(0, STUDY)

from plotting.figures import BASELINE_CURVES, PLOTS  # noqa: E402
from plotting.tables import (CELL_COLUMNS, CELLS, DISTANCE_COLUMNS, PEERS, POOLED,  # noqa: E402
                             RELIABILITY_COLUMNS, SUMMARY_COLUMNS, WORK_PREFIX, Bin, Dataset,
                             Setting, load)


def _ece(bins):
    """Expected calibration error of the fixture's bins (the tool's definition)."""
    used = [b for b in bins if b.count and b.confidence is not None]
    total = sum(b.count for b in used)
    return sum(b.count * abs(b.confidence - b.right) for b in used) / total if total else None


def _write_csv(path, header, rows):
    with open(path, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(header)
        writer.writerows(rows)


def _cell(value):
    return "" if value is None else value


SYNTHETIC_BUDGETS_US = (10.0, 30.0, 100.0, 300.0)
RELIABILITY_BINS = 10


def _synthetic_settings():
    """Every kind of row the tool writes: peers, baselines, ADB with and without budgets."""
    settings = [Setting(m) for m in PEERS] + [Setting("root-boxes")]
    settings += [Setting("adb", p, k) for p in (0.5, 0.9, 0.99) for k in (1, 5, 10)]
    bases = ((0.99, 10), (0.9, 5))
    settings += [Setting("adb", p, k, b) for p, k in bases for b in SYNTHETIC_BUDGETS_US]
    settings += [Setting("adb-work", p, k, work=w) for p, k in bases for w in (50, 200, 1000)]
    settings += [Setting(m, budget_us=b) for m in BASELINE_CURVES for b in SYNTHETIC_BUDGETS_US]
    return settings


def _csv_method(setting):
    return WORK_PREFIX + str(setting.work) if setting.method == "adb-work" else setting.method


def _synthetic_query(rng, s, truth, overlap, distance, exact_us):
    """(answer, confidence or None, time in µs, node pairs or None) of one made-up query."""
    noise = rng.lognormvariate(0, 0.25)
    peer_cost = {"exact": 1.0, "gimpact": 12.0, "fcl": 0.4}
    if s.method in peer_cost:
        time_us = exact_us * peer_cost[s.method] * noise
        return truth, 1.0, time_us, int(time_us * 8) if s.method == "exact" else None
    if s.method == "root-boxes":
        return overlap, None, 0.05 * noise, 1
    if s.method in BASELINE_CURVES:
        full_us = exact_us * (1.0 if s.method == "exact-cut" else 0.7) * noise
        if full_us <= s.budget_us:
            return truth, 1.0 if s.method == "exact-cut" else None, full_us, int(full_us * 8)
        # Cut short: exact-cut falls back on the root boxes, box-first on the boxes it reached.
        answer = overlap if s.method == "exact-cut" else truth != (rng.random() < 0.3)
        return (answer, 0.5 if s.method == "exact-cut" else None, s.budget_us * 1.05,
                int(s.budget_us * 8))
    near = 0.3 + 2 * math.exp(-((distance - 1.3) / 0.4) ** 2)
    # A per-query error chance spread around the setting's mean, so confidences fill
    # several reliability bins; capped at 0.5, where a yes/no guess is no better than a coin.
    error = min(0.5, near * (0.005 + 0.12 * (1 - s.p_min) + 0.03 / s.k_min)
                * rng.expovariate(1.0))
    # The estimate ignores what a budget costs, so budgeted ADB is overconfident: something
    # for the reliability diagram to show.
    confidence = max(0.0, min(1.0, 1 - error + rng.gauss(0, 0.02)))
    time_us = exact_us * (0.12 + 0.3 * s.k_min / 10) * noise
    if s.budget_us is not None:
        error += 0.25 * math.exp(-s.budget_us / 40)
        time_us = min(time_us, s.budget_us * 1.05)
    if s.work is not None:
        error += 0.25 * math.exp(-s.work / 150)
        time_us = min(time_us, s.work / 8 * 1.05)
    return truth != (rng.random() < error), confidence, time_us, int(time_us * 8)


def _synthetic_distances(groups_by_distance):
    rows = []
    for (model, triangles, s, distance), group in sorted(
            groups_by_distance.items(),
            key=lambda kv: (kv[0][0], kv[0][1], kv[0][2].sort_key(), kv[0][3])):
        overlapping = [g for g in group if g[3]]
        error = (100.0 * sum(g[1] for g in overlapping) / len(overlapping)) if overlapping else None
        confidences = [g[2] for g in overlapping if g[2] is not None]
        rows.append([model, triangles, _csv_method(s), _cell(s.p_min), _cell(s.k_min),
                     _cell(s.budget_us), distance, len(group),
                     "%.4f" % (sum(g[0] for g in group) / len(group)), len(overlapping),
                     "" if error is None else "%.4f" % error,
                     "%.4f" % (sum(confidences) / len(confidences)) if confidences else "",
                     "exact"])
    return rows


def synthetic_run(directory, seed=7):
    """Write a plausible small distances, summary, reliability and cells CSV into `directory`."""
    rng = random.Random(seed)
    models = {"teddy": (3192, 12768), "pipes": (20000, 80000)}
    distances = [round(0.4 + 0.2 * i, 2) for i in range(9)]
    settings = _synthetic_settings()
    groups, by_distance = defaultdict(list), defaultdict(list)
    for model, sizes in models.items():
        for triangles in sizes:
            for distance in distances:
                for _ in range(30):
                    truth = rng.random() < 1 / (1 + math.exp(-6 * (1.3 - distance)))
                    overlap = distance < 1.8  # stands in for "the root boxes overlap"
                    exact_us = 150 * math.exp(-1.8 * (distance - 0.4)) * (triangles / 3192) ** 0.15
                    for s in settings:
                        answer, confidence, time_us, nodes = _synthetic_query(
                            rng, s, truth, overlap, distance, exact_us)
                        group = (time_us, answer != truth, confidence, overlap, nodes)
                        groups[(model, triangles, s)].append(group)
                        by_distance[(model, triangles, s, distance)].append(group)
                        if s.method in ("adb", "adb-work"):
                            groups[(model, triangles, Setting(POOLED))].append(group)
    _write_csv(os.path.join(directory, "distances.csv"), DISTANCE_COLUMNS,
               _synthetic_distances(by_distance))
    summary_columns = list(SUMMARY_COLUMNS)
    summary_columns.insert(summary_columns.index("error_pct") + 1, "ece")
    _write_csv(os.path.join(directory, "summary.csv"), summary_columns,
               _synthetic_summary(groups))
    _write_csv(os.path.join(directory, "reliability.csv"), RELIABILITY_COLUMNS,
               _synthetic_reliability(groups))
    cells = []
    for model in models:
        for triangles in models[model]:
            for index in range(CELLS):
                bias = 1.3 if model == "pipes" and (index // 64) in (3, 4) else 1.0
                cells.append([model, triangles, index, int(rng.gauss(1000, 60) * bias)])
    _write_csv(os.path.join(directory, "cells.csv"), CELL_COLUMNS, cells)


def _has_bins(setting):
    """The settings reliability.csv holds: those whose confidence is an estimate."""
    return setting.method in ("adb", "adb-work", "exact-cut", POOLED)


def _synthetic_bins(group):
    """Ten equal confidence bins over the queries with overlapping root boxes."""
    members = [[] for _ in range(RELIABILITY_BINS)]
    for _, wrong, confidence, overlap, _ in group:
        if overlap and confidence is not None:
            members[min(RELIABILITY_BINS - 1, int(confidence * RELIABILITY_BINS))].append(
                (confidence, not wrong))
    return [Bin(i / RELIABILITY_BINS, (i + 1) / RELIABILITY_BINS, len(m),
                sum(c for c, _ in m) / len(m) if m else None,
                sum(r for _, r in m) / len(m) if m else None)
            for i, m in enumerate(members)]


def _sorted_groups(groups):
    return sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1], kv[0][2].sort_key()))


def _synthetic_reliability(groups):
    rows = []
    for (model, triangles, s), group in _sorted_groups(groups):
        if not _has_bins(s):
            continue
        for index, b in enumerate(_synthetic_bins(group)):
            rows.append([model, triangles, _csv_method(s), _cell(s.p_min), _cell(s.k_min),
                         _cell(s.budget_us), index, "%.1f" % b.lo, "%.1f" % b.hi, b.count,
                         "" if b.confidence is None else "%.4f" % b.confidence,
                         "" if b.right is None else "%.4f" % b.right])
    return rows


def _synthetic_summary(groups):
    means = {key: sum(g[0] for g in group) / len(group) for key, group in groups.items()}
    rows = []
    for (model, triangles, s), group in _sorted_groups(groups):
        times = sorted(g[0] for g in group)
        overlapping = [g for g in group if g[3]]
        error = 100.0 * sum(g[1] for g in overlapping) / len(overlapping)
        confidences = [g[2] for g in group if g[2] is not None]
        nodes = [g[4] for g in group if g[4] is not None]
        ece = _ece(_synthetic_bins(group)) if _has_bins(s) else None
        speedups = []
        for peer in PEERS:
            # Leave teddy's speed-up cells empty, as for a peer that did not run.
            peer_mean = means.get((model, triangles, Setting(peer)))
            speedups.append("" if model == "teddy" or peer_mean is None
                            else "%.3f" % (peer_mean / means[(model, triangles, s)]))
        rows.append([model, triangles, _csv_method(s), _cell(s.p_min), _cell(s.k_min),
                     _cell(s.budget_us), len(group), len(overlapping),
                     "%.3f" % means[(model, triangles, s)],
                     "%.3f" % times[int(0.95 * (len(times) - 1))],
                     "%.3f" % error, "" if ece is None else "%.4f" % ece,
                     "%.4f" % (sum(confidences) / len(confidences)) if confidences else "",
                     "%.1f" % (sum(nodes) / len(nodes)) if nodes else ""] + speedups)
    return rows


def _run(directory):
    result = subprocess.run(["/usr/bin/python3", SCRIPT, directory], capture_output=True,
                            text=True)
    return result.returncode, result.stdout + result.stderr


def _is_png(path):
    if not os.path.exists(path) or os.path.getsize(path) < 1000:
        return False
    with open(path, "rb") as handle:
        return handle.read(8) == b"\x89PNG\r\n\x1a\n"


def _keep_rows(path, keep):
    """Rewrite a CSV file keeping the header and the rows for which keep(row) is true."""
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    _write_csv(path, rows[0], [r for r in rows[1:] if keep(r)])


def _make_old_format(directory):
    """Turn a synthetic run into what adb-tradeoff wrote before the calibration columns and
    distances.csv: only adb and the peers, summary.csv without ece, no reliability.csv."""
    old = ("adb",) + PEERS
    path = os.path.join(directory, "summary.csv")
    with open(path, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    drop, method = rows[0].index("ece"), rows[0].index("method")
    _write_csv(path, [c for i, c in enumerate(rows[0]) if i != drop],
               [[c for i, c in enumerate(r) if i != drop] for r in rows[1:] if r[method] in old])
    os.remove(os.path.join(directory, "reliability.csv"))
    os.remove(os.path.join(directory, "distances.csv"))


def _new_rows_read(directory):
    """The method names, the ece column and reliability.csv come through the readers."""
    with contextlib.redirect_stdout(io.StringIO()):
        data = load(directory)
    key = ("pipes", 80000)
    pooled = data.summary.get(key + (Setting(POOLED),))
    bins = data.reliability.get(key + (Setting("adb-work", 0.99, 10, work=200),), [])
    return (pooled is not None and pooled.ece is not None
            and key + (Setting("exact-cut", budget_us=30.0),) in data.summary
            and key + (Setting("root-boxes"),) in data.summary
            and len(bins) == RELIABILITY_BINS and any(b.count == 0 for b in bins))


def _read_as_written(root):
    """A hand-made distances.csv: its error rate, time, confidence and reference are drawn as
    written (25 % of 4 overlapping queries wrong, 2.5 µs, judged against FCL), not
    recomputed or inferred."""
    directory = os.path.join(root, "as_written")
    os.mkdir(directory)
    _write_csv(os.path.join(directory, "distances.csv"), DISTANCE_COLUMNS,
               [["m", 100, "adb", 0.99, 10, "", "1.0", 5, "2.5", 4, "25", "0.9", "fcl"],
                ["m", 100, "fcl", "", "", "", "1.0", 5, "9", 4, "0", "1", "fcl"]])
    _write_csv(os.path.join(directory, "summary.csv"), SUMMARY_COLUMNS, [])
    data = Dataset(directory)
    with contextlib.redirect_stdout(io.StringIO()):
        data.read_distances()
        data.read_summary()
    point = data.per_distance[("m", 100, Setting("adb", 0.99, 10))][1.0]
    return (point.error_pct == 25.0 and point.mean_us == 2.5 and point.queries == 5
            and point.overlapping == 4 and point.mean_confidence == 0.9
            and data.reference_label() == "reference: FCL (no exact rows)")


def main():
    failures = []

    def check(condition, what, output=""):
        print("%s: %s" % ("ok  " if condition else "FAIL", what))
        if not condition:
            failures.append(what)
            if output:
                print("    " + output.strip().replace("\n", "\n    "))

    with tempfile.TemporaryDirectory(prefix="plot_tradeoff_") as root:
        full = os.path.join(root, "full")
        os.mkdir(full)
        synthetic_run(full)
        code, output = _run(full)
        check(code == 0, "full synthetic run exits 0", output)
        for name, _ in PLOTS:
            check(_is_png(os.path.join(full, name)), "full run wrote %s as a PNG" % name, output)
        check("Traceback" not in output, "full run printed no traceback", output)
        check(_new_rows_read(full), "new methods, ece and reliability bins are read")

        old = os.path.join(root, "old_format")
        os.mkdir(old)
        synthetic_run(old)
        _make_old_format(old)
        code, output = _run(old)
        check(code == 0 and "Traceback" not in output, "old-format run exits 0", output)
        check("skip reliability.png: no reliability.csv" in output,
              "old-format run skips the reliability diagram with a note", output)
        check("skip time_vs_distance.png" in output and "skip error_vs_distance.png" in output,
              "old-format run skips the per-distance figures with a note", output)
        for name in ("error_vs_budget.png", "speedup.png", "pareto.png"):
            check(_is_png(os.path.join(old, name)), "old-format run wrote %s" % name, output)

        # A run stopped before its first model ended: summary.csv with only its header, no
        # cells, and distances.csv of one model with its last line cut off mid-row.
        partial = os.path.join(root, "partial")
        os.mkdir(partial)
        synthetic_run(partial)
        _write_csv(os.path.join(partial, "summary.csv"), SUMMARY_COLUMNS, [])
        os.remove(os.path.join(partial, "cells.csv"))
        _keep_rows(os.path.join(partial, "distances.csv"),
                   lambda r: r[0] == "pipes" and r[1] == "20000" and (
                       r[2] == "fcl" or (r[2], r[3], r[4], r[5]) == ("adb", "0.99", "10", "")))
        with open(os.path.join(partial, "distances.csv"), "a", encoding="utf-8") as handle:
            handle.write("pipes,20000,adb,0.99,10,,1.2,30")
        code, output = _run(partial)
        check(code == 0, "partial run exits 0", output)
        check("Traceback" not in output, "partial run printed no traceback", output)
        for name in ("time_vs_distance.png", "error_vs_distance.png"):
            check(_is_png(os.path.join(partial, name)), "partial run wrote %s" % name, output)
        check("skip cells_histogram.png" in output, "partial run skips the cell histogram", output)
        check("summary.csv has no rows" in output, "partial run says no model finished", output)
        check("1 malformed or truncated row" in output, "partial run reports the cut-off row",
              output)
        check(_read_as_written(root), "the tool's per-distance numbers are drawn as written")

        for file_name, column in (("distances.csv", "error_pct"), ("summary.csv", "error_pct"),
                                  ("cells.csv", "count")):
            broken = os.path.join(root, "broken_" + file_name.split(".")[0])
            os.mkdir(broken)
            synthetic_run(broken)
            path = os.path.join(broken, file_name)
            with open(path, encoding="utf-8") as handle:
                lines = handle.read().split("\n")
            lines[0] = lines[0].replace(column, column + "_renamed")
            with open(path, "w", encoding="utf-8") as handle:
                handle.write("\n".join(lines))
            code, output = _run(broken)
            check(code != 0 and column in output and file_name in output,
                  "malformed %s header exits non-zero naming %s" % (file_name, column), output)

        code, output = _run(os.path.join(root, "does_not_exist"))
        check(code != 0 and "does_not_exist" in output, "missing DIR exits non-zero", output)
        no_summary = os.path.join(root, "no_summary")
        os.mkdir(no_summary)
        code, output = _run(no_summary)
        check(code != 0 and "summary.csv" in output, "missing summary.csv exits non-zero", output)

    print("plot script check %s" % ("passed" if not failures else "FAILED (%d)" % len(failures)))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
