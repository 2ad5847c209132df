// cells.csv: the paper's Fig. 8 histogram (adb/core/cell_histogram.h) per model.
#include "cell_histogram.h"

#include "csv_format.h"

namespace adb::tradeoff {

const char* const kCellsCsvHeader = "model,triangles,cell,count";

void writeCellRows(std::ostream& out, const std::string& model, std::size_t triangles,
                   const CellHistogram& histogram) {
  for (std::size_t c = 0; c < histogram.count.size(); ++c) {
    out << csvField(model) << ',' << triangles << ',' << c << ',' << histogram.count[c] << '\n';
  }
}

}  // namespace adb::tradeoff
