#include "hqview/core/shared_library.h"

#include <dlfcn.h>

namespace hq {

SharedLibrary::SharedLibrary(const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    // RTLD_LOCAL: its symbols serve only the lookups made through symbol().
    handle_ = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_ != nullptr) {
      name_ = name;
      error_.clear();
      return;
    }
    const char* why = dlerror();
    if (!error_.empty()) error_ += "; ";
    error_ += why != nullptr ? why : name + ": cannot be loaded";
  }
}

void* SharedLibrary::symbol(const char* symbol) const {
  return handle_ != nullptr ? dlsym(handle_, symbol) : nullptr;
}

}  // namespace hq
