// makeMethods: the method list of one run, from the --methods names and the ADB sweeps.
#include <stdexcept>

#include "adb_method.h"
#include "fcl_peer.h"
#include "gimpact_peer.h"
#include "methods.h"

namespace adb::tradeoff {

std::vector<std::unique_ptr<Method>> makeMethods(const std::vector<std::string>& names,
                                                 const std::vector<double>& pMins,
                                                 const std::vector<int>& kMins,
                                                 const std::vector<double>& budgetsUs,
                                                 const std::shared_ptr<SharedTree>& shared) {
  std::vector<std::unique_ptr<Method>> methods;
  for (const std::string& name : names) {
    if (name == "adb") {
      for (double p : pMins) {
        for (int k : kMins) {
          for (double budget : budgetsUs) {
            QuerySettings s;
            s.pMin = p;
            s.kMin = k;
            s.budgetMicros = budget;
            methods.push_back(std::make_unique<AdbMethod>(shared, s));
          }
        }
      }
    } else if (name == "exact") {
      QuerySettings s;
      s.mode = QueryMode::Exact;
      s.stopAtFirstHit = true;  // a yes/no answer, like FCL's first-contact mode
      methods.push_back(std::make_unique<AdbMethod>(shared, s));
    } else if (name == "gimpact") {
      methods.push_back(std::make_unique<GimpactPeer>());
    } else if (name == "fcl") {
      methods.push_back(std::make_unique<FclPeer>());
    } else {
      throw std::invalid_argument("unknown method '" + name + "'");
    }
  }
  return methods;
}

}  // namespace adb::tradeoff
