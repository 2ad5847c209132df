// makeMethods: the measured methods of a run, from the --methods names and the ADB sweeps.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "adb_method.h"
#include "method.h"

namespace adb::tradeoff {

/// The methods in the order listed; "adb" expands in place over p_min (outermost), k_min,
/// budget. ADB and exact methods share `tree` (one ADB-tree per model).
std::vector<std::unique_ptr<Method>> makeMethods(const std::vector<std::string>& names,
                                                 const std::vector<double>& pMins,
                                                 const std::vector<int>& kMins,
                                                 const std::vector<double>& budgetsUs,
                                                 const std::shared_ptr<SharedTree>& tree);

}  // namespace adb::tradeoff
