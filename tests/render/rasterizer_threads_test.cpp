// set_rasterizer_threads() chooses llvmpipe's thread count through Mesa's LP_NUM_THREADS, and
// a value the user put in the environment wins. Needs no GL context: it only sets the
// variable Mesa reads when the first context is created.
#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "discreel/render.hpp"

namespace discreel::render {
namespace {

class RasterizerThreadsTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (const char* value = std::getenv("LP_NUM_THREADS")) saved_ = value;
        unsetenv("LP_NUM_THREADS");
    }
    void TearDown() override {
        if (saved_) {
            setenv("LP_NUM_THREADS", saved_->c_str(), 1);
        } else {
            unsetenv("LP_NUM_THREADS");
        }
    }

private:
    std::optional<std::string> saved_;
};

TEST_F(RasterizerThreadsTest, SetsTheCountWhenTheUserDidNot) {
    set_rasterizer_threads(0);
    ASSERT_NE(std::getenv("LP_NUM_THREADS"), nullptr);
    EXPECT_STREQ(std::getenv("LP_NUM_THREADS"), "0");
}

TEST_F(RasterizerThreadsTest, KeepsTheUsersChoice) {
    setenv("LP_NUM_THREADS", "3", 1);
    set_rasterizer_threads(0);
    EXPECT_STREQ(std::getenv("LP_NUM_THREADS"), "3");
}

}  // namespace
}  // namespace discreel::render
