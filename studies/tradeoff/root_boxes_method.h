// "root-boxes": the trivial answer, "collides whenever the two root boxes overlap" (the
// study's own oriented-box test, root_overlap.h). The floor any method must beat: by
// construction it is wrong on every overlapping query that does not collide. It knows
// nothing beyond the boxes, so its confidence is a fixed 0.5.
#pragma once

#include <string>

#include "method.h"

namespace adb::tradeoff {

class RootBoxesMethod : public Method {
 public:
  const std::string& name() const override { return m_name; }
  void prepare(const Model& a, const Model& b) override {
    m_boundsA = a.mesh.bounds();
    m_boundsB = b.mesh.bounds();
  }
  Answer query(const Pose& a, const Pose& b) override;

 private:
  std::string m_name = "root-boxes";
  Aabb m_boundsA, m_boundsB;
};

}  // namespace adb::tradeoff
