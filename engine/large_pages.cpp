// Every allocation of 2 MiB or more starts on a 2 MiB boundary and asks the kernel for 2 MiB pages (Linux
// transparent huge pages, madvise). Beyond the caches a step walks a dozen arrays and jumps to far partners; on
// 4 KiB pages each of those jumps may cost a page-table walk, and a block of 10^6 particles spans 170 000 pages.
//
// This replaces the global operator new and delete (C++ [replacement.functions]) in every program that links the
// engine: std::vector reaches them through std::allocator. The linker takes this object from the engine's archive
// because each program asks for operator new before the C++ runtime library, which comes last, defines it. Small
// allocations go to malloc as before. The advice is only advice: a kernel that refuses it (huge pages off, or none
// free) leaves 4 KiB pages, and the numbers are the same either way.
#include <stdlib.h>
#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kLargePage = std::size_t(2) << 20;
constexpr std::size_t kPage = 4096;

void* allocate(std::size_t n) {
  if (n < kLargePage) return std::malloc(n == 0 ? 1 : n);
  void* p = nullptr;
  if (posix_memalign(&p, kLargePage, n) != 0) return nullptr;
  // Only the whole 2 MiB pages inside [p, p + n) become large pages; the tail keeps 4 KiB pages, so no memory is
  // spent on padding.
  madvise(p, (n + kPage - 1) / kPage * kPage, MADV_HUGEPAGE);
  return p;
}

}  // namespace

void* operator new(std::size_t n) {
  for (;;) {
    if (void* p = allocate(n)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

// The runtime's delete frees as well; defined here so that new and delete stay a pair under tools that replace
// one of them (sanitizers).
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
