// Writing queries.csv. Poses use %.17g (round-trips a double exactly); distances %.12g (the
// parser rounds them to 12 digits, so this is exact too), p_min and budgets %.15g (decimal
// input round-trips); times are integral nanoseconds.
#include "query_csv.h"

#include <cmath>
#include <stdexcept>

#include "csv_format.h"

namespace adb::tradeoff {

const char* const kQueryCsvHeader =
    "model,triangles,method,p_min,k_min,budget_us,distance,rotation,"
    "a_qw,a_qx,a_qy,a_qz,a_tx,a_ty,a_tz,b_qw,b_qx,b_qy,b_qz,b_tx,b_ty,b_tz,"
    "collides,confidence,time_ns,node_pairs";

namespace {

std::string full(double v) { return format("%.17g", v); }

std::string poseFields(const QuaternionPose& p) {
  return full(p.q.w()) + ',' + full(p.q.x()) + ',' + full(p.q.y()) + ',' + full(p.q.z()) + ',' +
         full(p.t.x()) + ',' + full(p.t.y()) + ',' + full(p.t.z());
}

}  // namespace

QueryCsv::QueryCsv(const std::string& path) : m_path(path), m_out(path, std::ios::trunc) {
  if (!m_out) throw std::runtime_error("cannot write " + path);
  m_out << kQueryCsvHeader << '\n';
}

void QueryCsv::write(const std::string& model, std::size_t triangles, const std::string& method,
                     const MethodParams& params, double distance, int rotation,
                     const StudyPose& pose, const QueryRecord& r) {
  m_out << csvField(model) << ',' << triangles << ',' << method << ',' << methodParamFields(params)
        << ',' << format("%.12g", distance) << ',' << rotation << ',' << poseFields(pose.a) << ','
        << poseFields(pose.b) << ',' << (r.collides ? 1 : 0) << ',' << format("%.9g", r.confidence)
        << ',' << format("%.0f", std::round(r.timeNs)) << ',';
  if (r.nodePairs >= 0) m_out << r.nodePairs;
  m_out << '\n';
}

void QueryCsv::flush() {
  m_out.flush();
  if (!m_out) throw std::runtime_error("writing " + m_path + " failed");
}

}  // namespace adb::tradeoff
