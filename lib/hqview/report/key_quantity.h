#pragma once
// What a report.json number is a number of, in words, for the keys whose
// name alone is ambiguous: three "scaled Jacobian" statistics (per hex, per
// corner, per vertex) and the metrics' num_degenerate (hexes where a Verdict
// metric is undefined, not degenerate hexes). hqview diff prints it beside
// such keys; index.html's cards and tables say the same in their labels.

#include <string>
#include <string_view>

namespace hq {

// The quantity of a report.json key (dotted path, e.g.
// "quality.metrics.condition.num_degenerate"), or "" when the key's name
// says it.
std::string key_quantity(std::string_view key);

}  // namespace hq
