// Judging a method's answers: the reference of a run (the tree's exact mode if it ran, else
// FCL) and, among the queries whose root boxes overlap (the paper's filter for the error
// rate), whether each answer equals the reference's. The error rate and the calibration
// both count exactly these queries.
#pragma once

#include <string>
#include <vector>

#include "calibration.h"
#include "results.h"

namespace adb::tradeoff {

/// The records of the method named `name`, or nullptr (the first, for repeated names).
const MethodRecords* findMethod(const ModelResult& result, const std::string& name);

/// The error reference: "exact" if it ran, else "fcl", else nullptr (no error rates).
const MethodRecords* referenceOf(const ModelResult& result);

/// `method`'s answers on the queries whose root boxes overlap, judged against `reference`
/// (both indexed like result.rootsOverlap).
std::vector<JudgedAnswer> judgeAnswers(const ModelResult& result, const MethodRecords& method,
                                       const MethodRecords& reference);

}  // namespace adb::tradeoff
