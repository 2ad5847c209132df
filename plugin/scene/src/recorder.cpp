#include "adb/scene/recorder.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <stdexcept>
#include <system_error>

namespace adb::scene {
namespace {

using Json = nlohmann::ordered_json;

// The q-quantile of `v` (nearest rank below), 0 when empty.
double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

// Per step and in all, with the ghosts as a share of the accepted plausible contacts and the
// missed as a share of the exact contacts of the audited pairs.
Json auditJson(const RunSummary::Audit& a) {
  const auto perStep = [&a](double total) { return total / a.steps; };
  const auto share = [](double part, double whole) { return whole > 0 ? part / whole : 0.0; };
  const double accepted = static_cast<double>(a.accepted), exact = static_cast<double>(a.exact);
  return {{"steps", a.steps},
          {"pairs", a.pairs},
          {"accepted", a.accepted},
          {"ghosts", a.ghosts},
          {"far_ghosts", a.farGhosts},
          {"exact", a.exact},
          {"missed", a.missed},
          {"missed_open", a.missedOpen},
          {"capped_pairs", a.cappedPairs},
          {"max_exact_pairs_per_pair", ContactAuditStats::kMaxExactPairs},
          {"mean_pairs", perStep(static_cast<double>(a.pairs))},
          {"mean_accepted", perStep(accepted)},
          {"mean_ghosts", perStep(static_cast<double>(a.ghosts))},
          {"max_ghosts", a.maxGhosts},
          {"mean_exact", perStep(exact)},
          {"mean_missed", perStep(static_cast<double>(a.missed))},
          {"max_missed", a.maxMissed},
          {"ghost_share", share(static_cast<double>(a.ghosts), accepted)},
          {"far_ghost_share", share(static_cast<double>(a.farGhosts), accepted)},
          {"missed_share", share(static_cast<double>(a.missed), exact)},
          {"missed_open_share", share(static_cast<double>(a.missedOpen), exact)},
          {"mean_ms", 1e-3 * perStep(a.micros)}};
}

const std::string& bodyName(const SceneWorld& world, std::uint32_t i) {
  return world.scene().bodies.at(i).name;
}

}  // namespace

std::array<StepCell, kStepColumns> stepCells(const StepRecord& r,
                                             const PenetrationReport* probe) {
  const FrameStats& f = r.frame;
  auto count = [](const char* column, double value) { return StepCell{column, value, true}; };
  auto real = [](const char* column, double value) { return StepCell{column, value, false}; };
  // The audit's columns hold -1 on a step not audited, as the probe's do.
  auto audited = [&f](double value) { return f.audit.on ? value : -1.0; };
  return {{count("step", r.step), real("time", r.time), real("seconds", r.seconds),
           real("budget_use", r.budgetUse), count("mesh_pairs", r.meshPairs),
           count("cut_pairs", r.cutPairs), real("mean_confidence", r.meanConfidence),
           real("worst_confidence", r.worstConfidence), count("overlapping", r.overlapping),
           count("events", r.events), count("contacts", r.contacts),
           real("penetration", r.penetration),
           real("probed_penetration", probe ? probe->depth : -1.0), real("kinetic", r.kinetic),
           real("energy", r.energy), count("at_rest", r.atRest),
           count("node_pairs", static_cast<double>(f.nodePairs)),
           count("needed_node_pairs", static_cast<double>(f.neededNodePairs)),
           count("from_scratch_node_pairs", static_cast<double>(f.fromScratchNodePairs)),
           count("other_node_pairs", static_cast<double>(f.otherNodePairs)),
           count("lost", r.lost), real("probed_relative", probe ? probe->relative : -1.0),
           real("probed_mean", probe ? probe->meanDepth : -1.0), real("frame_us", f.micros),
           real("contact_us", f.contactMicros), count("pairs", f.pairs),
           count("exact_pairs", f.exactPairs), count("quality_pairs", f.qualityPairs),
           count("exact_contacts", f.exactContacts),
           count("plausible_contacts", f.plausibleContacts),
           real("mean_completeness", f.meanCompleteness),
           real("worst_completeness", f.worstCompleteness),
           real("out_of_bounds", r.outOfBounds),
           real("out_of_bounds_relative", r.outOfBoundsRelative), count("threads", f.threads),
           real("parallel_us", f.parallelMicros), count("asleep", r.asleep),
           count("reused_pairs", f.reusedPairs),
           count("other_reused_pairs", f.otherReusedPairs),
           count("must_run_node_pairs", static_cast<double>(f.mustRunNodePairs)),
           count("audit_pairs", audited(f.audit.pairs)),
           count("audit_accepted", audited(f.audit.accepted)),
           count("audit_ghosts", audited(f.audit.ghosts)),
           count("audit_far_ghosts", audited(f.audit.farGhosts)),
           count("audit_exact", audited(static_cast<double>(f.audit.exact))),
           count("audit_missed", audited(static_cast<double>(f.audit.missed))),
           count("audit_missed_open", audited(static_cast<double>(f.audit.missedOpen))),
           real("audit_us", audited(f.audit.micros))}};
}

std::string effectsName(const Effects& effects) {
  switch (effects.kind) {
    case Effects::Kind::Overlap: return "overlap";
    case Effects::Kind::Contacts: return "contacts";
    case Effects::Kind::Dynamics: break;
  }
  std::string s = "dynamics";
  if (effects.friction) s += "+friction";
  if (effects.restitution) s += "+restitution";
  if (effects.sleeping) s += "+sleeping";
  if (effects.ccd) s += "+ccd";
  if (effects.softContacts) s += "+soft_contacts";
  return s;
}

Recorder::Recorder(const SceneWorld& world) {
  const BuildReport& b = world.built();
  m_summary.scene = world.scene().file.string();
  m_summary.description = world.scene().description;
  m_summary.backend = toString(world.backend());
  m_summary.effects = effectsName(world.scene().effects);
  m_summary.world = b.describe();
  m_summary.bodies = b.bodies;
  m_summary.triangles = b.triangles;
  m_summary.buildSeconds = b.buildSeconds;
  m_summary.worldBounds = world.scene().world.bounds.has_value();
  for (std::size_t i = 0; i < world.bodyCount(); ++i) m_summary.dynamicBodies += world.isDynamic(i);
}

Recorder::Recorder(const SceneWorld& world, const std::filesystem::path& folder)
    : Recorder(world) {
  m_folder = folder;
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) {
    throw std::runtime_error("cannot create folder '" + folder.string() + "': " + error.message());
  }
  open(m_steps, "steps.csv");
  const char* separator = "";
  for (const StepCell& cell : stepCells(StepRecord{})) {
    m_steps << separator << cell.column;
    separator = ",";
  }
  m_steps << '\n';
  if (world.scene().effects.kind == Effects::Kind::Overlap) open(m_events, "events.jsonl");
}

// Counts as integers (a double holds every count below 2^53 exactly), the rest as the
// stream writes a double.
void Recorder::writeRow(const std::array<StepCell, kStepColumns>& cells) {
  const char* separator = "";
  for (const StepCell& cell : cells) {
    m_steps << separator;
    if (cell.integer) {
      m_steps << static_cast<long long>(cell.value);
    } else {
      m_steps << cell.value;
    }
    separator = ",";
  }
  m_steps << '\n';
}

void Recorder::flush() {
  if (m_steps.is_open()) m_steps.flush();
  if (m_events.is_open()) m_events.flush();
}

void Recorder::open(std::ofstream& stream, const std::string& name) {
  const std::filesystem::path file = m_folder / name;
  stream.open(file);
  if (!stream) throw std::runtime_error("cannot write '" + file.string() + "'");
}

void Recorder::record(const SceneWorld& world, const PenetrationReport* probe) {
  const StepRecord& r = world.last();
  RunSummary& s = m_summary;
  ++s.steps;
  m_stepSeconds += r.seconds;
  s.maxStepMillis = std::max(s.maxStepMillis, 1e3 * r.seconds);
  m_budgetUse += r.budgetUse;
  s.meshPairSteps += r.meshPairs;
  s.cutPairSteps += r.cutPairs;
  if (r.meshPairs > 0) {
    m_confidence += r.meanConfidence;
    ++m_confidenceSteps;
    s.worstConfidence = std::min(s.worstConfidence, r.worstConfidence);
  }
  s.maxPenetration = std::max(s.maxPenetration, r.penetration);
  m_penetration += r.penetration;
  if (probe) {
    s.maxProbedPenetration = std::max(s.maxProbedPenetration, probe->depth);
    m_probedMean += probe->meanDepth;
    ++m_probes;
  }
  s.mostLost = std::max(s.mostLost, r.lost);
  s.lostAtEnd = r.lost;
  s.maxOutOfBounds = std::max(s.maxOutOfBounds, r.outOfBounds);
  s.maxOutOfBoundsRelative = std::max(s.maxOutOfBoundsRelative, r.outOfBoundsRelative);
  s.outOfBoundsAtEnd = r.outOfBounds;
  s.exactContacts += r.frame.exactContacts;
  s.plausibleContacts += r.frame.plausibleContacts;
  m_stepMillis.push_back(1e3 * r.seconds);
  m_pairMillis.push_back(1e-3 * r.frame.micros);
  s.atRestAtEnd = r.atRest;
  s.asleepAtEnd = r.asleep;
  if (s.dynamicBodies == 0 || r.asleep < s.dynamicBodies) {
    s.allAsleepFrom = -1;
  } else if (s.allAsleepFrom < 0) {
    s.allAsleepFrom = r.step;
  }
  s.kineticAtEnd = r.kinetic;
  if (s.steps == 1) s.energyAtStart = r.energy;
  s.energyAtEnd = r.energy;
  s.events += r.events;
  if (const ContactAuditStats& a = r.frame.audit; a.on) {
    RunSummary::Audit& t = s.audit;
    ++t.steps;
    t.pairs += a.pairs;
    t.accepted += a.accepted;
    t.ghosts += a.ghosts;
    t.farGhosts += a.farGhosts;
    t.exact += a.exact;
    t.missed += a.missed;
    t.missedOpen += a.missedOpen;
    t.cappedPairs += a.cappedPairs;
    t.maxGhosts = std::max<std::uint64_t>(t.maxGhosts, a.ghosts);
    t.maxMissed = std::max<std::uint64_t>(t.maxMissed, a.missed);
    t.micros += a.micros;
  }
  if (m_steps.is_open()) {
    writeRow(stepCells(r, probe));
  }
  if (m_events.is_open()) {
    for (const OverlapEvent& e : world.events()) {
      const Json line = {{"step", e.step},
                         {"time", e.time},
                         {"event", e.begin ? "begin" : "end"},
                         {"body0", bodyName(world, e.body0)},
                         {"body1", bodyName(world, e.body1)},
                         {"confidence", e.confidence}};
      m_events << line.dump() << '\n';
    }
  }
}

const RunSummary& Recorder::finish() {
  RunSummary& s = m_summary;
  if (s.steps > 0) {
    s.meanStepMillis = meanStepMillisSoFar();
    s.meanBudgetUse = m_budgetUse / s.steps;
    s.meanPenetration = m_penetration / s.steps;
  }
  if (m_confidenceSteps > 0) s.meanConfidence = m_confidence / m_confidenceSteps;
  if (m_probes > 0) s.meanProbedPenetration = m_probedMean / m_probes;
  s.p99StepMillis = percentile(m_stepMillis, 0.99);
  s.meanPairMillis = mean(m_pairMillis);
  s.p99PairMillis = percentile(m_pairMillis, 0.99);
  if (m_folder.empty()) return s;
  m_steps.flush();
  m_events.flush();
  Json j = {{"scene", s.scene},
            {"description", s.description},
            {"backend", s.backend},
            {"effects", s.effects},
            {"world", s.world},
            {"steps", s.steps},
            {"bodies", s.bodies},
            {"dynamic_bodies", s.dynamicBodies},
            {"triangles", s.triangles},
            {"build_seconds", s.buildSeconds},
            {"mean_step_ms", s.meanStepMillis},
            {"max_step_ms", s.maxStepMillis},
            {"p99_step_ms", s.p99StepMillis},
            {"mean_pair_ms", s.meanPairMillis},
            {"p99_pair_ms", s.p99PairMillis},
            {"exact_contacts", s.exactContacts},
            {"plausible_contacts", s.plausibleContacts},
            {"mean_budget_use", s.meanBudgetUse},
            {"mesh_pair_steps", s.meshPairSteps},
            {"cut_pair_steps", s.cutPairSteps},
            {"mean_confidence", s.meanConfidence},
            {"worst_confidence", s.worstConfidence},
            {"max_penetration", s.maxPenetration},
            {"mean_penetration", s.meanPenetration},
            {"max_probed_penetration", s.maxProbedPenetration},
            {"mean_probed_penetration", s.meanProbedPenetration},
            {"most_lost", s.mostLost},
            {"lost_at_end", s.lostAtEnd},
            {"max_out_of_bounds", s.maxOutOfBounds},
            {"max_out_of_bounds_relative", s.maxOutOfBoundsRelative},
            {"out_of_bounds_at_end", s.outOfBoundsAtEnd},
            {"at_rest_at_end", s.atRestAtEnd},
            {"asleep_at_end", s.asleepAtEnd},
            {"all_asleep_from", s.allAsleepFrom},
            {"kinetic_at_end", s.kineticAtEnd},
            {"energy_at_start", s.energyAtStart},
            {"energy_at_end", s.energyAtEnd},
            {"events", s.events}};
  if (s.audit.steps > 0) j["audit"] = auditJson(s.audit);
  const std::filesystem::path file = m_folder / "summary.json";
  std::ofstream out(file);
  out << j.dump(2) << '\n';
  if (!out) throw std::runtime_error("cannot write '" + file.string() + "'");
  return s;
}

}  // namespace adb::scene
