// Measuring one model: prepare every method (untimed), then for every distance and rotation
// query every method on the same pose pair (methods interleaved pose by pose, timing policy
// in timing.h), writing each query's row to queries.csv and keeping the records for the
// summary.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "method.h"
#include "options.h"
#include "shared/progress.h"
#include "query_csv.h"
#include "results.h"

namespace adb::tradeoff {

struct StudyContext {
  const Options& options;
  std::vector<std::unique_ptr<Method>>& methods;
  QueryCsv& csv;
  tools::Progress& progress;
};

/// Runs the study of one model (the cell histogram is added by the caller).
ModelResult runModel(const Model& model, StudyContext& context);

/// Queries one model takes (distances x rotations x methods), for the progress total.
std::uint64_t queriesPerModel(const Options& options, std::size_t methodCount);

}  // namespace adb::tradeoff
