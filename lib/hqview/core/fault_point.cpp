#include "hqview/core/fault_point.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <string>

namespace hq {
namespace {

struct Armed {
  std::string name;  // empty: no point armed
  long nth = 1;
};

const Armed& armed() {
  static const Armed a = [] {
    Armed out;
    const char* value = std::getenv("HQVIEW_FAULT_POINT");
    if (value == nullptr) return out;
    out.name = value;
    if (const std::size_t at = out.name.find('@'); at != std::string::npos) {
      out.nth = std::max(1L, std::atol(out.name.c_str() + at + 1));
      out.name.resize(at);
    }
    return out;
  }();
  return a;
}

std::atomic<long> g_hits{0};

}  // namespace

void fault_point(const char* name) {
  const Armed& a = armed();
  if (a.name.empty() || a.name != name) return;
  if (g_hits.fetch_add(1) + 1 == a.nth) ::kill(::getpid(), SIGKILL);
}

}  // namespace hq
