// Recorder: what a scene run did, step by step, summed up, and written out.
//
// With a folder it writes
// - steps.csv: one row per step (time, budget use, pairs, cut pairs, confidence, contacts,
//   penetration, energy, bodies at rest; the columns are in docs/scenes.md);
// - events.jsonl: one JSON object per overlap event, for scenes that ask for overlap;
// - summary.json: the run's summary (RunSummary), when finish() is called.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "adb/scene/scene_world.h"

namespace adb::scene {

/// A run in figures.
struct RunSummary {
  std::string scene;        ///< the scene file
  std::string description;
  std::string backend;
  std::string effects;      ///< "overlap", "contacts" or "dynamics+friction+..."
  std::string world;        ///< BuildReport::describe()
  int steps = 0;
  int bodies = 0;
  std::size_t triangles = 0;
  double buildSeconds = 0.0;
  double meanStepMillis = 0.0;
  double maxStepMillis = 0.0;
  double p99StepMillis = 0.0;
  double meanPairMillis = 0.0;  ///< adb's dispatcher: its pairs' time per step (FrameStats)
  double p99PairMillis = 0.0;
  std::uint64_t exactContacts = 0, plausibleContacts = 0;  ///< summed over the steps
  double meanBudgetUse = 0.0;        ///< 0 without a budget
  std::uint64_t meshPairSteps = 0;   ///< mesh-mesh pairs summed over the steps
  std::uint64_t cutPairSteps = 0;    ///< of those, cut by the budget
  double meanConfidence = 1.0;       ///< per step's mean, averaged over steps with pairs
  double worstConfidence = 1.0;
  double maxPenetration = 0.0;       ///< deepest contact point of any step
  double meanPenetration = 0.0;      ///< each step's deepest, averaged
  double maxProbedPenetration = -1;  ///< from the geometry (probe), -1 when not probed
  /// Each body's deepest penetration, averaged over the bodies and the probes; -1: no probe.
  double meanProbedPenetration = -1;
  bool worldBounds = false;          ///< the scene sets world.bounds (out_of_bounds applies)
  int mostLost = 0;                  ///< bodies lost (StepRecord::lost), at the worst step
  int lostAtEnd = 0;
  /// StepRecord::outOfBounds: at the worst step (also over the body's size), and at the end.
  double maxOutOfBounds = 0.0;
  double maxOutOfBoundsRelative = 0.0;
  double outOfBoundsAtEnd = 0.0;
  int dynamicBodies = 0;
  int atRestAtEnd = 0;
  int asleepAtEnd = 0;               ///< bodies Bullet has deactivated, after the last step
  /// The step from which every dynamic body slept to the end; -1 if they did not all sleep
  /// at the end.
  int allAsleepFrom = -1;
  double kineticAtEnd = 0.0;
  double energyAtStart = 0.0;        ///< after the first step
  double energyAtEnd = 0.0;
  std::uint64_t events = 0;
  /// The contact audit (adb::FrameSettings::auditContacts, adb::ContactAuditStats) summed
  /// over the audited steps, and the worst step's ghosts and misses; steps 0: not audited.
  struct Audit {
    int steps = 0;
    std::uint64_t pairs = 0, accepted = 0, ghosts = 0, farGhosts = 0;
    std::uint64_t exact = 0, missed = 0, missedOpen = 0, cappedPairs = 0;
    std::uint64_t maxGhosts = 0, maxMissed = 0;
    double micros = 0.0;
  } audit;
};

std::string effectsName(const Effects& effects);

/// One cell of a steps.csv row: its column's name and the step's value.
struct StepCell {
  const char* column;
  double value;
  bool integer;  ///< a count, written without a fraction
};
inline constexpr std::size_t kStepColumns = 48;
/// A step's row of steps.csv, column by column, in the file's order (docs/scenes.md says what
/// each means): the one place the columns are listed, for the file and for the Python
/// module's World.stats(). `probe`: the step's penetration from the geometry, if measured
/// (its columns hold -1 otherwise).
std::array<StepCell, kStepColumns> stepCells(const StepRecord& r,
                                             const PenetrationReport* probe = nullptr);

class Recorder {
 public:
  /// Records without writing.
  explicit Recorder(const SceneWorld& world);
  /// Records into `folder` (created). Throws std::runtime_error naming a file it cannot write.
  Recorder(const SceneWorld& world, const std::filesystem::path& folder);

  /// After each step. `probe`: the step's penetration from the geometry, if measured.
  void record(const SceneWorld& world, const PenetrationReport* probe = nullptr);
  /// Hands what was recorded so far to the files (a reader may open them mid-run).
  void flush();
  /// Writes summary.json (with a folder) and returns the summary.
  const RunSummary& finish();
  const RunSummary& summary() const { return m_summary; }
  /// The mean wall clock of the steps recorded so far, in milliseconds (0 before any): what
  /// finish() gives as RunSummary::meanStepMillis, mid-run (a picture's caption).
  double meanStepMillisSoFar() const {
    return m_summary.steps > 0 ? 1e3 * m_stepSeconds / m_summary.steps : 0.0;
  }

 private:
  void open(std::ofstream& stream, const std::string& name);
  void writeRow(const std::array<StepCell, kStepColumns>& cells);

  std::filesystem::path m_folder;
  std::ofstream m_steps, m_events;
  RunSummary m_summary;
  double m_stepSeconds = 0.0, m_budgetUse = 0.0, m_confidence = 0.0, m_penetration = 0.0;
  int m_confidenceSteps = 0;
  double m_probedMean = 0.0;
  std::vector<double> m_stepMillis, m_pairMillis;
  int m_probes = 0;
};

}  // namespace adb::scene
