#pragma once
// Happens-before edges for ThreadSanitizer (`make test-tsan`) where a hand-off between threads
// goes through oneTBB's scheduler: Debian's libtbb is not built with the sanitizer, so TSan does
// not see that a task starts after the code that spawned it, nor that wait_for_all() returns after
// the tasks ended. Code that hands data to a task marks the hand-off with HappensBefore(key) on
// the giving side and HappensAfter(key) on the taking side. Both compile to nothing without TSan.
#if defined(__SANITIZE_THREAD__)
#include <sanitizer/tsan_interface.h>
#endif

namespace aperture::perception {

inline void HappensBefore([[maybe_unused]] const void* key) {
#if defined(__SANITIZE_THREAD__)
  __tsan_release(const_cast<void*>(key));
#endif
}

inline void HappensAfter([[maybe_unused]] const void* key) {
#if defined(__SANITIZE_THREAD__)
  __tsan_acquire(const_cast<void*>(key));
#endif
}

}  // namespace aperture::perception
