// cells.csv: the paper's Fig. 8 histogram (adb/core/cell_histogram.h), 512 rows per model.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>

#include "adb/core/cell_histogram.h"

namespace adb::tradeoff {

/// cells.csv: `model,triangles,cell,count`, 512 rows per model.
extern const char* const kCellsCsvHeader;
void writeCellRows(std::ostream& out, const std::string& model, std::size_t triangles,
                   const CellHistogram& histogram);

}  // namespace adb::tradeoff
