#pragma once
// Named points where the fault tests kill the process (tests/e2e/
// check_faults.py): with HQVIEW_FAULT_POINT=NAME (or NAME@K, the K-th time
// the point is reached) in the environment, the process sends itself
// SIGKILL there, so a test can stop a run exactly between two writes
// (docs/testing.md, "Faults"). Without the variable a point costs one
// relaxed load.
//
// The points: "bundle-before-swap" (a bundle complete in its temporary
// directory, not yet in place), "batch-before-index" (every bundle written,
// no index yet), "batch-index-write" (index.json written, the other index
// files not).

namespace hq {

void fault_point(const char* name);

}  // namespace hq
