#pragma once
/// Helpers shared by the surface tests.
#include "core/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace kasumi::test {

/// The message of the input error f throws, or "" (and a test failure) if it throws none.
inline std::string input_error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "no error thrown";
    return "";
}

/// Writes text to a file under the build tree (one folder per test, so parallel ctest runs do
/// not collide) and returns its path.
inline std::string write_temp_file(const std::string& name, const std::string& text) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir = std::filesystem::path(KASUMI_BINARY_DIR) / "test_tmp" /
                                      "surface" / info->test_suite_name() / info->name();
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
}

}  // namespace kasumi::test
