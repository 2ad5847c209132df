// The reference of a run, and answers judged against it.
#include "judging.h"

#include <algorithm>

namespace adb::tradeoff {

const MethodRecords* findMethod(const ModelResult& result, const std::string& name) {
  for (const MethodRecords& m : result.methods) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const MethodRecords* referenceOf(const ModelResult& result) {
  const MethodRecords* exact = findMethod(result, "exact");
  return exact ? exact : findMethod(result, "fcl");
}

std::vector<JudgedAnswer> judgeAnswers(const ModelResult& result, const MethodRecords& method,
                                       const MethodRecords& reference) {
  // Every method answered every pose; the bound only guards a partial record.
  const std::size_t n = std::min({method.queries.size(), reference.queries.size(),
                                  result.rootsOverlap.size()});
  std::vector<JudgedAnswer> judged;
  judged.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!result.rootsOverlap[i]) continue;
    const QueryRecord& q = method.queries[i];
    judged.push_back(JudgedAnswer{q.confidence, q.collides == reference.queries[i].collides});
  }
  return judged;
}

}  // namespace adb::tradeoff
