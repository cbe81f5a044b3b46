#include "trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace discreel::job {
namespace {

std::string number(double v) {
    std::string s;
    append_number(s, v);
    return s;
}

TEST(TraceNumberTest, ShortestForm) {
    EXPECT_EQ(number(0.1), "0.1");
    EXPECT_EQ(number(-3.0), "-3");
    EXPECT_EQ(number(0.0), "0");
    EXPECT_EQ(number(1e-9), "1e-09");
}

TEST(TraceNumberTest, ReadsBackBitForBit) {
    std::uint64_t state = 0x9e3779b97f4a7c15ULL;
    for (int i = 0; i < 10000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        double v = 0;
        std::memcpy(&v, &state, sizeof v);
        if (!std::isfinite(v)) continue;
        const std::string text = number(v);
        const double back = std::strtod(text.c_str(), nullptr);
        EXPECT_EQ(std::memcmp(&v, &back, sizeof v), 0) << text;
    }
}

}  // namespace
}  // namespace discreel::job
