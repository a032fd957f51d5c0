// libFuzzer target for hq::read_vtk_legacy (vtk_legacy_reader.h).
#include "fuzz/fuzz_reader.h"
#include "hqview/io/vtk_legacy_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return hq::fuzz::run_reader(data, size, [](std::string_view b, const std::string& n) { return hq::read_vtk_legacy(b, n); });
}
