#pragma once
// Warnings that name what HQView does not (yet) do on a mesh, as opposed to
// a defect of the input (report.json `warnings` holds both): the batch index
// gives a mesh with only these the neutral status "limited analysis", not
// "input warning" (docs/contract.md, "Batch").

#include <algorithm>
#include <iterator>
#include <string_view>

namespace hq {

inline constexpr std::string_view kSurfaceBoundaryErrorViewsNotDrawn =
    "the boundary-error views of surface meshes are not drawn yet (report.json boundary_error has the numbers)";

// No longer written (the viewer draws surface meshes since issue 47 part
// L), but an index.json of an earlier HQView may hold it: `merge` and the
// batch page still read it as a limitation.
inline constexpr std::string_view kSurfaceViewerNotWrittenBefore =
    "the viewer of surface meshes is not written yet (the views are drawn)";

// A batch row's --compare (its manifest's compare column) beside a surface
// mesh, on either side: the mesh is analysed alone (AnalyzeOptions::
// limitations_as_warnings); a single run refuses it (exit 3).
inline constexpr std::string_view kSurfaceCompareNotAvailable =
    "--compare: surface meshes are not compared yet (this mesh was analysed without its compare mesh)";

inline constexpr std::string_view kLimitationWarnings[] = {kSurfaceBoundaryErrorViewsNotDrawn,
                                                           kSurfaceViewerNotWrittenBefore, kSurfaceCompareNotAvailable};

// True when `warning` is one of kLimitationWarnings (exactly).
inline bool is_limitation_warning(std::string_view warning) {
  return std::find(std::begin(kLimitationWarnings), std::end(kLimitationWarnings), warning) !=
         std::end(kLimitationWarnings);
}

}  // namespace hq
