// adb::Dispatcher: Bullet's dispatch, then the step's budget spent across adb's pairs.
#include "adb/bullet/dispatcher.h"

#include <string>
#include <utility>

#include "adb/core/tree.h"
#include "frame_scheduler.h"

namespace adb {

Dispatcher::Dispatcher(btDefaultCollisionConfiguration* configuration)
    : btCollisionDispatcher(configuration),
      m_scheduler(std::make_unique<detail::FrameScheduler>()) {
  registerAlgorithms(*this, *configuration);
}

Dispatcher::~Dispatcher() = default;

void Dispatcher::setFrameSettings(const FrameSettings& s) {
  validate(s);
  m_settings = s;
}

const FrameStats& Dispatcher::lastFrameStats() const { return m_scheduler->stats(); }

void Dispatcher::lastMeshPairs(std::vector<MeshPairReport>& out) const {
  m_scheduler->meshPairs(out);
}

void Dispatcher::lastAuditedContacts(std::vector<AuditedContact>& out) const {
  out = m_scheduler->auditedContacts();
}

void Dispatcher::setBadPoseCallback(std::function<void(const BadPose&)> callback) {
  m_scheduler->setBadPoseCallback(std::move(callback));
}

void Dispatcher::dispatchAllCollisionPairs(btOverlappingPairCache* pairCache,
                                           const btDispatcherInfo& info,
                                           btDispatcher* dispatcher) {
  m_scheduler->begin();
  try {
    btCollisionDispatcher::dispatchAllCollisionPairs(pairCache, info, dispatcher);
  } catch (...) {
    m_scheduler->abandon();  // else later contactTests would be deferred into no step
    throw;
  }
  m_scheduler->run(m_settings, info);
}

}  // namespace adb
