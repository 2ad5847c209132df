// The reference of a run, and answers judged against it.
#include "judging.h"

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
  std::vector<JudgedAnswer> judged;
  judged.reserve(result.rootsOverlap.size());
  forEachJudged(result, method, reference,
                [&](std::size_t, const JudgedAnswer& answer) { judged.push_back(answer); });
  return judged;
}

}  // namespace adb::tradeoff
