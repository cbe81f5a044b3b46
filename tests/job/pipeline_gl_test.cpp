// run_pipeline in-process with hand-made stages: every frame reaches the encoder once and in
// order, in both modes, and a failing encoder or a stop request ends the run early.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "pipeline.hpp"

namespace discreel::job {
namespace {

// Frame n is a 16x8 image of one colour whose red channel is n, so the encoder can tell which
// frame it got.
struct FakeClip {
    render::FrameScene scene;
    std::vector<int> simulated;
    std::vector<int> encoded_red;
    int stop_after = -1;   // frames simulated before should_stop() says yes; -1: never

    PipelineStages stages() {
        return {
            .simulate = [this](int frame) -> const render::FrameScene* {
                simulated.push_back(frame);
                if (frame % 2 == 1) return nullptr;   // odd frames are simulated, not drawn
                scene.background = {static_cast<float>(frame) / 255.0f, 0, 0, 1};
                return &scene;
            },
            .encode = [this](const ImageView& image) -> Status {
                if (image.width != 16 || image.height != 8) return Error{"wrong size"};
                encoded_red.push_back(image.rgba[0]);
                if (encoded_red.size() == 4 && fail_at_fourth) return Error{"disk full"};
                return {};
            },
            .encoded = [this](int done) { progress.push_back(done); },
            .should_stop = [this] {
                return stop_after >= 0 && static_cast<int>(simulated.size()) >= stop_after;
            },
        };
    }

    bool fail_at_fourth = false;
    std::vector<int> progress;
};

PipelineDef small(bool threaded) {
    return {.frame_count = 20, .renderer = {.width = 16, .height = 8}, .threaded = threaded};
}

TEST(PipelineGLTest, EveryDrawnFrameReachesTheEncoderInOrder) {
    for (const bool threaded : {true, false}) {
        FakeClip clip;
        const PipelineResult result = run_pipeline(small(threaded), clip.stages());
        ASSERT_TRUE(result.status) << result.status.error().message;
        EXPECT_FALSE(result.stopped);
        EXPECT_EQ(clip.simulated.size(), 20u);
        const std::vector<int> even{0, 2, 4, 6, 8, 10, 12, 14, 16, 18};
        EXPECT_EQ(clip.encoded_red, even) << "threaded " << threaded;
        EXPECT_EQ(clip.progress, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
        EXPECT_NE(result.renderer_info.find("llvmpipe"), std::string::npos);
    }
}

TEST(PipelineGLTest, AnEncoderFailureStopsEveryStage) {
    for (const bool threaded : {true, false}) {
        FakeClip clip;
        clip.fail_at_fourth = true;
        const PipelineResult result = run_pipeline(small(threaded), clip.stages());
        ASSERT_FALSE(result.status);
        EXPECT_EQ(result.status.error().message, "disk full");
        EXPECT_EQ(clip.encoded_red.size(), 4u);
        // Three slots: simulation runs at most a few drawn frames ahead of the failure.
        EXPECT_LT(clip.simulated.size(), 20u) << "threaded " << threaded;
    }
}

TEST(PipelineGLTest, AStopRequestEndsTheRunEarly) {
    for (const bool threaded : {true, false}) {
        FakeClip clip;
        clip.stop_after = 6;
        const PipelineResult result = run_pipeline(small(threaded), clip.stages());
        EXPECT_TRUE(result.status);
        EXPECT_TRUE(result.stopped);
        EXPECT_EQ(clip.simulated.size(), 6u);
        EXPECT_LE(clip.encoded_red.size(), 3u);
    }
}

TEST(PipelineGLTest, ARendererThatCannotStartIsAnError) {
    FakeClip clip;
    PipelineDef def = small(true);
    def.renderer.width = 0;
    const PipelineResult result = run_pipeline(def, clip.stages());
    ASSERT_FALSE(result.status);
    EXPECT_EQ(result.status.error().message, "renderer size must be positive, got 0x8");
    EXPECT_TRUE(clip.encoded_red.empty());
}

// A stage that throws (say, out of memory) must not take the process down with
// std::terminate: the other stages stop and the caller gets the exception, as it would if the
// stages ran on its thread.
TEST(PipelineGLTest, AnExceptionInAStageReachesTheCaller) {
    for (const bool threaded : {false, true}) {
        FakeClip clip;
        PipelineStages stages = clip.stages();
        stages.simulate = [&, simulate = stages.simulate](int frame) {
            if (frame == 6) throw std::runtime_error("out of luck");
            return simulate(frame);
        };
        try {
            (void)run_pipeline(small(threaded), stages);
            ADD_FAILURE() << "no exception, threaded " << threaded;
        } catch (const std::runtime_error& e) {
            EXPECT_STREQ(e.what(), "out of luck");
        }
        EXPECT_LE(clip.encoded_red.size(), 3u);   // frames 0, 2, 4 at most
    }
}

int this_thread_nice() {
    return getpriority(PRIO_PROCESS, static_cast<id_t>(gettid()));
}

// encoder_first: the simulate stage runs at nice 19; the encoding thread and the caller keep
// their priority. (The render thread is set up by the same code as the simulate one.)
TEST(PipelineGLTest, EncoderFirstLowersTheProducersOnly) {
    const int before = this_thread_nice();
    if (before >= 19) GTEST_SKIP() << "already at the lowest priority";
    std::vector<int> simulate_nice, encode_nice;
    FakeClip clip;
    PipelineStages stages = clip.stages();
    stages.simulate = [&, simulate = stages.simulate](int frame) {
        simulate_nice.push_back(this_thread_nice());
        return simulate(frame);
    };
    stages.encode = [&, encode = stages.encode](const ImageView& image) {
        encode_nice.push_back(this_thread_nice());
        return encode(image);
    };
    PipelineDef def = small(true);
    def.encoder_first = true;
    def.slots = 6;
    const PipelineResult result = run_pipeline(def, stages);
    ASSERT_TRUE(result.status) << result.status.error().message;
    EXPECT_EQ(simulate_nice, std::vector<int>(20, 19));
    EXPECT_EQ(encode_nice, std::vector<int>(10, before));
    EXPECT_EQ(this_thread_nice(), before);
    EXPECT_EQ(clip.encoded_red, (std::vector<int>{0, 2, 4, 6, 8, 10, 12, 14, 16, 18}));
}

}  // namespace
}  // namespace discreel::job
