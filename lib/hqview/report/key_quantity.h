#pragma once
// What a report.json number is a number of, in words, for the keys whose
// name alone is ambiguous: three "scaled Jacobian" statistics (per cell, per
// corner, per vertex) and the metrics' num_degenerate (cells where a Verdict
// metric is undefined, not degenerate cells), in the words of the mesh's
// cells (a hex mesh's "per hex", a surface mesh's "per face"). hqview diff prints it beside
// such keys; index.html's cards and tables say the same in their labels.

#include <string>
#include <string_view>

namespace hq {

// Which cells a report's quality numbers run over, for their words: only
// hexes; volume cells of several kinds (issue 46); the quads and triangles
// of a surface mesh (issue 47).
enum class MeshCells { hex, volume, surface };

// "hexes", "cells" or "faces": the cells' name in a row label.
std::string cells_plural(MeshCells cells);

// The quantity of a report.json key (dotted path, e.g.
// "quality.metrics.condition.num_degenerate"), or "" when the key's name
// says it.
std::string key_quantity(std::string_view key, MeshCells cells = MeshCells::hex);

}  // namespace hq
