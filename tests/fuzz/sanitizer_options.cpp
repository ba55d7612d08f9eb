// The address sanitizer's defaults for the fuzz targets: no stack trace recorded at each
// malloc and free (most of an execution's cost in yaml-cpp's many small allocations). Every
// check stays on; a report then shows the faulting access's stack but not where the memory was
// allocated or freed: replay the input with ASAN_OPTIONS=malloc_context_size=30 for those.
extern "C" const char* __asan_default_options() { return "malloc_context_size=0"; }
