#pragma once
/// Loading the project's own shared modules (volume/grid/vdb_module.h: OpenVDB; core/ocio_module.h:
/// OpenColorIO) with dlopen on first use, so a process that does not need a heavy library never
/// pays for binding its symbols.
#include <mutex>
#include <string>
#include <vector>

namespace kasumi {

struct ModuleSpec {
    const char* what;        ///< for messages, e.g. "OpenVDB module"
    const char* needed_for;  ///< for messages, e.g. "to read or write .vdb files"
    const char* file;        ///< file name, e.g. "libkasumi_vdb.so"
    const char* env;         ///< variable that overrides the search, e.g. "KASUMI_VDB_MODULE"
    const char* build_path;  ///< where the build tree wrote it ("" if unknown)
    const char* entry;       ///< C symbol of `const T* entry()`; T starts with `int abi`
    int abi;                 ///< the ABI version T::abi must equal
};

/// The binary holding kasumi's code: the executable for the CLI, the extension module
/// (site-packages/kasumi/_kasumi*.so) when kasumi is imported into Python; empty if unknown.
std::string code_object_path();

/// Where `spec.file` is looked for, in order: $env if set (then only there); the directory of the
/// binary holding kasumi's code (the executable, or the Python extension module: the package
/// installs its modules beside it); the executable's directory; <executable's directory>/../lib/
/// kasumi (installed CLI); `spec.build_path` (so tests and benchmarks find it without
/// installing). No path appears twice.
std::vector<std::string> module_search_paths(const ModuleSpec& spec);

/// Loads the first module found (RTLD_NOW | RTLD_LOCAL; never closed) and returns what its entry
/// returned. Throws Error (Runtime, exit code 1) naming every path tried and why it failed. Not
/// cached: callers call it through module_api.
const void* load_module(const ModuleSpec& spec);

/// The module's API, loaded by the first call (thread-safe) and kept for the process; one module
/// per API type. A call that throws leaves it unloaded, so the next call tries again.
template <class Api>
const Api& module_api(const ModuleSpec& spec) {
    static const Api* api = nullptr;
    static std::once_flag once;
    std::call_once(once, [&spec] { api = static_cast<const Api*>(load_module(spec)); });
    return *api;
}

}  // namespace kasumi
