// Writing the summary, reliability, cell-histogram and per-distance files.
#include "report.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "budgets.h"
#include "cell_histogram.h"
#include "distances.h"
#include "machine_note.h"
#include "reliability.h"
#include "summary.h"

namespace adb::tradeoff {
namespace {

std::string path(const Options& o, const char* name) { return o.outDir + "/" + name; }

RunNotes notes(const Options& o, const std::vector<ModelResult>& done) {
  RunNotes n;
  n.lines.push_back("Command: `" + o.commandLine + "`  ");
  n.lines.push_back("Machine: " + machineNote() + "  ");
  if (o.poses == PoseMode::Inside) {
    n.lines.push_back("Poses: " + std::to_string(o.rotations) +
                      " per case, inside (A at the identity, B randomly rotated with its box "
                      "centre uniformly random in A's bounding box), seed " +
                      std::to_string(o.seed) + "; the same poses for every method.  ");
  } else {
    n.lines.push_back("Poses: " + std::to_string(o.distances.size()) + " distances x " +
                      std::to_string(o.rotations) + " rotations per case, seed " +
                      std::to_string(o.seed) + "; the same poses for every method.  ");
  }
  for (const ModelResult& r : done) n.lines.push_back(r.note + "  ");
  n.lines.push_back(std::string("Timing: per query, ") +
                    (o.warmup ? "one untimed warm-up run, then " : "no warm-up run, ") +
                    "the fastest of " +
                    std::to_string(o.repeats) +
                    " timed runs (steady_clock around the call); mean and p95 over all "
                    "queries of the row. Data structures built once per model, untimed. "
                    "GImpact (collision margin 0, algorithm created once per model) computes full contact "
                    "sets; the others stop at the first hit.");
  n.lines.push_back("");
  for (const ModelResult& r : done) {
    std::string sampling;
    if (r.cells.stride > 1) {
      sampling = " (every " + std::to_string(r.cells.stride) +
                 "th node of each level, counts scaled to the level)";
    }
    char buf[320];
    std::snprintf(buf, sizeof buf, "Cell histogram (cells.csv) of %s: %zu of %zu nodes%s, %.2f s.  ",
                  r.label.c_str(), r.cells.nodesCounted, r.cells.nodesTotal, sampling.c_str(),
                  r.cells.seconds);
    n.lines.push_back(buf);
  }
  return n;
}

void writeCells(const std::string& file, const std::vector<ModelResult>& done) {
  std::ofstream out(file, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + file);
  out << kCellsCsvHeader << '\n';
  for (const ModelResult& r : done) writeCellRows(out, r.label, r.triangles, r.cells);
  out.flush();
  if (!out) throw std::runtime_error("writing " + file + " failed");
}

}  // namespace

void writeReports(const Options& options, const std::vector<ModelResult>& done) {
  std::vector<std::vector<SummaryRow>> perModel;
  std::vector<SummaryRow> rows;
  for (const ModelResult& r : done) {
    perModel.push_back(summarize(r));
    rows.insert(rows.end(), perModel.back().begin(), perModel.back().end());
  }
  writeSummaryCsv(path(options, "summary.csv"), rows);
  writeSummaryMarkdown(path(options, "summary.md"), rows, notes(options, done),
                       budgetsSection(perModel));
  writeReliabilityCsv(path(options, "reliability.csv"), done);
  writeCells(path(options, "cells.csv"), done);
  writeDistancesCsv(path(options, "distances.csv"), done);
}

}  // namespace adb::tradeoff
