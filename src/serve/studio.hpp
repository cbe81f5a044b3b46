#pragma once
// The studio's previews (docs/serve.md, "Studio"): a scene played on demand, frame by frame, at
// a preview size, kept between requests so that scrubbing, playing and picking a body cost a
// few frames of physics and one draw, not a render from t = 0. Each scene (with its overrides
// and size) has a session: its playback with a checkpoint every second of frames, a warm
// renderer and the contact events seen so far. Sessions are kept least recently used first,
// at most `sessions` of them; nothing is written to disk.
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
    // The clip's contact events ({"frames", "fps", "events": [{"frame", "t", "a", "other",
    // "wall", "impulse"}]}), playing the scene to its end once per session.
    Expected<nlohmann::json> timeline(const std::string& key, job::RenderPlan plan);
    // The body drawn at pixel (x, y) of the frame, with its state there, or {"body": null}.
    Expected<nlohmann::json> body_at(const std::string& key, job::RenderPlan plan, int x, int y);
    std::size_t sessions() const;

private:
    struct Session;
    std::shared_ptr<Session> session(const std::string& key, job::RenderPlan& plan);
    // A request's deadline, and the error of a request that ran past it.
    std::function<bool()> deadline() const;
    Error too_long(const Error& error) const;

    StudioDef def_;
    mutable std::mutex mutex_;       // guards sessions_
    std::list<std::pair<std::string, std::shared_ptr<Session>>> sessions_;   // newest first
};

}  // namespace discreel::serve
