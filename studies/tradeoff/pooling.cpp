// Pooling a model's ADB settings into one method.
#include "pooling.h"

#include <algorithm>

#include "judging.h"

namespace adb::tradeoff {

bool isPooledAdb(const std::string& name) {
  return name == "adb" || name.rfind("adb-work:", 0) == 0;
}

std::optional<PooledAdb> pooledAdb(const ModelResult& result) {
  PooledAdb pool;
  pool.records.name = kPooledAdbName;
  pool.records.params.estimates = true;
  const MethodRecords* reference = referenceOf(result);
  pool.hasReference = reference != nullptr;
  const auto overlapping = static_cast<std::size_t>(
      std::count(result.rootsOverlap.begin(), result.rootsOverlap.end(), true));
  std::size_t settings = 0;
  for (const MethodRecords& m : result.methods) {
    if (!isPooledAdb(m.name)) continue;
    ++settings;
    pool.records.queries.insert(pool.records.queries.end(), m.queries.begin(), m.queries.end());
    pool.overlapping += overlapping;
    if (!reference) continue;
    // Judged setting by setting: each indexes the model's poses, as the reference does.
    const std::vector<JudgedAnswer> judged = judgeAnswers(result, m, *reference);
    pool.judged.insert(pool.judged.end(), judged.begin(), judged.end());
  }
  if (settings == 0) return std::nullopt;
  return pool;
}

}  // namespace adb::tradeoff
