// Same scene, same bits: a busy scene hashed after two seconds, compared across runs and with a
// pinned value (busy_scene.hpp; the `arch` tests check it on other targets and builds).
#include <cstdint>

#include <gtest/gtest.h>

#include "busy_scene.hpp"

namespace discreel::physics {
namespace {

TEST(Determinism, BusySceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = testing::run_busy_scene();
    EXPECT_EQ(testing::run_busy_scene(), first);
    EXPECT_EQ(first, testing::busy_scene_hash) << first;
}

TEST(Determinism, MixedSceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = testing::run_mixed_scene();
    EXPECT_EQ(testing::run_mixed_scene(), first);
    EXPECT_EQ(first, testing::mixed_scene_hash) << first;
}

TEST(Determinism, RestingSceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = testing::run_resting_scene();
    EXPECT_EQ(testing::run_resting_scene(), first);
    EXPECT_EQ(first, testing::resting_scene_hash) << first;
}

TEST(Determinism, JointSceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = testing::run_joint_scene();
    EXPECT_EQ(testing::run_joint_scene(), first);
    EXPECT_EQ(first, testing::joint_scene_hash) << first;
}

TEST(Determinism, HeavyLightSceneGivesTheSameBitsEveryRun) {
    const std::uint64_t first = testing::run_heavy_light_scene();
    EXPECT_EQ(testing::run_heavy_light_scene(), first);
    EXPECT_EQ(first, testing::heavy_light_scene_hash) << first;
}

}  // namespace
}  // namespace discreel::physics
