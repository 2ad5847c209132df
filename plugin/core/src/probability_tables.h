// Internal: the tables behind the balls-into-bins probabilities (probability.cpp), built
// once per process.
#pragma once

namespace adb::detail {

/// Builds the factorial tables now if they are not built yet (thread-safe, idempotent). A
/// query that met them first built them inside its own clock.
void prepareProbabilityTables();

}  // namespace adb::detail
