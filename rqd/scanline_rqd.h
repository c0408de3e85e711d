#pragma once
/// RQD along one scanline from the positions where it crosses fractures.
///
/// A scanline is a segment of length L; the fracture hits are distances from its start,
/// sorted, in [0, L]. Hits closer than a merge distance to the previous kept hit count as
/// one fracture (a disc crossed twice near its rim, two coincident discs). The intact pieces
/// are the gaps between successive kept hits, clipped at 0 and L, and
/// RQD(t) = 100 * (sum of the pieces of length >= t) / L, in percent (Deere 1964 uses
/// t = 0.1 m; RQD(t) for other t follows Priest & Hudson 1976).
#include <span>
#include <vector>

namespace rockmass::rqd {

/// Default distance below which two hits are one fracture (unit: metres).
constexpr double kDefaultMergeDistance = 1e-3;

/// Lengths (m) of the intact pieces, in order along the scanline, between the merged `hits`
/// (m, sorted, in [0, length]) on a scanline of `length` (m, > 0); hits within
/// `merge_distance` (m, >= 0) of the previous kept hit are dropped. Pieces of zero length
/// (a hit exactly at 0 or at `length`) are left out. The pieces sum to `length`.
/// Throws std::invalid_argument for a non-positive length, a negative merge distance,
/// unsorted hits or hits outside [0, length].
std::vector<double> intactPieces(std::span<const double> hits, double length,
                                 double merge_distance = kDefaultMergeDistance);

/// RQD(t) in percent [0, 100] for each threshold t (m, >= 0) in `thresholds`, from the
/// intact pieces of intactPieces(hits, length, merge_distance); a piece of length exactly t
/// counts. Throws std::invalid_argument as intactPieces does, and for a negative threshold.
std::vector<double> rqd(std::span<const double> hits, double length,
                        std::span<const double> thresholds,
                        double merge_distance = kDefaultMergeDistance);

/// The same RQD(t) values written into `out` (one per threshold, same size as `thresholds`),
/// without allocating: for loops over many scanlines. Throws as rqd() does, and
/// std::invalid_argument when `out` and `thresholds` differ in size.
void rqd(std::span<const double> hits, double length, std::span<const double> thresholds,
         std::span<double> out, double merge_distance = kDefaultMergeDistance);

/// Expected RQD(t) in percent, 100 (1 + lambda t) exp(-lambda t), for exponentially
/// distributed spacings of mean 1/lambda on an infinite scanline; `frequency` lambda is in
/// fractures per metre (>= 0), `threshold` t in metres (>= 0). Priest, S. D. & Hudson, J. A.
/// (1976), "Discontinuity spacings in rock", Int. J. Rock Mech. Min. Sci. 13, 135-148.
/// Throws std::invalid_argument for a negative or non-finite argument.
double priestHudsonRqd(double frequency, double threshold);

}  // namespace rockmass::rqd
