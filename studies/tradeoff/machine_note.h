// One line describing where a run was measured (CPU, threads, compiler, build), for
// summary.md: times from different machines must not be compared.
#pragma once

#include <string>

namespace adb::tradeoff {

std::string machineNote();

}  // namespace adb::tradeoff
