// A std::vector whose resize leaves new elements of a trivial type uninitialized: its allocator
// default-initializes where std::allocator value-initializes (zeroes). A large array that a
// parallel loop fills is then first touched by the threads that fill it, so the kernel faults its
// pages in and zeroes them on every core, not on the one thread of a memset before the loop
// (where fresh memory is dear, as on some virtual machines, that memset made the 1M-cell mesh's
// cell faces a serial stage).
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace mlsdeform
{
template <typename T>
struct DefaultInitAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() noexcept = default;
  template <typename U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U; // default-initialization: no zeroing of a trivial type
  }
  template <typename U, typename... Arguments>
  void construct(U* p, Arguments&&... arguments)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Arguments>(arguments)...);
  }
};

template <typename T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;
} // namespace mlsdeform
