#pragma once
// Warnings that name what HQView does not (yet) do on a mesh, as opposed to
// a defect of the input (report.json `warnings` holds both): the batch index
// gives a mesh with only these the neutral status "limited analysis", not
// "input warning" (docs/contract.md, "Batch").

#include <algorithm>
#include <iterator>
#include <string_view>

namespace hq {

// Warnings this HQView never writes (it draws the boundary-error views and
// the viewer of surface meshes) but an index.json written by an earlier
// version may hold: `merge` and the batch page read them as limitations.
inline constexpr std::string_view kSurfaceBoundaryErrorViewsNotDrawnBefore =
    "the boundary-error views of surface meshes are not drawn yet (report.json boundary_error has the numbers)";
inline constexpr std::string_view kSurfaceViewerNotWrittenBefore =
    "the viewer of surface meshes is not written yet (the views are drawn)";

inline constexpr std::string_view kLimitationWarnings[] = {kSurfaceBoundaryErrorViewsNotDrawnBefore,
                                                           kSurfaceViewerNotWrittenBefore};

// True when `warning` is one of kLimitationWarnings (exactly).
inline bool is_limitation_warning(std::string_view warning) {
  return std::find(std::begin(kLimitationWarnings), std::end(kLimitationWarnings), warning) !=
         std::end(kLimitationWarnings);
}

}  // namespace hq
