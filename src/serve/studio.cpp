// The studio's sessions: a playback with checkpoints and a warm renderer per scene.
#include "studio.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include "discreel/encode.hpp"
#include "discreel/job.hpp"
#include "discreel/render.hpp"

namespace discreel::serve {

using Clock = std::chrono::steady_clock;

struct Studio::Session {
    Session(scene::Scene s, double budget)
        : scene(std::move(s)),
          // A checkpoint a second: going back re-simulates at most a second of physics, while
          // the memory allows.
          playback(scene, {.checkpoint_every = scene.video.fps,
                           .max_checkpoints = 4096,
                           .max_checkpoint_bytes = budget}) {}

    // Shows `frame`, recording the contact events of frames never shown before.
    Expected<const render::FrameScene*> show(int frame, bool drawn,
                                             const std::function<bool()>& stop) {
        auto shown = playback.show(frame, drawn, stop);
        for (const physics::ContactEvent& e : playback.take_events()) {
            if (e.t <= recorded_until) continue;   // seen before going back
            if (e.kind == physics::ContactEvent::Kind::contact) events.push_back(e);
        }
        recorded_until = std::max(recorded_until, playback.world().time());
        recorded_steps = std::max(recorded_steps, playback.world().step_count());
        return shown;
    }

    // The first frame that shows physics step `step` or a later one (the clip's end past it).
    int first_frame_from(std::int64_t step) const {
        const int last = playback.frame_count() - 1;
        const double fps = scene.video.fps, rate = scene.physics.rate;
        int n = std::clamp(static_cast<int>(std::ceil(static_cast<double>(step) * fps / rate)),
                           0, last);
        while (n > 0 && playback.step_of_frame(n - 1) >= step) --n;
        while (n < last && playback.step_of_frame(n) < step) ++n;
        return n;
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
    std::atomic<int> waiting{0};      // previews waiting for the mutex: a timeline lets them in
    std::atomic<bool> evicted{false};   // no longer kept: its timelines stop
    const scene::Scene scene;         // the playback keeps a reference to it
    job::Playback playback;
    std::optional<render::Renderer> renderer;
    std::vector<physics::ContactEvent> events;   // contacts, in order, of the frames shown
    double recorded_until = -1;       // seconds: events up to here are in `events`
    std::int64_t recorded_steps = 0;  // physics steps the events cover
};

namespace {

// A preview's turn on a session: counted as waiting until it holds the session's mutex.
struct Turn {
    explicit Turn(std::atomic<int>& waiting, std::mutex& mutex) : lock(mutex, std::defer_lock) {
        ++waiting;
        lock.lock();
        --waiting;
    }
    std::unique_lock<std::mutex> lock;
};

// Stops a request that simulates past its time.
std::function<bool()> deadline_after(double seconds) {
    const auto deadline =
        Clock::now() +
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    return [deadline] { return Clock::now() > deadline; };
}

}  // namespace

Studio::Studio(StudioDef def) : def_(def) {}
Studio::~Studio() = default;

std::function<bool()> Studio::deadline() const { return deadline_after(def_.timeout); }

// A request stopped by its deadline says so, in the studio's terms.
Error Studio::too_long(const Error& error) const {
    if (error.message != job::cancelled_message) return error;
    std::ostringstream text;
    text << "the preview took longer than the studio's " << def_.timeout
         << " s; play less of the clip, or render it (POST /v1/renders)";
    return Error{text.str()};
}

std::size_t Studio::sessions() const {
    std::lock_guard lock(mutex_);
    return sessions_.size();
}

std::shared_ptr<Studio::Session> Studio::session(const std::string& key, job::RenderPlan& plan) {
    // The session of `key` moved to the front, if there is one; with mutex_ held.
    const auto to_front = [&] {
        const auto found = std::find_if(sessions_.begin(), sessions_.end(),
                                        [&](const auto& entry) { return entry.first == key; });
        if (found == sessions_.end()) return false;
        sessions_.splice(sessions_.begin(), sessions_, found);
        return true;
    };
    {
        std::lock_guard lock(mutex_);
        if (to_front()) return sessions_.front().second;
    }
    // Built (the world, its walls) and evicted (checkpoints, a GL context) outside the lock:
    // other requests go on meanwhile. A session in use stays alive through its shared_ptr.
    auto made = std::make_shared<Session>(std::move(plan.scene), def_.checkpoint_bytes);
    std::list<std::pair<std::string, std::shared_ptr<Session>>> evicted;
    std::shared_ptr<Session> kept;
    {
        std::lock_guard lock(mutex_);
        // Another request may have made it meanwhile.
        if (!to_front()) sessions_.emplace_front(key, std::move(made));
        kept = sessions_.front().second;
        while (sessions_.size() > std::max<std::size_t>(1, def_.sessions)) {
            evicted.splice(evicted.end(), sessions_, std::prev(sessions_.end()));
        }
    }
    for (const auto& [evicted_key, old] : evicted) old->evicted = true;
    return kept;
}

Expected<StudioFrame> Studio::frame(const std::string& key, job::RenderPlan plan) {
    const int frame = plan.frames.first;
    const auto s = session(key, plan);
    const Turn turn(s->waiting, s->mutex);
    const std::int64_t before = s->playback.steps_taken();
    auto image = s->draw(frame, deadline());
    if (!image) return too_long(image.error());
    auto png = encode::png_bytes(*image);
    if (!png) return png.error();
    return StudioFrame{.png = std::move(*png),
                       .frame = frame,
                       .frames = s->playback.frame_count(),
                       .fps = s->scene.video.fps,
                       .steps = s->playback.steps_taken() - before};
}

void Studio::stop_others(const std::string& tab, const std::string& key) {
    for (const Playing& p : playing_) {
        if (p.tab == tab && p.key != key) p.stop->store(true, std::memory_order_relaxed);
    }
}

void Studio::moved_on(const std::string& tab, const std::string& key) {
    std::lock_guard lock(mutex_);
    stop_others(tab, key);
}

Expected<nlohmann::json> Studio::timeline(const std::string& key, job::RenderPlan plan,
                                          const std::string& tab) {
    const auto s = session(key, plan);
    const auto superseded = std::make_shared<std::atomic<bool>>(false);
    {
        std::lock_guard lock(mutex_);
        if (!tab.empty()) {
            stop_others(tab, key);
            playing_.push_back({tab, key, superseded});
        }
        ++timelines_;
    }
    struct Done {
        Studio& studio;
        const std::shared_ptr<std::atomic<bool>>& flag;
        ~Done() {
            std::lock_guard lock(studio.mutex_);
            std::erase_if(studio.playing_, [&](const Playing& p) { return p.stop == flag; });
            --studio.timelines_;
        }
    } done{*this, superseded};
    const auto moved_away = [&] {
        return superseded->load(std::memory_order_relaxed) ||
               s->evicted.load(std::memory_order_relaxed);
    };
    // The studio's time limit counts the timeline's own physics, not its waits for previews.
    const std::chrono::duration<double> budget(def_.timeout);
    Clock::duration spent{};
    Clock::time_point slice_start = Clock::now();
    const auto stop = [&] {
        return moved_away() || spent + (Clock::now() - slice_start) > budget;
    };
    // Played to the end a second of frames at a time, the session free between them: a
    // preview waiting meanwhile goes first, so it waits for a second's physics at most.
    // Observed, not drawn: the look goes on with the physics, so later previews step on from
    // there. Each second goes on from what the timeline has recorded, not from where a
    // preview left the playback (from the latest checkpoint before it).
    const int last = s->playback.frame_count() - 1;
    const int fps = s->scene.video.fps;
    std::int64_t steps = 0;
    for (;;) {
        while (s->waiting.load() > 0 && !moved_away()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        std::lock_guard lock(s->mutex);
        slice_start = Clock::now();
        if (s->recorded_steps >= s->playback.step_of_frame(last)) break;
        const int from = std::max(s->playback.next_frame(),
                                  s->first_frame_from(s->recorded_steps + 1));
        const int to = std::min(last, from + fps - 1);
        const std::int64_t before = s->playback.steps_taken();
        auto shown = s->show(to, false, stop);
        spent += Clock::now() - slice_start;
        steps += s->playback.steps_taken() - before;
        if (!shown) {
            if (moved_away()) {
                return Error{superseded->load() ? superseded_message : dropped_message};
            }
            return too_long(shown.error());
        }
    }
    std::lock_guard lock(s->mutex);
    nlohmann::json events = nlohmann::json::array();
    const double rate = s->scene.physics.rate;
    for (const physics::ContactEvent& e : s->events) {
        const bool wall = e.other_kind == physics::ContactEvent::Other::wall;
        const auto step = static_cast<std::int64_t>(std::llround(e.t * rate));
        events.push_back({{"frame", s->first_frame_from(step)},
                          {"t", e.t},
                          {"a", s->scene.bodies[e.a].id},
                          {"other", wall ? "walls[" + std::to_string(e.other) + "]"
                                         : s->scene.bodies[e.other].id},
                          {"impulse", e.impulse}});
    }
    return nlohmann::json{{"frames", s->playback.frame_count()},
                          {"fps", fps},
                          {"steps", steps},
                          {"events", std::move(events)}};
}

Expected<nlohmann::json> Studio::body_at(const std::string& key, job::RenderPlan plan, int x,
                                         int y) {
    const int frame = plan.frames.first;
    const int width = plan.scene.video.width, height = plan.scene.video.height;
    if (x < 0 || y < 0 || x >= width || y >= height) {
        return Error{"the pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                     ") is outside the " + std::to_string(width) + "x" + std::to_string(height) +
                     " frame"};
    }
    const auto s = session(key, plan);
    const Turn turn(s->waiting, s->mutex);
    auto view = s->show(frame, true, deadline());
    if (!view) return too_long(view.error());
    // The instance mask: exactly what the frame shows at that pixel, occlusion included.
    const std::vector<std::uint16_t> mask = render::draw_mask(**view, width, height);
    const std::uint16_t id =
        mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
             static_cast<std::size_t>(x)];
    if (id == 0 || id == render::wall_mask_id) return nlohmann::json{{"body", nullptr}};
    const std::size_t i = id - 1U;
    // The body there now: the file's, or that of the latest respawn that replaced it.
    const scene::Body* shown = &s->scene.bodies[i];
    const std::size_t applied = s->playback.world().respawns_applied();
    for (std::size_t r = 0; r < applied && r < s->scene.respawns.size(); ++r) {
        const scene::Respawn& set = s->scene.respawns[r];
        if (i >= set.first && i - set.first < set.bodies.size()) shown = &set.bodies[i - set.first];
    }
    const scene::Body& body = *shown;
    const physics::BodyState& state = s->playback.bodies()[i];
    const bool fixed = body.is_static || body.kinematic.has_value();
    return nlohmann::json{
        {"body",
         {{"index", i},
          {"id", body.id},
          {"line", body.line > 0 ? nlohmann::json(body.line) : nlohmann::json(nullptr)},
          {"column", body.column > 0 ? nlohmann::json(body.column) : nlohmann::json(nullptr)},
          {"kind", body.kinematic ? "kinematic" : body.is_static ? "static" : "dynamic"},
          {"mass", fixed ? nlohmann::json(nullptr) : nlohmann::json(body.mass)},
          {"position", {state.position.x, state.position.y}},
          {"velocity", {state.velocity.x, state.velocity.y}},
          {"angle", state.angle},
          {"spin", state.angular_velocity}}},
        {"frame", frame},
        {"t", s->playback.time_of_frame(frame)}};
}

}  // namespace discreel::serve
