// Pooling a model's ADB settings into one method.
#include "pooling.h"

namespace adb::tradeoff {
namespace {

template <typename T>
void appendRepeated(std::vector<T>& out, const std::vector<T>& items, std::size_t times) {
  for (std::size_t k = 0; k < times; ++k) out.insert(out.end(), items.begin(), items.end());
}

}  // namespace

bool isPooledAdb(const std::string& name) {
  return name == "adb" || name.rfind("adb-work:", 0) == 0;
}

std::optional<ModelResult> pooledAdb(const ModelResult& result) {
  MethodRecords pooled;
  pooled.name = kPooledAdbName;
  pooled.params.estimates = true;
  std::size_t settings = 0;
  for (const MethodRecords& m : result.methods) {
    if (!isPooledAdb(m.name)) continue;
    pooled.queries.insert(pooled.queries.end(), m.queries.begin(), m.queries.end());
    ++settings;
  }
  if (settings == 0) return std::nullopt;
  ModelResult out;
  out.label = result.label;
  out.triangles = result.triangles;
  appendRepeated(out.distance, result.distance, settings);
  appendRepeated(out.rootsOverlap, result.rootsOverlap, settings);
  out.methods.push_back(std::move(pooled));
  for (const MethodRecords& m : result.methods) {
    if (isPooledAdb(m.name)) continue;
    MethodRecords repeated{m.name, m.params, {}};
    appendRepeated(repeated.queries, m.queries, settings);
    out.methods.push_back(std::move(repeated));
  }
  return out;
}

}  // namespace adb::tradeoff
