// The root-box answer (see root_boxes_method.h).
#include "root_boxes_method.h"

#include "root_overlap.h"

namespace adb::tradeoff {

Answer RootBoxesMethod::query(const Pose& a, const Pose& b) {
  Answer answer;
  answer.collides = rootBoxesOverlap(m_boundsA, a, m_boundsB, b);
  answer.confidence = 0.5;  // no estimate
  answer.nodePairs = -1;    // it does not use the tree
  return answer;
}

}  // namespace adb::tradeoff
