#pragma once
// A shared library opened when first needed (dlopen), for the dependencies
// only some runs use: the OSMesa renderer (Mesa and LLVM: about 65 ms of
// relocations and page faults at every process start, paid twice by the
// huge-page re-exec) and netCDF for Exodus II (about 17 ms). A library once
// opened stays loaded for the life of the process.

#include <string>
#include <vector>

namespace hq {

class SharedLibrary {
 public:
  // Opens the first of `names` (sonames, tried in order) that loads. On
  // failure is_open() is false and error() says what the loader said.
  explicit SharedLibrary(const std::vector<std::string>& names);

  bool is_open() const { return handle_ != nullptr; }
  const std::string& error() const { return error_; }
  const std::string& name() const { return name_; }

  // The address of `symbol`, or nullptr when the library lacks it.
  void* symbol(const char* symbol) const;

  // Sets `f` to the function `symbol` of the library; false when missing.
  template <class F>
  bool load(F& f, const char* symbol) const {
    f = reinterpret_cast<F>(this->symbol(symbol));
    return f != nullptr;
  }

 private:
  void* handle_ = nullptr;
  std::string name_;
  std::string error_;
};

}  // namespace hq
