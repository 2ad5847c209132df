// "adb-pooled": every ADB setting of a model (the "adb" time-budget settings, including no
// budget, and the "adb-work:N" work-budget settings) pooled into one method, so that the
// calibration of ADB's confidence is measured over all the confidences it reports.
//
// The pooled run is a ModelResult of its own: the pooled method holds the ADB settings'
// records one after another, and every other method's records (the reference, the peers)
// are repeated once per pooled setting, so that index i still names the same pose in every
// method and the summary and calibration code run on it unchanged.
#pragma once

#include <optional>
#include <string>

#include "results.h"

namespace adb::tradeoff {

inline constexpr const char* kPooledAdbName = "adb-pooled";

/// Whether `name` is one of the pooled methods: "adb" or "adb-work:N".
bool isPooledAdb(const std::string& name);

/// The pooled run of `result`: its first method is "adb-pooled" (no p_min, k_min or budget;
/// an estimating method), followed by the other methods, repeated. Empty when no ADB setting
/// ran.
std::optional<ModelResult> pooledAdb(const ModelResult& result);

}  // namespace adb::tradeoff
