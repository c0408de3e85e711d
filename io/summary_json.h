#pragma once
/// Internal to io: the JSON pieces every summary.json shares (summary.cpp, dda_summary.cpp).
#include <nlohmann/json.hpp>

#include "io/summary.h"

namespace rockmass::io {

/// Key order is insertion order, so that summaries are byte-identical run to run.
using Json = nlohmann::ordered_json;

/// The fields every summary starts with: version, command, scene, name, seed, stages,
/// effects.
Json runHeader(const RunInfo& run);

/// Appends "timings" (seconds per stage). Timings go last: the only part that differs
/// between identical runs.
void appendTimings(Json& j, const Timings& timings);

}  // namespace rockmass::io
