// adb::Dispatcher: Bullet's dispatch, then the step's budget spent across adb's pairs.
#include "adb/bullet/dispatcher.h"

#include <cmath>
#include <string>
#include <utility>

#include "adb/core/tree.h"
#include "frame_scheduler.h"

namespace adb {

detail::FrameScheduler& detail::schedulerOf(Dispatcher& dispatcher) {
  return *dispatcher.m_scheduler;
}

namespace {

void require(bool ok, const char* field, double value, const char* rule) {
  if (ok) return;
  throw SettingsError(std::string("FrameSettings::") + field + " is " + std::to_string(value) +
                      "; it must be " + rule);
}

}  // namespace

Dispatcher::Dispatcher(btDefaultCollisionConfiguration* configuration)
    : btCollisionDispatcher(configuration),
      m_scheduler(std::make_unique<detail::FrameScheduler>()) {
  registerAlgorithms(*this, *configuration);
}

Dispatcher::~Dispatcher() = default;

void Dispatcher::setFrameSettings(const FrameSettings& s) {
  require(!std::isnan(s.budgetMicros) && s.budgetMicros >= 0.0, "budgetMicros", s.budgetMicros,
          ">= 0 (infinity for none)");
  require(s.pMin >= 0.0 && s.pMin <= 1.0, "pMin", s.pMin, "in [0, 1]");
  require(s.kMin >= 0, "kMin", s.kMin, ">= 0 (0: never stop on quality)");
  require(s.pAccept >= 0.0 && s.pAccept <= 1.0, "pAccept", s.pAccept, "in [0, 1]");
  require(s.maxPlausibleContacts >= 0, "maxPlausibleContacts", s.maxPlausibleContacts,
          ">= 0");
  require(s.softCfm >= 0.0 && std::isfinite(s.softCfm), "softCfm", s.softCfm,
          "finite and >= 0");
  m_settings = s;
}

const FrameStats& Dispatcher::lastFrameStats() const { return m_scheduler->stats(); }

void Dispatcher::lastMeshPairs(std::vector<MeshPairReport>& out) const {
  m_scheduler->meshPairs(out);
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
