#pragma once
// The render loop as three stages: simulate (physics up to a frame, then the frame's
// description), render (OSMesa draw and readback) and encode. Threaded, each stage runs on its
// own thread and a small fixed pool of frame slots (description + pixel buffer) circulates
// between them, so a frame is drawn into the buffer the encoder later reads and nothing is
// allocated per frame. The OSMesa context is created, used and destroyed on the render thread.
// Frames reach the encoder in order either way, so the output bytes do not depend on the mode.
#include <functional>
#include <string>

#include "discreel/expected.hpp"
#include "discreel/image.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"

namespace discreel::job {

struct PipelineDef {
    int first_frame = 0;             // simulate() is called for frames first_frame ..
    int frame_count = 0;             // .. frame_count - 1
    render::RendererDef renderer;
    // A renderer of that size to draw with instead of creating one (its context is made
    // current on the drawing thread); it must not be drawing elsewhere meanwhile.
    render::Renderer* warm_renderer = nullptr;
    bool threaded = true;            // false: every stage on the calling thread, frame by frame
    int slots = 3;                   // frames in flight when threaded: one per stage
    // Threaded only: the simulate and render threads run at the lowest priority (nice 19), so
    // they use the cycles the encoder's threads leave idle instead of preempting them, and
    // work ahead into the free slots while the encoder is busy.
    bool encoder_first = false;
};

struct PipelineStages {
    // Advances the simulation to `frame` and returns what to draw, or nullptr for a frame that
    // is simulated but not drawn. Called on one thread (the caller's when not threaded), frames
    // in order. The returned scene is copied into a slot before the next call.
    std::function<const render::FrameScene*(int frame)> simulate;
    // Every drawn frame, in order, on one thread.
    std::function<Status(const ImageView& image)> encode;
    // After each encode() with the number of frames encoded so far, on the same thread.
    std::function<void(int frames_encoded)> encoded;
    // Polled once per frame; true stops every stage as soon as it finishes what it is doing.
    std::function<bool()> should_stop;
};


struct PipelineResult {
    Status status;                   // the first failure of any stage
    bool stopped = false;            // should_stop() asked for it; the output is incomplete
    std::string renderer_info;       // GL_RENDERER and GL_VERSION
    StageSeconds busy;
};

PipelineResult run_pipeline(const PipelineDef& def, const PipelineStages& stages);

}  // namespace discreel::job
