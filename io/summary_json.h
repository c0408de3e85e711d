#pragma once
/// Parts shared by the summary.json writers of io/ (internal to io: nlohmann::json is a
/// private dependency of the module, so only io's .cpp files include this).
#include <nlohmann/json.hpp>

#include "blocks/block_merge.h"
#include "io/summary.h"

namespace rockmass::io {

/// The JSON type of summaries (keys keep their insertion order).
using SummaryJson = nlohmann::ordered_json;

/// The fields every summary starts with: version, command, scene, name, seed, stages,
/// effects.
SummaryJson summaryHeader(const RunInfo& run);

/// Adds "timings" (seconds per stage); call it last: the only part that differs between
/// identical runs.
void appendTimings(SummaryJson& j, const Timings& timings);

/// A number, or null where JSON has none (an infinite or undefined value).
SummaryJson finiteOrNull(double value);

/// The `glued_blocks` object of a DDA or stability summary: min_volume, blocks_before,
/// blocks_after, merged, merged_volume, left_small, merged_across_materials,
/// merged_across_materials_volume (blocks::MergeReport).
SummaryJson gluedBlocksJson(const blocks::MergeReport& glued);

/// The `uplift` list of a DDA or stability summary: per structure {structure, force [3] (N),
/// vertical (N, upward > 0)}.
SummaryJson upliftJson(const std::vector<StructureUplift>& uplift);

}  // namespace rockmass::io
