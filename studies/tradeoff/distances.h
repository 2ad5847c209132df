// distances.csv: the paper's Figs. 9 and 10 already judged, one row per model, method and
// parameters, and distance: the queries at that distance, their mean time, and the error rate
// and mean confidence by the same rule as summary.csv (the run's reference, among the queries
// whose root boxes overlap: judging.h), and which reference that was ("exact", "fcl", or
// empty: nothing judged). The plots only draw it.
#pragma once

#include <string>
#include <vector>

#include "results.h"

namespace adb::tradeoff {

/// The header line of distances.csv, exactly.
extern const char* const kDistancesCsvHeader;

/// Writes (truncates) distances.csv for the finished models; throws std::runtime_error when
/// writing fails.
void writeDistancesCsv(const std::string& path, const std::vector<ModelResult>& done);

}  // namespace adb::tradeoff
