// makeMethods: the method list of one run, from the --methods names and the sweeps.
#include "methods.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "adb_method.h"
#include "box_first.h"
#include "fcl_peer.h"
#include "gimpact_peer.h"
#include "root_boxes_method.h"

namespace adb::tradeoff {
namespace {

using MethodList = std::vector<std::unique_ptr<Method>>;

void addAdbTimeSettings(const Options& o, const std::shared_ptr<SharedTree>& shared,
                        MethodList& out) {
  for (double p : o.pMins) {
    for (int k : o.kMins) {
      for (double budget : o.budgetsUs) {
        QuerySettings s;
        s.pMin = p;
        s.kMin = k;
        s.budgetMicros = budget;
        s.adbKey = o.adbKey;
        out.push_back(std::make_unique<AdbMethod>(shared, s, "adb"));
      }
    }
  }
}

// ADB under a work budget (node pairs, no time budget): reproducible, unlike the clock.
void addAdbWorkSettings(const Options& o, const std::shared_ptr<SharedTree>& shared,
                        MethodList& out) {
  for (double p : o.pMins) {
    for (int k : o.kMins) {
      for (std::uint64_t pairs : o.budgetPairs) {
        QuerySettings s;
        s.pMin = p;
        s.kMin = k;
        s.budgetNodePairs = pairs;
        s.adbKey = o.adbKey;
        out.push_back(std::make_unique<AdbMethod>(shared, s, workMethodName(pairs)));
      }
    }
  }
}

QuerySettings exactSettings(double budgetUs) {
  QuerySettings s;
  s.mode = QueryMode::Exact;
  s.stopAtFirstHit = true;  // a yes/no answer, like FCL's first-contact mode
  s.budgetMicros = budgetUs;
  return s;
}

// Under a time budget only: without one, exact-cut would be exact and box-first another
// exact method, neither of which says what a budget buys.
void addBudgeted(const std::string& name, const Options& o,
                 const std::shared_ptr<SharedTree>& shared, MethodList& out) {
  for (double budget : o.budgetsUs) {
    if (!std::isfinite(budget)) continue;
    if (name == "exact-cut") {
      out.push_back(std::make_unique<AdbMethod>(shared, exactSettings(budget), "exact-cut"));
    } else {
      out.push_back(std::make_unique<BoxFirstMethod>(shared, budget));
    }
  }
}

}  // namespace

std::string workMethodName(std::uint64_t pairs) { return "adb-work:" + std::to_string(pairs); }

MethodList makeMethods(const Options& o, const std::shared_ptr<SharedTree>& shared) {
  MethodList methods;
  for (const std::string& name : o.methods) {
    if (name == "adb") {
      addAdbTimeSettings(o, shared, methods);
      addAdbWorkSettings(o, shared, methods);
    } else if (name == "exact") {
      methods.push_back(std::make_unique<AdbMethod>(
          shared, exactSettings(std::numeric_limits<double>::infinity()), "exact"));
    } else if (name == "exact-cut" || name == "box-first") {
      addBudgeted(name, o, shared, methods);
    } else if (name == "root-boxes") {
      methods.push_back(std::make_unique<RootBoxesMethod>());
    } else if (name == "gimpact") {
      methods.push_back(std::make_unique<GimpactPeer>());
    } else if (name == "fcl") {
      methods.push_back(std::make_unique<FclPeer>());
    } else {
      throw std::invalid_argument("unknown method '" + name + "'");
    }
  }
  if (std::find(o.methods.begin(), o.methods.end(), "adb") == o.methods.end()) {
    addAdbWorkSettings(o, shared, methods);  // --budget-pairs asked for them
  }
  return methods;
}

}  // namespace adb::tradeoff
