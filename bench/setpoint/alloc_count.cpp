// bench/setpoint_stream.py: heap allocations counted per thread, linked into the bench's
// bridges only. malloc and friends defined in the program take the place of glibc's for
// every library (Fast DDS included); each counts, then calls glibc's own. The counter is
// initial-exec TLS: reading or bumping it never allocates.
#include <cstddef>
#include <new>

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
__thread unsigned long thread_allocs __attribute__((tls_model("initial-exec"))) = 0;
}

extern "C" {
unsigned long rapid_bench_thread_allocs() { return thread_allocs; }

void* malloc(std::size_t n) {
    ++thread_allocs;
    return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
    ++thread_allocs;
    return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
    ++thread_allocs;
    return __libc_realloc(p, n);
}
void* memalign(std::size_t align, std::size_t n) {
    ++thread_allocs;
    return __libc_memalign(align, n);
}
void* aligned_alloc(std::size_t align, std::size_t n) {
    ++thread_allocs;
    return __libc_memalign(align, n);
}
int posix_memalign(void** out, std::size_t align, std::size_t n) {
    ++thread_allocs;
    void* p = __libc_memalign(align, n);
    if (p == nullptr) return 12;  // ENOMEM
    *out = p;
    return 0;
}
void free(void* p) { __libc_free(p); }
}
