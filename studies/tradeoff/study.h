// Measuring one case (a model against a copy of itself, or against another model): prepare
// every method (untimed), then for every pose (each distance and rotation, or each of the
// inside poses) query every method on the same pose pair (methods interleaved pose by pose,
// timing policy in timing.h), writing each query's row to queries.csv and keeping the records
// for the summary.
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

/// Runs the study of case `caseIndex`: model `a` against model `b`, which is `a` itself (the
/// same object) for two copies of one model. The cell histogram is added by the caller.
ModelResult runCase(const Model& a, const Model& b, std::size_t caseIndex,
                    StudyContext& context);

/// What a case is called in the files: the model's label, or "A+B" for a pair.
std::string caseLabel(const Model& a, const Model& b);

/// Queries one case takes (distances x rotations x methods; with --poses inside, rotations x
/// methods), for the progress total.
std::uint64_t queriesPerCase(const Options& options, std::size_t methodCount);

}  // namespace adb::tradeoff
