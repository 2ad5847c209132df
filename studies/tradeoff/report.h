// The files written from the finished models' results: summary.csv, summary.md (with its
// Budgets section), reliability.csv, cells.csv and distances.csv. Rewritten in full after every model, so
// that they always describe exactly the models completed so far (a later failure keeps them).
#pragma once

#include <string>
#include <vector>

#include "options.h"
#include "results.h"

namespace adb::tradeoff {

void writeReports(const Options& options, const std::vector<ModelResult>& done);

}  // namespace adb::tradeoff
