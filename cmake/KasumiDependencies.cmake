# Every dependency comes from Debian 12's packages (see README). Known quirks are handled here,
# in one place.
find_package(Threads REQUIRED)
find_package(glm REQUIRED)
find_package(nlohmann_json 3.9 REQUIRED)
find_package(CLI11 REQUIRED)
# TBB before Embree: Embree's config looks for it.
find_package(TBB REQUIRED)
find_package(embree 3 REQUIRED)
find_package(OpenEXR 3 REQUIRED)
find_package(ZLIB REQUIRED)

# Debian's OpenVDB config lives outside CMake's default module path and needs Boost iostreams.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)

# Debian's OpenColorIOConfig.cmake points at /include; pkg-config is correct.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)
