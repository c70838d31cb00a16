#pragma once
// Shared by the test folders: the message of the input error a call throws.
#include "core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace kasumi {

/// The message of the input error (exit code 3) `f` throws, or "" when it throws none.
template <typename F>
std::string input_error(F f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.exit_code(), 3);
        return e.what();
    }
    return "";
}

}  // namespace kasumi
