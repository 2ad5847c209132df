// Judging a method's answers: the reference of a run (the tree's exact mode if it ran, else
// FCL) and, among the queries whose root boxes overlap (the paper's filter for the error
// rate), whether each answer equals the reference's. The error rate and the calibration
// both count exactly these queries.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "calibration.h"
#include "results.h"

namespace adb::tradeoff {

/// The records of the method named `name`, or nullptr (the first, for repeated names).
const MethodRecords* findMethod(const ModelResult& result, const std::string& name);

/// The error reference: "exact" if it ran, else "fcl", else nullptr (no error rates).
const MethodRecords* referenceOf(const ModelResult& result);

/// Calls f(pose, JudgedAnswer) for each of `method`'s answers on a query whose root boxes
/// overlap, judged against `reference` (both indexed like result.rootsOverlap): the one rule
/// every figure of a run (error rate, calibration, per distance) counts by.
template <typename F>
void forEachJudged(const ModelResult& result, const MethodRecords& method,
                   const MethodRecords& reference, F&& f) {
  // Every method answered every pose; the bound only guards a partial record.
  const std::size_t n = std::min({method.queries.size(), reference.queries.size(),
                                  result.rootsOverlap.size()});
  for (std::size_t i = 0; i < n; ++i) {
    if (!result.rootsOverlap[i]) continue;
    const QueryRecord& q = method.queries[i];
    f(i, JudgedAnswer{q.confidence, q.collides == reference.queries[i].collides});
  }
}

/// forEachJudged's answers, in pose order.
std::vector<JudgedAnswer> judgeAnswers(const ModelResult& result, const MethodRecords& method,
                                       const MethodRecords& reference);

}  // namespace adb::tradeoff
