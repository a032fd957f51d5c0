// libFuzzer target for hq::read_off (polygon_reader.h).
#include "fuzz/fuzz_reader.h"
#include "hqview/io/polygon_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return hq::fuzz::run_reader(data, size, [](std::string_view b, const std::string& n) { return hq::read_off(b, n); });
}
