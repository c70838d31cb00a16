#include "core/module_loader.h"

#include "core/error.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

namespace kasumi {

namespace {

std::string executable_dir() {
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : exe.parent_path().string();
}

std::string code_object_dir() {
    const std::string object = code_object_path();
    return object.empty() ? std::string() : std::filesystem::path(object).parent_path().string();
}

}  // namespace

std::string code_object_path() {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&code_object_path), &info) == 0 ||
        info.dli_fname == nullptr)
        return {};
    std::error_code ec;
    const std::filesystem::path object = std::filesystem::canonical(info.dli_fname, ec);
    return ec ? std::string() : object.string();
}

std::vector<std::string> module_search_paths(const ModuleSpec& spec) {
    if (const char* env = std::getenv(spec.env); env != nullptr && *env != '\0')
        return {env};
    std::vector<std::string> paths;
    const auto add = [&paths](const std::string& path) {
        for (const std::string& p : paths)
            if (p == path)
                return;
        paths.push_back(path);
    };
    const std::string object_dir = code_object_dir();
    if (!object_dir.empty())
        add(object_dir + "/" + spec.file);
    const std::string dir = executable_dir();
    if (!dir.empty()) {
        add(dir + "/" + spec.file);
        add(dir + "/../lib/kasumi/" + spec.file);
    }
    const std::string built = spec.build_path;
    if (!built.empty())
        add(built);
    return paths;
}

const void* load_module(const ModuleSpec& spec) {
    std::string tried;
    const auto note = [&](const std::string& path, const std::string& why) {
        tried += (tried.empty() ? " " : "; ") + path + " (" + why + ")";
    };
    for (const std::string& path : module_search_paths(spec)) {
        if (!std::filesystem::exists(path)) {
            note(path, "no such file");
            continue;
        }
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            const char* why = dlerror();
            note(path, why != nullptr ? why : "cannot load");
            continue;
        }
        // Never closed: objects it made (grids, processors) live until the process ends.
        using Entry = const void* (*)();
        const auto entry = reinterpret_cast<Entry>(dlsym(handle, spec.entry));
        const void* api = entry != nullptr ? entry() : nullptr;
        if (api == nullptr || *static_cast<const int*>(api) != spec.abi) {
            note(path, std::string("not a kasumi ") + spec.what + " of this build");
            continue;
        }
        return api;
    }
    throw Error(ErrorKind::Runtime, std::string("cannot load the ") + spec.what + " " + spec.file +
                                        " (needed " + spec.needed_for + "); tried" + tried +
                                        "; set " + spec.env + " to its path");
}

}  // namespace kasumi
