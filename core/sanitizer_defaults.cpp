// Default run-time options of the AddressSanitizer build (KASUMI_SANITIZE: cmake/KasumiTarget.cmake
// adds this file to every executable). Options given in ASAN_OPTIONS still win.
//
// intercept_tls_get_addr=0. Up to GCC 13 and LLVM 16 the runtime's __tls_get_addr interceptor
// takes a dynamic TLS block whose address is 16 mod 4096 for a glibc < 2.25 block with a header
// and reads the two words before it as the block's start and size. Since glibc 2.25 the block is
// plain malloc'ed memory, so when one happens to land at that offset (here: thread-locals of the
// dlopen'd libkasumi_vdb.so, depending on the heap's history, i.e. on the scene and options)
// LeakSanitizer records a garbage range (seen: 0x114b-0x80000224d) and its exit-time tracer dies
// scanning it: "Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error", exit 1
// after a clean run (google/sanitizers#1322; Debian 12 has GCC 12 and glibc 2.36). Without the
// interceptor LeakSanitizer only scans less as roots, so it can report more, never hide a leak.
extern "C" const char* __asan_default_options();
extern "C" const char* __asan_default_options() {
    return "intercept_tls_get_addr=0";
}
