#pragma once
/// summary.json of `rockmass run`: one file for the whole chain of stages. It holds the
/// run header, the keys of every stage's own summary (the same keys `rockmass dfn`,
/// `blocks`, `rqd` and `dda` write, so scripts read either), what the run itself adds
/// (quick mode, section, unavailable stages, files, figures) and, last, the timings.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/box.h"
#include "io/summary.h"

namespace rockmass::io {

/// One stage's own summary.json text (from formatDfnSummary, formatBlocksSummary, ...).
struct StageSummary {
  std::string stage;  ///< "dfn", "cut", "rqd", "dda"
  std::string json;   ///< the stage's summary.json text
};

/// What `rockmass run` adds to the stages' summaries.
struct RunReport {
  bool quick = false;    ///< run --quick
  geometry::Box domain;  ///< the domain box the run used (the quick box)
  std::string cutter;    ///< cutter used, empty when no blocks were cut
  std::string section;   ///< section plane label, e.g. "y=10"; empty: none
  /// Stages the scene asks for that this build cannot run: (stage, reason).
  std::vector<std::pair<std::string, std::string>> unavailable;
  std::vector<std::string> files;     ///< output files written (names, sorted)
  std::vector<std::string> figures;   ///< PNG figures written (names, sorted)
  std::vector<std::string> warnings;  ///< e.g. no python for the figures
};

/// Merges the stage summaries in order under `run`'s header: a key of a stage summary that
/// is not yet present is copied to the top level; a key already present with the same value
/// is skipped (e.g. `discs`, `blocks`); one with a different value goes under an object
/// named after the stage (e.g. `dda.pieces`), so nothing is lost. Header keys (version,
/// command, scene, name, seed, stages, effects) come from `run`. Then the `run` object
/// (quick, domain, cutter, section, unavailable, files, figures, warnings) and, last,
/// `timings`: run.timings followed by the stages' own extra timing keys (cut_split,
/// dda_phases, dda_steps, ...). Throws std::runtime_error for a stage text that is not JSON.
std::string formatRunSummary(const RunInfo& run, const std::vector<StageSummary>& stages,
                             const RunReport& report);

}  // namespace rockmass::io
