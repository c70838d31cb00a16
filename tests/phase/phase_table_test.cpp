#include "phase/phase_table.h"

#include "core/error.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace kasumi {
namespace {

std::string write_temp(const std::string& name, const std::string& text) {
    const std::string path = std::string(KASUMI_BINARY_DIR) + "/" + name;
    std::ofstream(path) << text;
    return path;
}

TEST(PhaseTable, NormalisesAndComputesExactMeanCosine) {
    // p linear in mu: p = 1 + mu (unnormalised) has ∫ = 2 and ∫ mu p = 2/3, so <mu> = 1/3.
    const PhaseTable t({-1.0, 1.0}, {0.0, 2.0}, "linear");
    EXPECT_NEAR(t.eval(0.0), 1.0 / (4.0 * kPiD), 1e-15);
    EXPECT_NEAR(t.mean_cosine(), 1.0 / 3.0, 1e-15);
    // CDF (1 + mu)² / 4 = u inverts to mu = 2 sqrt(u) - 1.
    for (const double u : {0.0, 0.09, 0.25, 0.64, 1.0})
        EXPECT_NEAR(t.sample_cosine(u), 2.0 * std::sqrt(u) - 1.0, 1e-12) << u;
}

TEST(PhaseTable, ReadsCsvWithHeaderAndComments) {
    const std::string path =
        write_temp("phase_table_test.csv", "theta_deg,value\n# comment\n0,4\n90,1\n180,2\n");
    const PhaseTable t = read_phase_table_csv(path);
    ASSERT_EQ(t.mu().size(), 3u);
    EXPECT_NEAR(t.eval(1.0) / t.eval(0.0), 4.0, 1e-12);
    EXPECT_NEAR(t.eval(-1.0) / t.eval(0.0), 2.0, 1e-12);
}

TEST(PhaseTable, RejectsBadTables) {
    EXPECT_THROW(read_phase_table_csv(write_temp("bad1.csv", "0,1\n90,-1\n180,1\n")), Error);
    EXPECT_THROW(read_phase_table_csv(write_temp("bad2.csv", "0,1\n90,1\n")), Error);
    EXPECT_THROW(read_phase_table_csv(write_temp("bad3.csv", "0,1\n90,1\n80,1\n180,1\n")), Error);
    EXPECT_THROW(read_phase_table_csv(write_temp("bad4.csv", "0,0\n180,0\n")), Error);
    EXPECT_THROW(read_phase_table_csv(write_temp("bad5.csv", "0,1\nninety,1\n180,1\n")), Error);
    EXPECT_THROW(read_phase_table_csv("/nonexistent/table.csv"), Error);
}

}  // namespace
}  // namespace kasumi
