// FCL 0.7 as a measured peer: BVHModel<OBBRSS> of each model's triangles, boolean query that
// stops at the first intersecting triangle pair (CollisionRequest(1, false)). Exact; the
// independent oracle the tests check the ADB-tree's exact mode against.
#pragma once

#include <memory>
#include <string>

#include "method.h"

namespace adb::tradeoff {

class FclPeer : public Method {
 public:
  FclPeer();
  ~FclPeer() override;

  const std::string& name() const override { return m_name; }
  void prepare(const Model& a, const Model& b) override;
  Answer query(const Pose& a, const Pose& b) override;

 private:
  struct Impl;  // keeps FCL's heavy headers out of the rest of the tool
  std::unique_ptr<Impl> m_impl;
  std::string m_name = "fcl";
};

}  // namespace adb::tradeoff
