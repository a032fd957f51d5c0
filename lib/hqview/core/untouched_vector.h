#pragma once
// UntouchedVector<T>: a std::vector whose resize(n) leaves trivial elements
// uninitialised (default-initialised, not value-initialised), for large
// arrays that a parallel loop fills whole right after. A fresh page costs
// its first touch, which the kernel zeroes; with std::vector's resize that
// is one memset on one core, here the loop's first writes, spread over
// every core. Everything else (values given, copies, push_back) works as in
// std::vector.

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace hq {

template <class T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  using value_type = T;
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T, class U>
bool operator==(const DefaultInitAllocator<T>&, const DefaultInitAllocator<U>&) noexcept {
  return true;
}

template <class T>
using UntouchedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace hq
