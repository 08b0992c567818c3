// give_freed_heap_back (plmap/core/freed_heap.hpp).

#include <plmap/core/freed_heap.hpp>

#include <cstdlib>  // defines __GLIBC__ where the C library is glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace plmap {

void give_freed_heap_back() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace plmap
