#include "hqview/render/gl_api.h"

#include <optional>
#include <string>

#include "hqview/core/error.h"
#include "hqview/core/shared_library.h"

namespace hq {
namespace {

struct Loaded {
  GlApi api;
  std::string error;  // empty when every entry point was found
};

Loaded load_gl_api() {
  Loaded loaded;
  // Debian 12's soname first; the unversioned name where only the
  // development link is installed.
  const SharedLibrary library({"libOSMesa.so.8", "libOSMesa.so"});
  if (!library.is_open()) {
    loaded.error = "cannot load libOSMesa (Debian package libosmesa6): " + library.error();
    return loaded;
  }
  GlApi& api = loaded.api;
  const auto need = [&](auto& f, const std::string& symbol) {
    if (!library.load(f, symbol.c_str()) && loaded.error.empty())
      loaded.error = library.name() + " has no " + symbol + " (Mesa >= 20 is needed)";
  };
#define HQ_LOAD_GL(name) need(api.name, "gl" #name);
#define HQ_LOAD_OSMESA(name) need(api.name, "OSMesa" #name);
  HQ_GL_FUNCTIONS(HQ_LOAD_GL)
  HQ_OSMESA_FUNCTIONS(HQ_LOAD_OSMESA)
#undef HQ_LOAD_GL
#undef HQ_LOAD_OSMESA
  return loaded;
}

}  // namespace

const GlApi& gl_api() {
  static const Loaded loaded = load_gl_api();
  if (!loaded.error.empty()) throw RenderError(loaded.error);
  return loaded.api;
}

}  // namespace hq
