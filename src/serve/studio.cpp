// The studio's sessions: a playback with checkpoints and a warm renderer per scene.
#include "studio.hpp"

#include <algorithm>
#include <cmath>

#include "discreel/encode.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"

namespace discreel::serve {

using Clock = std::chrono::steady_clock;

struct Studio::Session {
    explicit Session(scene::Scene s)
        : scene(std::move(s)),
          // A checkpoint a second: going back re-simulates at most a second of physics.
          playback(scene, {.checkpoint_every = scene.video.fps}) {}

    // Shows `frame`, recording the contact events of frames never shown before.
    Expected<const render::FrameScene*> show(int frame, bool drawn,
                                             const std::function<bool()>& stop) {
        auto shown = playback.show(frame, drawn, stop);
        for (const physics::ContactEvent& e : playback.take_events()) {
            if (e.t <= recorded_until) continue;   // seen before going back
            if (e.kind == physics::ContactEvent::Kind::contact) events.push_back(e);
        }
        recorded_until = std::max(recorded_until, playback.world().time());
        return shown;
    }

    Expected<ImageView> draw(int frame, const std::function<bool()>& stop) {
        if (!renderer) {
            auto made = render::Renderer::create(
                {.width = scene.video.width, .height = scene.video.height});
            if (!made) return made.error();
            renderer.emplace(std::move(*made));
        }
        auto view = show(frame, true, stop);
        if (!view) {
            renderer->release();
            return view.error();
        }
        auto image = renderer->draw(**view);
        // The next request may come on another thread, and an evicted session's renderer is
        // destroyed on whichever thread evicts it.
        renderer->release();
        return image;
    }

    std::mutex mutex;                 // one request at a time draws on it
    const scene::Scene scene;         // the playback keeps a reference to it
    job::Playback playback;
    std::optional<render::Renderer> renderer;
    std::vector<physics::ContactEvent> events;   // contacts, in order, of the frames shown
    double recorded_until = -1;       // seconds: events up to here are in `events`
};

namespace {

// Stops a request that simulates past its time.
std::function<bool()> deadline_after(double seconds) {
    const auto deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    return [deadline] { return Clock::now() > deadline; };
}

}  // namespace

Studio::Studio(StudioDef def) : def_(def) {}
Studio::~Studio() = default;

std::size_t Studio::sessions() const {
    std::lock_guard lock(mutex_);
    return sessions_.size();
}

std::shared_ptr<Studio::Session> Studio::session(const std::string& key, job::RenderPlan& plan) {
    std::lock_guard lock(mutex_);
    const auto found = std::find_if(sessions_.begin(), sessions_.end(),
                                    [&](const auto& entry) { return entry.first == key; });
    if (found != sessions_.end()) {
        sessions_.splice(sessions_.begin(), sessions_, found);
        return sessions_.front().second;
    }
    sessions_.emplace_front(key, std::make_shared<Session>(std::move(plan.scene)));
    // A session in use stays alive through its shared_ptr until that request ends.
    while (sessions_.size() > std::max<std::size_t>(1, def_.sessions)) sessions_.pop_back();
    return sessions_.front().second;
}

Expected<StudioFrame> Studio::frame(const std::string& key, job::RenderPlan plan) {
    const int frame = plan.frames.first;
    const auto s = session(key, plan);
    std::lock_guard lock(s->mutex);
    const std::int64_t before = s->playback.steps_taken();
    auto image = s->draw(frame, deadline_after(def_.timeout));
    if (!image) return image.error();
    auto png = encode::png_bytes(*image);
    if (!png) return png.error();
    return StudioFrame{.png = std::move(*png),
                       .frame = frame,
                       .frames = s->playback.frame_count(),
                       .fps = s->scene.video.fps,
                       .steps = s->playback.steps_taken() - before};
}

Expected<nlohmann::json> Studio::timeline(const std::string& key, job::RenderPlan plan) {
    const auto s = session(key, plan);
    std::lock_guard lock(s->mutex);
    const int last = s->playback.frame_count() - 1;
    const auto stop = deadline_after(def_.timeout);
    // Observed, not drawn: the look goes on with the physics, so later previews step on.
    if (s->playback.next_frame() <= last) {
        if (auto shown = s->show(last, false, stop); !shown) return shown.error();
    }
    nlohmann::json events = nlohmann::json::array();
    const int fps = s->scene.video.fps;
    for (const physics::ContactEvent& e : s->events) {
        const bool wall = e.other_kind == physics::ContactEvent::Other::wall;
        events.push_back({{"frame", static_cast<int>(std::ceil(e.t * fps - 1e-9))},
                          {"t", e.t},
                          {"a", s->scene.bodies[e.a].id},
                          {"other", wall ? "walls[" + std::to_string(e.other) + "]"
                                         : s->scene.bodies[e.other].id},
                          {"impulse", e.impulse}});
    }
    return nlohmann::json{{"frames", s->playback.frame_count()}, {"fps", fps},
                          {"events", std::move(events)}};
}

Expected<nlohmann::json> Studio::body_at(const std::string& key, job::RenderPlan plan, int x,
                                         int y) {
    const int frame = plan.frames.first;
    const auto s = session(key, plan);
    std::lock_guard lock(s->mutex);
    auto view = s->show(frame, true, deadline_after(def_.timeout));
    if (!view) return view.error();
    const int width = s->scene.video.width, height = s->scene.video.height;
    if (x < 0 || y < 0 || x >= width || y >= height) {
        return Error{"the pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                     ") is outside the " + std::to_string(width) + "x" + std::to_string(height) +
                     " frame"};
    }
    // The instance mask: exactly what the frame shows at that pixel, occlusion included.
    const std::vector<std::uint16_t> mask = render::draw_mask(**view, width, height);
    const std::uint16_t id =
        mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(x)];
    if (id == 0 || id == render::wall_mask_id) return nlohmann::json{{"body", nullptr}};
    const std::size_t i = id - 1U;
    const scene::Body& body = s->scene.bodies[i];
    const physics::BodyState& state = s->playback.bodies()[i];
    const bool fixed = body.is_static;
    return nlohmann::json{
        {"body",
         {{"index", i},
          {"id", body.id},
          {"line", body.line > 0 ? nlohmann::json(body.line) : nlohmann::json(nullptr)},
          {"column", body.column > 0 ? nlohmann::json(body.column) : nlohmann::json(nullptr)},
          {"kind", body.kinematic ? "kinematic" : fixed ? "static" : "dynamic"},
          {"mass", fixed ? nlohmann::json(nullptr) : nlohmann::json(body.mass)},
          {"position", {state.position.x, state.position.y}},
          {"velocity", {state.velocity.x, state.velocity.y}},
          {"angle", state.angle},
          {"spin", state.angular_velocity}}},
        {"frame", frame},
        {"t", s->playback.time_of_frame(frame)}};
}

}  // namespace discreel::serve
