#pragma once
// The interactive 3D viewer of a bundle (viewer.html): the hex boundary
// coloured by a chosen field, the aggregated glyphs, overlap markers,
// intersecting cells and the interior cells under the glyph threshold,
// drawn by three.js (Debian's libjs-three r111, embedded in the binary) as
// classic scripts, so the page opens from file:// with no server and no
// network. The mesh goes into viewer/data.js as one JSON object with
// base64 binary arrays (quantised positions, 8-bit colour indices), loaded
// by a plain <script src>. docs/viewer.md has the format.

#include <string>
#include <vector>

#include "hqview/report/report_model.h"

namespace hq {

struct ViewerFile {
  std::string relative_path;  // "viewer.html", "viewer/data.js", ...
  std::string text;
};

// The viewer's files for a bundle. Deterministic (no thread-dependent order).
std::vector<ViewerFile> viewer_files(const ReportModel& model);

// JSON text made safe inside a <script> element or a .js file: <, >, & and
// U+2028/2029 written as \u escapes (they only occur inside JSON strings).
std::string script_safe_json(std::string json_text);

// RFC 4648 base64 with padding.
std::string base64_encode(const void* bytes, std::size_t size);

}  // namespace hq
