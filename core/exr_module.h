#pragma once
/// The interface between kasumi and its OpenEXR module (libkasumi_exr.so, built from exr_imf.cpp
/// and exr_half.cpp). OpenEXR's C++ library and what it pulls in (Iex, IlmThread, Imath) cost
/// ~3M instructions and ~60 page faults to bind at every start (3 ms of CPU), yet a render
/// writes its default ZIP EXR through OpenEXR's small core C library (exr_io.cpp): only reading
/// EXRs and writing them with piz, rle or none need Imf, so exr_io.cpp loads the module
/// (core/module_loader.h) on the first such call.
#include "core/exr_io.h"

namespace kasumi {

/// Bumped whenever ExrModuleApi, Image, ExrChannelView or ExrWriteReport change layout.
constexpr int kExrModuleAbi = 1;

struct ExrModuleApi {
    int abi = kExrModuleAbi;
    /// Writes `channels` (checked) to `path` with `compression` (not ZIP) through
    /// Imf::OutputFile; `report` holds the HALF channels' range (scanned before), the flushes are
    /// added to it. Throws what Imf throws.
    void (*write)(const Image& header, const std::vector<ExrChannelView>& channels,
                  const std::string& path, ExrCompression compression, int threads,
                  ExrWriteReport& report) = nullptr;
    /// read_exr.
    Image (*read)(const std::string& path) = nullptr;
};

/// File name of the module (override: $KASUMI_EXR_MODULE) and the C symbol it exports:
/// `const ExrModuleApi* NAME()`.
constexpr const char* kExrModuleFile = "libkasumi_exr.so";
constexpr const char* kExrModuleEntry = "kasumi_exr_module_api";

}  // namespace kasumi
