#include "pipeline.hpp"

#include <chrono>
#include <cstdint>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "pipeline_queue.hpp"

namespace discreel::job {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::size_t frame_bytes(const render::RendererDef& def) {
    return std::size_t{4} * static_cast<std::size_t>(def.width) *
           static_cast<std::size_t>(def.height);
}

// The caller's warm renderer, or a new one kept in `own`.
Expected<render::Renderer*> renderer_for(const PipelineDef& def,
                                         std::optional<render::Renderer>& own) {
    if (def.warm_renderer != nullptr) return def.warm_renderer;
    auto made = render::Renderer::create(def.renderer);
    if (!made) return made.error();
    own = std::move(*made);
    return &*own;
}

PipelineResult run_on_one_thread(const PipelineDef& def, const PipelineStages& stages) {
    PipelineResult result;
    std::optional<render::Renderer> own;
    auto found = renderer_for(def, own);
    if (!found) {
        result.status = found.error();
        return result;
    }
    render::Renderer* renderer = *found;
    result.renderer_info = renderer->renderer_info();
    std::vector<std::uint8_t> pixels(frame_bytes(def.renderer));
    int encoded = 0;
    for (int frame = def.first_frame; frame < def.frame_count; ++frame) {
        if (stages.should_stop()) {
            result.stopped = true;
            return result;
        }
        auto start = Clock::now();
        const render::FrameScene* scene = stages.simulate(frame);
        result.busy.simulate += seconds_since(start);
        if (scene == nullptr) continue;
        start = Clock::now();
        auto image = renderer->draw_into(*scene, pixels);
        result.busy.render += seconds_since(start);
        if (!image) {
            result.status = image.error();
            return result;
        }
        start = Clock::now();
        Status written = stages.encode(*image);
        result.busy.encode += seconds_since(start);
        if (!written) {
            result.status = written;
            return result;
        }
        stages.encoded(++encoded);
    }
    return result;
}

// Gives the calling thread the lowest priority (nice 19; Linux applies nice per thread),
// best effort: where the call fails, the thread keeps its priority. Nothing restores it: only
// the producer threads call this, and they end with the run.
void yield_to_other_threads() {
    setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);
}

// What the three threads share. Slots move free -> drawable -> encodable -> free; a slot is
// touched only by the stage that last popped it, so the slots themselves need no lock.
class ThreadedRun {
public:
    ThreadedRun(const PipelineDef& def, const PipelineStages& stages)
        : def_(def), stages_(stages), slots_(static_cast<std::size_t>(def.slots)),
          free_(def.slots), drawable_(def.slots), encodable_(def.slots) {
        for (Slot& slot : slots_) slot.pixels.resize(frame_bytes(def.renderer));
        for (int i = 0; i < def.slots; ++i) free_.push(i);
    }

    PipelineResult run() {
        // The simulate stage gets a thread of its own too, so that lowering its priority never
        // touches the caller's.
        std::thread simulate_thread([this] { guarded([this] { simulate_stage(); }); });
        std::thread render_thread([this] { guarded([this] { render_stage(); }); });
        std::thread encode_thread([this] { guarded([this] { encode_stage(); }); });
        simulate_thread.join();
        render_thread.join();
        encode_thread.join();
        // What a stage threw reaches the caller as if the stages ran on its thread.
        if (exception_) std::rethrow_exception(exception_);
        result_.stopped = stopped_;
        return std::move(result_);
    }

private:
    struct Slot {
        render::FrameScene scene;          // vectors keep their capacity from frame to frame
        std::vector<std::uint8_t> pixels;
        ImageView image;
    };

    void simulate_stage() {
        if (def_.encoder_first) yield_to_other_threads();
        for (int frame = def_.first_frame; frame < def_.frame_count; ++frame) {
            if (stages_.should_stop()) {
                stopped_ = true;
                cancel_all();
                return;
            }
            const auto start = Clock::now();
            const render::FrameScene* scene = stages_.simulate(frame);
            result_.busy.simulate += seconds_since(start);
            if (scene == nullptr) continue;
            const std::optional<int> slot = free_.pop();
            if (!slot) return;
            const auto copy_start = Clock::now();
            slots_[static_cast<std::size_t>(*slot)].scene = *scene;
            result_.busy.simulate += seconds_since(copy_start);
            drawable_.push(*slot);
        }
        drawable_.close();
    }

    void render_stage() {
        if (def_.encoder_first) yield_to_other_threads();
        std::optional<render::Renderer> own;
        auto found = renderer_for(def_, own);
        if (!found) return fail(found.error());
        render::Renderer* renderer = *found;
        result_.renderer_info = renderer->renderer_info();
        double busy = 0;
        while (const std::optional<int> index = drawable_.pop()) {
            Slot& slot = slots_[static_cast<std::size_t>(*index)];
            const auto start = Clock::now();
            auto image = renderer->draw_into(slot.scene, slot.pixels);
            busy += seconds_since(start);
            if (!image) return fail(image.error());
            slot.image = *image;
            encodable_.push(*index);
        }
        encodable_.close();
        result_.busy.render = busy;
    }

    void encode_stage() {
        int encoded = 0;
        double busy = 0;
        while (const std::optional<int> index = encodable_.pop()) {
            const auto start = Clock::now();
            Status written = stages_.encode(slots_[static_cast<std::size_t>(*index)].image);
            busy += seconds_since(start);
            if (!written) return fail(written.error());
            stages_.encoded(++encoded);
            free_.push(*index);
        }
        result_.busy.encode = busy;
    }

    // Runs a stage; an exception it throws cancels the other stages and is kept for run().
    template <class Stage>
    void guarded(Stage stage) {
        try {
            stage();
        } catch (...) {
            {
                std::lock_guard lock(failure_mutex_);
                if (!exception_) exception_ = std::current_exception();
            }
            cancel_all();
        }
    }

    void fail(Error error) {
        {
            std::lock_guard lock(failure_mutex_);
            if (result_.status) result_.status = std::move(error);
        }
        cancel_all();
    }

    void cancel_all() {
        free_.cancel();
        drawable_.cancel();
        encodable_.cancel();
    }

    const PipelineDef& def_;
    const PipelineStages& stages_;
    std::vector<Slot> slots_;
    SlotQueue free_;
    SlotQueue drawable_;
    SlotQueue encodable_;
    std::mutex failure_mutex_;
    PipelineResult result_;
    std::exception_ptr exception_;   // the first exception a stage threw
    bool stopped_ = false;   // written by the simulate thread only, read after it ends
};

}  // namespace

PipelineResult run_pipeline(const PipelineDef& def, const PipelineStages& stages) {
    if (!def.threaded) return run_on_one_thread(def, stages);
    return ThreadedRun(def, stages).run();
}

}  // namespace discreel::job
