// "adb-pooled": every ADB setting of a model (the "adb" time-budget settings, including no
// budget, and the "adb-work:N" work-budget settings) pooled into one method, so that the
// calibration of ADB's confidence is measured over all the confidences it reports.
//
// The pool holds the ADB settings' records one setting after another, and their answers
// judged against the run's reference (each setting judged on its own poses, then
// concatenated): nothing else of the run is copied, and the summary and the reliability
// diagram read the pool as they read one method.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "calibration.h"
#include "results.h"

namespace adb::tradeoff {

inline constexpr const char* kPooledAdbName = "adb-pooled";

/// Whether `name` is one of the pooled methods: "adb" or "adb-work:N".
bool isPooledAdb(const std::string& name);

/// The pooled ADB settings of one model.
struct PooledAdb {
  /// "adb-pooled" (no p_min, k_min or budget; an estimating method): every ADB setting's
  /// records, one setting after another.
  MethodRecords records;
  /// Whether the run has a reference (exact, else fcl): without one nothing is judged.
  bool hasReference = false;
  /// Every setting's answers on the poses whose root boxes overlap, judged against the
  /// reference, concatenated in the order of `records`.
  std::vector<JudgedAnswer> judged;
  /// Pooled queries whose root boxes overlap: the settings' count times the model's.
  std::size_t overlapping = 0;
};

/// The pool of `result`'s ADB settings; empty when no ADB setting ran.
std::optional<PooledAdb> pooledAdb(const ModelResult& result);

}  // namespace adb::tradeoff
