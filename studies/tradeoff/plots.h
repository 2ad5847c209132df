// Running the plotting script (studies/tradeoff/plot_tradeoff.py, written separately) on the
// output directory. The CSVs are the result: a missing script, python3 or matplotlib only
// gives a warning.
#pragma once

#include <string>

namespace adb::tradeoff {

/// The script's path, fixed at compile time (ADB_TRADEOFF_PLOT_SCRIPT).
std::string plotScriptPath();

/// Runs `python3 SCRIPT DIR`; returns true on success, prints a warning on stderr otherwise.
bool runPlotScript(const std::string& outDir);

/// Runs `python3 script outDir` for any study (`tool` names it in warnings); the same
/// contract.
bool runPythonScript(const std::string& script, const std::string& outDir, const char* tool);

}  // namespace adb::tradeoff
