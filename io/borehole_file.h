#pragma once
/// Borehole files of analysis.rqd.boreholes: the collars (`file`) and the measured RQD log
/// (`measured`). Both are CSV with a header row; blank lines are skipped. Any problem is an
/// InputError located at "file:line: ...".
#include <filesystem>
#include <vector>

#include "geometry/box.h"
#include "rqd/borehole.h"

namespace rockmass::io {

/// Reads `id,x,y,z,azimuth,plunge,length` rows: id is text (unique, no commas); (x, y, z) the
/// collar (m); azimuth clockwise from North (deg, [0, 360]); plunge positive downward (deg,
/// [-90, 90]); length along the hole (m, > 0). The whole hole must lie in `domain`.
std::vector<rqd::Borehole> readBoreholes(const std::filesystem::path& file,
                                         const geometry::Box& domain);

/// Reads `id,from,to,rqd` rows of a measured log: id names one of `holes`; 0 <= from < to
/// <= the hole's length (m); rqd in [0, 100] (%). Returns the intervals in file order.
std::vector<rqd::LoggedInterval> readMeasuredLog(const std::filesystem::path& file,
                                                 const std::vector<rqd::Borehole>& holes);

}  // namespace rockmass::io
