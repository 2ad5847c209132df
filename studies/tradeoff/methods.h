// makeMethods: the measured methods of a run, from the --methods names and the sweeps.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "adb_method.h"
#include "method.h"
#include "options.h"

namespace adb::tradeoff {

/// The methods in the order --methods lists them. "adb" expands in place over p_min
/// (outermost), k_min, time budget; the work-budget runs ("adb-work:N", p_min outermost,
/// then k_min, then N) follow the "adb" settings, or come last when "adb" is not listed.
/// "exact-cut" and "box-first" expand over the finite time budgets. Every method on the
/// ADB-tree shares `tree` (one tree per model).
std::vector<std::unique_ptr<Method>> makeMethods(const Options& options,
                                                 const std::shared_ptr<SharedTree>& tree);

/// The method name of ADB under a work budget of `pairs` node pairs: "adb-work:N".
std::string workMethodName(std::uint64_t pairs);

}  // namespace adb::tradeoff
