#pragma once
// The studio's previews (docs/serve.md, "Studio"): a scene played on demand, frame by frame, at
// a preview size, kept between requests so that scrubbing, playing and picking a body cost a
// few frames of physics and one draw, not a render from t = 0. Each scene (with its overrides
// and size) has a session: its playback with a checkpoint every second of frames, a warm
// renderer and the contact events seen so far. Sessions are kept least recently used first,
// at most `sessions` of them; nothing is written to disk.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "discreel/expected.hpp"
#include "discreel/render_plan.hpp"

namespace discreel::serve {

struct StudioDef {
    std::size_t sessions = 4;        // scenes kept warm at once
    double timeout = 60;             // seconds one request may simulate
    // What a session's checkpoints may hold, bytes (estimated from its bodies): beyond it they
    // are thinned out, every other one dropped, and kept half as often.
    double checkpoint_bytes = 256.0 * (1 << 20);
};

struct StudioFrame {
    std::vector<std::uint8_t> png;   // the frame as `render --frame N` writes it at this size
    int frame = 0;
    int frames = 0;                  // in the clip
    int fps = 0;
    std::int64_t steps = 0;          // physics steps this request took
};

class Studio {
public:
    explicit Studio(StudioDef def);
    ~Studio();
    Studio(const Studio&) = delete;
    Studio& operator=(const Studio&) = delete;

    // `key` names the scene, its overrides and size (not the frame); `plan` is its plan, of
    // which the session keeps the scene when it is new. plan.frames.first is the frame.
    Expected<StudioFrame> frame(const std::string& key, job::RenderPlan plan);
    // The clip's contact events ({"frames", "fps", "steps", "events": [{"frame", "t", "a",
    // "other", "impulse"}]}), playing the scene to its end once per session; "steps" are the
    // physics steps this request took. A timeline asked
    // for by a `tab` (the page's name for itself; empty for none) stops with
    // superseded_message once that tab asks about another scene (moved_on): a page being
    // typed into would otherwise keep the studio playing every text it showed to its end.
    Expected<nlohmann::json> timeline(const std::string& key, job::RenderPlan plan,
                                      const std::string& tab = {});
    // `tab` asks about the scene `key`: its timelines of other scenes stop at their next step
    // (their sessions keep what they played).
    void moved_on(const std::string& tab, const std::string& key);
    static constexpr const char* superseded_message =
        "stopped: the tab that asked for this timeline went on to another scene";
    // A timeline of a session dropped for newer ones (StudioDef::sessions) stops too.
    static constexpr const char* dropped_message =
        "stopped: the studio dropped this scene's session for newer scenes";
    // The body drawn at pixel (x, y) of the frame, with its state there, or {"body": null}.
    Expected<nlohmann::json> body_at(const std::string& key, job::RenderPlan plan, int x, int y);
    std::size_t sessions() const;
    std::size_t timelines_playing() const { return timelines_.load(); }

private:
    struct Session;
    std::shared_ptr<Session> session(const std::string& key, job::RenderPlan& plan);
    // Stops `tab`'s timelines of scenes other than `key`; with mutex_ held.
    void stop_others(const std::string& tab, const std::string& key);
    // A request's deadline, and the error of a request that ran past it.
    std::function<bool()> deadline() const;
    Error too_long(const Error& error) const;

    StudioDef def_;
    mutable std::mutex mutex_;       // guards sessions_
    std::list<std::pair<std::string, std::shared_ptr<Session>>> sessions_;   // newest first
    // The timelines running for a tab, guarded by mutex_ (one per studio request at most).
    struct Playing {
        std::string tab, key;
        std::shared_ptr<std::atomic<bool>> stop;
    };
    std::vector<Playing> playing_;
    std::atomic<std::size_t> timelines_{0};   // timeline requests being answered
};

}  // namespace discreel::serve
