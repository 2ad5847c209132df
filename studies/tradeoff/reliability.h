// reliability.csv: the reliability diagram (calibration.h) of every method setting that
// estimates its confidence (every adb setting, every adb-work:N, every exact-cut budget),
// plus "adb-pooled" (all adb and adb-work settings of the model together), 10 rows per
// group (empty bins too), counting the queries whose root boxes overlap, "right" meaning
// the answer equals the reference's (exact, else fcl). A model without a reference gets no
// rows: there is nothing to call right.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "results.h"

namespace adb::tradeoff {

/// The header line of reliability.csv, exactly.
extern const char* const kReliabilityCsvHeader;

/// Writes (truncates) `path` with the rows of every model; throws std::runtime_error when
/// writing fails.
void writeReliabilityCsv(const std::string& path, const std::vector<ModelResult>& done);

/// The rows of one model (no header).
void writeReliabilityRows(std::ostream& out, const ModelResult& result);

}  // namespace adb::tradeoff
