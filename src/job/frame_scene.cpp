#include "frame_scene.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace discreel::job {
namespace {

render::Rgba to_rgba(const scene::Color& c) {
    return {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, c.a / 255.0f};
}

struct Bounds {
    double min_x = std::numeric_limits<double>::infinity();
    double min_y = std::numeric_limits<double>::infinity();
    double max_x = -std::numeric_limits<double>::infinity();
    double max_y = -std::numeric_limits<double>::infinity();

    void add(Vec2 p, double pad) {
        min_x = std::min(min_x, p.x - pad);
        min_y = std::min(min_y, p.y - pad);
        max_x = std::max(max_x, p.x + pad);
        max_y = std::max(max_y, p.y + pad);
    }
    bool empty() const { return !(min_x <= max_x); }
};

// A box's walls are drawn just outside its corners, so that a disc resting against the box
// touches the wall's inner edge on screen as it does in the simulation.
void add_box_capsules(const scene::Wall& w, std::vector<render::CapsuleGeom>& out) {
    const double r = w.thickness / 2;
    const double x0 = w.a.x - r, y0 = w.a.y - r, x1 = w.b.x + r, y1 = w.b.y + r;
    const render::Rgba color = to_rgba(w.color);
    const auto f = [](double v) { return static_cast<float>(v); };
    out.push_back({f(x0), f(y0), f(x1), f(y0), f(r), color});
    out.push_back({f(x1), f(y0), f(x1), f(y1), f(r), color});
    out.push_back({f(x1), f(y1), f(x0), f(y1), f(r), color});
    out.push_back({f(x0), f(y1), f(x0), f(y0), f(r), color});
}

// The trail is drawn in the disc's colour, this far toward it from the background at its
// newest end, so that trails never compete with the discs themselves.
constexpr float kTrailStrength = 0.65f;
// With fading, the oldest end thins to this fraction of the trail's width.
constexpr float kTrailThinnest = 0.3f;

// v turned counter-clockwise by `angle` radians.
Vec2 rotated(Vec2 v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x - s * v.y, s * v.x + c * v.y};
}

Vec2 normalised(Vec2 v) {
    const double length = std::hypot(v.x, v.y);
    return length > 0 ? Vec2{v.x / length, v.y / length} : Vec2{1, 0};
}

render::Rgba toward(const render::Rgba& from, const render::Rgba& to, float amount) {
    const float k = amount * to.a;
    return {from.r + (to.r - from.r) * k, from.g + (to.g - from.g) * k,
            from.b + (to.b - from.b) * k, 1.0f};
}

render::Corner to_render(scene::Corner c) {
    switch (c) {
        case scene::Corner::top_left: return render::Corner::top_left;
        case scene::Corner::top_right: return render::Corner::top_right;
        case scene::Corner::bottom_left: return render::Corner::bottom_left;
        case scene::Corner::bottom_right: return render::Corner::bottom_right;
    }
    return render::Corner::top_left;
}

// "t = 1.25 s": fixed two decimals, independent of the C locale.
std::string time_text(double seconds) {
    std::array<char, 32> digits{};
    const auto end = std::to_chars(digits.data(), digits.data() + digits.size(), seconds,
                                   std::chars_format::fixed, 2).ptr;
    return "t = " + std::string(digits.data(), end) + " s";
}

}  // namespace

render::Camera fit_camera(const scene::Scene& scene) {
    const double aspect = static_cast<double>(scene.video.width) / scene.video.height;
    // What the scene holds at t = 0 (and each respawned set where it appears): every wall and
    // every body, so that a stack standing on a ground segment is not cut off at its top.
    Bounds box;
    for (const scene::Wall& w : scene.walls) {
        box.add(w.a, w.thickness);
        box.add(w.b, w.thickness);
    }
    // A shape by its outline at its angle, not its bounding circle (a wide flat gate would
    // reach far below the floor).
    const auto add_body = [&](const scene::Body& d) {
        if (!d.shape) {
            box.add(d.position, d.radius);
            return;
        }
        for (const Vec2& v : d.shape->vertices) {
            const Vec2 r = rotated(v, d.angle);
            box.add({d.position.x + r.x, d.position.y + r.y}, d.shape->radius);
        }
    };
    for (const scene::Body& d : scene.bodies) add_body(d);
    for (const scene::Respawn& r : scene.respawns) {
        for (const scene::Body& d : r.bodies) add_body(d);
    }
    render::Camera camera;
    if (box.empty()) {
        camera.height = 10.0;
    } else {
        const double margin = 1.1;  // 5 % of the extent on each side
        camera.center_x = (box.min_x + box.max_x) / 2;
        camera.center_y = (box.min_y + box.max_y) / 2;
        camera.height = std::max({(box.max_y - box.min_y) * margin,
                                  (box.max_x - box.min_x) * margin / aspect, 1e-3});
    }
    if (scene.camera.center) {
        camera.center_x = scene.camera.center->x;
        camera.center_y = scene.camera.center->y;
    }
    if (scene.camera.height) camera.height = *scene.camera.height;
    return camera;
}

FrameSceneBuilder::FrameSceneBuilder(const scene::Scene& scene) : scene_(scene) {
    frame_.background = to_rgba(scene.video.background);
    fitted_camera_ = fit_camera(scene);
    frame_.camera = fitted_camera_;
    frame_.disc_outlines = scene.style.outline;
    frame_.spin_markers = scene.style.spin_marker;
    for (const scene::Wall& w : scene.walls) {
        if (w.shape == scene::Wall::Shape::box) {
            add_box_capsules(w, frame_.capsules);
        } else {
            frame_.capsules.push_back({static_cast<float>(w.a.x), static_cast<float>(w.a.y),
                                       static_cast<float>(w.b.x), static_cast<float>(w.b.y),
                                       static_cast<float>(w.thickness / 2), to_rgba(w.color)});
        }
    }
    slots_.resize(scene.bodies.size());
    outline_.resize(scene.bodies.size());
    rounding_.resize(scene.bodies.size());
    radius_.resize(scene.bodies.size());
    fill_.resize(scene.bodies.size());
    born_.assign(scene.bodies.size(), -HUGE_VAL);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
        const bool polygon = scene.bodies[i].shape.has_value();
        std::size_t& count = polygon ? polygon_count_ : disc_count_;
        slots_[i] = {polygon, count++};
    }
    frame_.discs.resize(disc_count_);
    frame_.polygons.resize(polygon_count_);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) set_look(i, scene.bodies[i]);

    for (const physics::JointDef& j : scene.joints) {
        // In the body's frame: turned back by its angle at t = 0.
        const auto local = [&](const std::optional<std::size_t>& body, Vec2 p) {
            if (!body || *body >= scene.bodies.size()) return p;
            const scene::Body& b = scene.bodies[*body];
            return rotated(Vec2{p.x - b.position.x, p.y - b.position.y}, -b.angle);
        };
        const double turn = j.a && *j.a < scene.bodies.size() ? scene.bodies[*j.a].angle : 0.0;
        joint_ends_.push_back({local(j.a, j.anchor_a), local(j.b, j.anchor_b),
                               rotated(normalised(j.axis), -turn)});
    }

    const scene::Trails& trails = scene.style.trails;
    if (trails.enabled) {
        for (std::size_t i = 0; i < scene.bodies.size(); ++i)
            if (!scene.bodies[i].is_static) trailed_.push_back(i);
    }
    if (!trailed_.empty()) {
        const auto wanted =
            static_cast<std::size_t>(std::ceil(trails.length * scene.video.fps)) + 1;
        const std::size_t affordable = max_trail_points / trailed_.size();
        trail_capacity_ = std::max<std::size_t>(2, std::min(wanted, affordable));
        trail_points_.resize(trail_capacity_ * trailed_.size());
        trail_since_.assign(trailed_.size(), 0);
    }
}

void FrameSceneBuilder::set_look(std::size_t body, const scene::Body& d) {
    const Slot slot = slots_[body];
    // An instance mask holds the body's index + 1 (render::wall_mask_id is the walls').
    const auto mask_id = body + 1 < render::wall_mask_id ? static_cast<std::uint16_t>(body + 1)
                                                         : std::uint16_t{0};
    fill_[body] = to_rgba(d.color);
    radius_[body] = static_cast<float>(d.radius);
    outline_[body].clear();
    rounding_[body] = 0;
    if (d.shape) {
        outline_[body] = d.shape->vertices;
        rounding_[body] = static_cast<float>(d.shape->radius);
    }
    if (!slot.polygon) {
        render::DiscGeom& g = frame_.discs[slot.slot];
        g.radius = static_cast<float>(d.radius);
        g.fill = fill_[body];
        g.is_static = d.is_static;
        g.mask_id = mask_id;
        return;
    }
    render::PolygonGeom& g = frame_.polygons[slot.slot];
    g = {};
    if (d.shape) {
        const std::size_t n = std::min<std::size_t>(d.shape->vertices.size(), 8);
        for (std::size_t k = 0; k < n; ++k) {
            g.vertices[2 * k] = static_cast<float>(d.shape->vertices[k].x);
            g.vertices[2 * k + 1] = static_cast<float>(d.shape->vertices[k].y);
        }
        g.count = static_cast<int>(n);
        g.rounding = static_cast<float>(d.shape->radius);
    } else {   // a plain disc in a polygon's place: a circle is one vertex swept by its radius
        g.count = 1;
        g.rounding = static_cast<float>(d.radius);
    }
    g.fill = fill_[body];
    g.is_static = d.is_static;
    g.mask_id = mask_id;
}

void FrameSceneBuilder::respawned(std::size_t applied) {
    for (; respawns_applied_ < std::min(applied, scene_.respawns.size()); ++respawns_applied_) {
        const scene::Respawn& r = scene_.respawns[respawns_applied_];
        for (std::size_t k = 0; k < r.bodies.size() && r.first + k < slots_.size(); ++k) {
            set_look(r.first + k, r.bodies[k]);
            // Its contacts are those after the respawn (the body it replaced had the earlier).
            born_[r.first + k] = r.at;
            const auto at = std::lower_bound(trailed_.begin(), trailed_.end(), r.first + k);
            if (at != trailed_.end() && *at == r.first + k) {
                trail_since_[static_cast<std::size_t>(at - trailed_.begin())] = trail_rows_seen_;
            }
        }
    }
}

void FrameSceneBuilder::observe(int frame, std::span<const physics::BodyState> discs) {
    if (const auto follow = scene_.camera.follow; follow && *follow < discs.size()) {
        const Vec2 target = discs[*follow].position;
        const double lag = scene_.camera.follow_lag;
        if (last_frame_ < 0 || lag <= 0) {
            follow_center_ = target;
        } else {
            // Exponential smoothing in simulation time: after dt the camera has closed the
            // fraction 1 - exp(-dt / lag) of its distance to the disc, whatever the frame rate.
            const double dt = static_cast<double>(frame - last_frame_) / scene_.video.fps;
            const double closed = 1.0 - std::exp(-dt / lag);
            follow_center_.x += (target.x - follow_center_.x) * closed;
            follow_center_.y += (target.y - follow_center_.y) * closed;
        }
    }
    if (!trailed_.empty()) {
        trail_newest_ = trail_rows_filled_ == 0 ? 0 : (trail_newest_ + 1) % trail_capacity_;
        trail_rows_filled_ = std::min(trail_rows_filled_ + 1, trail_capacity_);
        ++trail_rows_seen_;
        const std::size_t n = trailed_.size();
        Point* row = &trail_points_[trail_newest_ * n];
        const Point* before = trail_rows_filled_ >= 2
                                  ? &trail_points_[(trail_newest_ + trail_capacity_ - 1) %
                                                   trail_capacity_ * n]
                                  : nullptr;
        for (std::size_t j = 0; j < n; ++j) {
            const physics::BodyState& b = discs[trailed_[j]];
            Point p{static_cast<float>(b.position.x), static_cast<float>(b.position.y),
                    radius_[trailed_[j]]};
            // A shape's width across the motion that brought it here, once per point.
            if (before != nullptr && !outline_[trailed_[j]].empty()) {
                const float dx = p.x - before[j].x, dy = p.y - before[j].y;
                const float length = std::hypot(dx, dy);
                if (length > 0) {
                    p.half = trail_half_width(trailed_[j], static_cast<float>(b.angle),
                                              dx / length, dy / length);
                }
            }
            row[j] = p;
        }
    }
    last_frame_ = frame;
}

const render::FrameScene& FrameSceneBuilder::build(int frame,
                                                   std::span<const physics::BodyState> discs,
                                                   std::span<const double> last_contacts) {
    observe(frame, discs);
    for (std::size_t i = 0; i < discs.size(); ++i) {
        const auto x = static_cast<float>(discs[i].position.x);
        const auto y = static_cast<float>(discs[i].position.y);
        const auto angle = static_cast<float>(discs[i].angle);
        if (slots_[i].polygon) {
            render::PolygonGeom& g = frame_.polygons[slots_[i].slot];
            g.x = x;
            g.y = y;
            g.angle = angle;
        } else {
            render::DiscGeom& g = frame_.discs[slots_[i].slot];
            g.x = x;
            g.y = y;
            g.angle = angle;
        }
    }
    if (scene_.camera.follow) {
        frame_.camera.center_x = follow_center_.x;
        frame_.camera.center_y = follow_center_.y;
    }
    if (!scene_.camera.keys.empty()) {
        frame_.camera = keyed_camera(static_cast<double>(frame) / scene_.video.fps, discs);
    }
    flash(frame, last_contacts);
    add_trails();
    add_joints(discs);
    add_arrows(frame, discs, last_contacts);
    add_clock(frame);
    add_text(frame, discs);
    add_debug();
    return frame_;
}

void FrameSceneBuilder::add_debug() {
    const scene::DebugDraw& debug = scene_.style.debug;
    if (!debug.any()) return;
    if (debug.sleep) {
        for (std::size_t i = 0; i < slots_.size(); ++i) {
            // flash() has set this frame's fill when the scene flashes; else the body's own.
            render::Rgba& fill = slots_[i].polygon ? frame_.polygons[slots_[i].slot].fill
                                                   : frame_.discs[slots_[i].slot].fill;
            const render::Rgba base = scene_.style.flash ? fill : fill_[i];
            const bool asleep = i < debug_.sleeping.size() && debug_.sleeping[i];
            fill = asleep ? asleep_fill(base) : base;
        }
    }
    add_debug_geometry(scene_, debug_, frame_);
}

render::Camera FrameSceneBuilder::keyed_camera(double now,
                                               std::span<const physics::BodyState> bodies) const {
    struct Aim {
        double t;
        Vec2 center;
        double height;
    };
    // Each key's aim and height up to the first at or after `now`; a key that gives none keeps
    // the one before (the first key, the fitted view's).
    Aim before{0, {fitted_camera_.center_x, fitted_camera_.center_y}, fitted_camera_.height};
    Aim after = before;
    for (std::size_t k = 0; k < scene_.camera.keys.size(); ++k) {
        const scene::CameraKey& key = scene_.camera.keys[k];
        before = k == 0 ? Aim{key.t, before.center, before.height} : after;
        after.t = key.t;
        if (key.follow && *key.follow < bodies.size()) {
            after.center = bodies[*key.follow].position;
        } else if (key.center) {
            after.center = *key.center;
        }
        if (key.height) after.height = *key.height;
        if (k == 0) before = after;
        if (now < key.t) break;
        before = after;   // past this key: it holds unless a later one moves on
    }
    // Between the two keys around `now` (holding before the first and after the last), eased.
    double s = after.t > before.t ? std::clamp((now - before.t) / (after.t - before.t), 0.0, 1.0)
                                  : 1.0;
    if (scene_.camera.ease == scene::Ease::in_out) s = s * s * (3 - 2 * s);
    render::Camera camera = fitted_camera_;
    camera.center_x = before.center.x + (after.center.x - before.center.x) * s;
    camera.center_y = before.center.y + (after.center.y - before.center.y) * s;
    camera.height = before.height + (after.height - before.height) * s;
    return camera;
}

// How much of the way to white a flash takes a body at its contact.
constexpr float kFlashStrength = 0.7f;

void FrameSceneBuilder::flash(int frame, std::span<const double> last_contacts) {
    if (!scene_.style.flash) return;
    const double now = static_cast<double>(frame) / scene_.video.fps;
    const render::Rgba white{1, 1, 1, 1};
    for (std::size_t i = 0; i < slots_.size(); ++i) {
        // Full at the contact, back to the body's colour over `flash` seconds (linearly); a
        // respawned body's contacts count from when it was put in.
        const double touched = i < last_contacts.size() ? last_contacts[i] : -HUGE_VAL;
        const double since = now - touched;
        const bool lit = touched > born_[i] && since < *scene_.style.flash;
        const auto amount = lit ? static_cast<float>(1 - std::max(since, 0.0) /
                                                             *scene_.style.flash)
                                : 0.0f;
        render::Rgba fill = fill_[i];
        if (amount > 0) {
            const render::Rgba bright = toward(fill, white, kFlashStrength * amount);
            fill = {bright.r, bright.g, bright.b, fill.a};
        }
        if (slots_[i].polygon) {
            frame_.polygons[slots_[i].slot].fill = fill;
        } else {
            frame_.discs[slots_[i].slot].fill = fill;
        }
    }
}

void FrameSceneBuilder::add_joints(std::span<const physics::BodyState> discs) {
    frame_.joints.clear();
    const scene::JointLines& style = scene_.style.joints;
    if (!style.enabled || scene_.joints.empty()) return;
    const double metres_per_pixel = frame_.camera.height / scene_.video.height;
    const auto half = static_cast<float>(0.5 * style.width * metres_per_pixel);
    const render::Rgba color = to_rgba(style.color);
    const render::Rgba hole = toward(color, frame_.background, 0.85f);
    // Where a point fixed to a body (its frame's p) is now; the world's points stay.
    const auto at = [&](const std::optional<std::size_t>& body, Vec2 p) {
        if (!body || *body >= discs.size()) return p;
        const physics::BodyState& s = discs[*body];
        const Vec2 r = rotated(p, s.angle);
        return Vec2{s.position.x + r.x, s.position.y + r.y};
    };
    const auto line = [&](Vec2 p, Vec2 q, float radius, const render::Rgba& c) {
        frame_.joints.push_back({static_cast<float>(p.x), static_cast<float>(p.y),
                                 static_cast<float>(q.x), static_cast<float>(q.y), radius, c});
    };
    const auto ring = [&](Vec2 p) {
        line(p, p, 3.5f * half, color);
        line(p, p, 1.8f * half, hole);
    };
    for (std::size_t k = 0; k < scene_.joints.size(); ++k) {
        const physics::JointDef& j = scene_.joints[k];
        const Vec2 pa = at(j.a, joint_ends_[k].a), pb = at(j.b, joint_ends_[k].b);
        using Kind = physics::JointDef::Kind;
        switch (j.kind) {
        case Kind::revolute:
            ring(pb);
            break;
        case Kind::weld:
            line(pb, pb, 3.0f * half, color);
            break;
        case Kind::prismatic: {
            // The rail: along the axis through A's anchor, over the limits (or to B).
            const Vec2 u = j.a ? rotated(joint_ends_[k].axis, discs[*j.a].angle)
                               : normalised(joint_ends_[k].axis);
            const auto along = [&](double s) { return Vec2{pa.x + s * u.x, pa.y + s * u.y}; };
            const double travel = (pb.x - pa.x) * u.x + (pb.y - pa.y) * u.y;
            const auto [lo, hi] = j.limits ? std::pair{(*j.limits)[0], (*j.limits)[1]}
                                           : std::pair{std::min(0.0, travel), std::max(0.0, travel)};
            line(along(lo), along(hi), half, color);
            ring(pb);
            break;
        }
        case Kind::distance:
            if (j.spring) {
                add_zigzag(pa, pb, half, color);
            } else {
                line(pa, pb, half, color);
            }
            line(pa, pa, 2.2f * half, color);
            line(pb, pb, 2.2f * half, color);
            break;
        }
    }
}

void FrameSceneBuilder::add_zigzag(Vec2 a, Vec2 b, float half, const render::Rgba& color) {
    // A spring: straight ends and eight zigs between, as wide as a few line widths or a
    // twentieth of its length, so a stretched spring thins and a squeezed one bunches up.
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double length = std::hypot(dx, dy);
    const auto push = [&](Vec2 p, Vec2 q) {
        frame_.joints.push_back({static_cast<float>(p.x), static_cast<float>(p.y),
                                 static_cast<float>(q.x), static_cast<float>(q.y), half, color});
    };
    if (!(length > 0)) return;
    const double ux = dx / length, uy = dy / length;
    const double width = std::max(4.0 * half, 0.05 * length);
    constexpr int zigs = 8;
    const auto point = [&](double s, double side) {
        return Vec2{a.x + s * dx - side * width * uy, a.y + s * dy + side * width * ux};
    };
    Vec2 previous = point(0.15, 0);
    push(a, previous);
    for (int z = 0; z < zigs; ++z) {
        const double s = 0.15 + 0.7 * (z + 0.5) / zigs;
        const Vec2 next = point(s, z % 2 == 0 ? 1 : -1);
        push(previous, next);
        previous = next;
    }
    const Vec2 end = point(0.85, 0);
    push(previous, end);
    push(end, b);
}

float FrameSceneBuilder::trail_half_width(std::size_t body, float angle, float dx,
                                           float dy) const {
    const std::vector<Vec2>& outline = outline_[body];
    if (outline.empty()) return radius_[body];
    // The outline's extent across the motion: its vertices turned by the angle, projected on
    // the motion's normal (-dy, dx).
    const double c = std::cos(angle), s = std::sin(angle);
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const Vec2& v : outline) {
        const double x = c * v.x - s * v.y, y = s * v.x + c * v.y;
        const double across = -dy * x + dx * y;
        lo = std::min(lo, across);
        hi = std::max(hi, across);
    }
    return static_cast<float>(0.5 * (hi - lo)) + rounding_[body];
}

void FrameSceneBuilder::add_trails() {
    frame_.trails.clear();
    if (trail_rows_filled_ < 2) return;
    const scene::Trails& style = scene_.style.trails;
    const std::size_t n = trailed_.size();
    const std::size_t segments = trail_rows_filled_ - 1;
    const float oldest_age = static_cast<float>(trail_capacity_ - 1);
    const auto width = static_cast<float>(style.width);
    for (std::size_t j = 0; j < n; ++j) {
        const std::size_t body = trailed_[j];
        const render::Rgba& fill = fill_[body];
        // Segments whose older end was seen before the body's trail began are not drawn (a
        // respawned body's first segment would join it to the body it replaced).
        const std::size_t newest_seen = trail_rows_seen_ - 1;
        // Oldest first, so newer stretches lie on top where a trail crosses itself.
        for (std::size_t k = segments; k-- > 0;) {
            if (newest_seen < k + 1 + trail_since_[j]) continue;
            const std::size_t newer = (trail_newest_ + trail_capacity_ - k) % trail_capacity_;
            const std::size_t older = (newer + trail_capacity_ - 1) % trail_capacity_;
            const Point a = trail_points_[older * n + j];
            const Point b = trail_points_[newer * n + j];
            const float dx = b.x - a.x, dy = b.y - a.y;
            const float length = std::hypot(dx, dy);
            if (!(length > 0)) continue;
            // The colour is mixed with the background here, not blended in GL: neighbouring
            // segments overlap at their round caps, and opaque colours keep the joints even.
            const float age = (static_cast<float>(k) + 0.5f) / oldest_age;   // 0 new .. 1 old
            const float fresh = style.fade ? 1.0f - age : 1.0f;
            const float full_radius = width * b.half;
            const float radius =
                full_radius * (style.fade ? kTrailThinnest + (1 - kTrailThinnest) * fresh : 1.0f);
            frame_.trails.push_back({a.x, a.y, b.x, b.y, radius,
                                     toward(frame_.background, fill, kTrailStrength * fresh)});
        }
    }
}

void FrameSceneBuilder::add_arrows(int frame, std::span<const physics::BodyState> discs,
                                   std::span<const double> last_contacts) {
    frame_.arrows.clear();
    const scene::VelocityArrows& style = scene_.style.velocity_arrows;
    if (!style.enabled) return;
    const double now = static_cast<double>(frame) / scene_.video.fps;
    const render::Rgba color = to_rgba(style.color);
    for (std::size_t i = 0; i < discs.size(); ++i) {
        if (scene_.bodies[i].is_static) continue;
        float shown = 1;
        if (style.after_contact) {
            // Full at the contact, fading linearly to nothing over after_contact seconds; a
            // respawned body's contacts count from when it was put in.
            const double touched = i < last_contacts.size() ? last_contacts[i] : -HUGE_VAL;
            if (!(touched > born_[i])) continue;
            const double since = now - touched;
            if (since >= *style.after_contact) continue;
            shown = static_cast<float>(1 - std::max(since, 0.0) / *style.after_contact);
        }
        const Vec2 tail = discs[i].position;
        const Vec2 v = discs[i].velocity;
        frame_.arrows.push_back({static_cast<float>(tail.x), static_cast<float>(tail.y),
                                 static_cast<float>(tail.x + v.x * style.scale),
                                 static_cast<float>(tail.y + v.y * style.scale),
                                 static_cast<float>(style.width),
                                 {color.r, color.g, color.b, color.a * shown}});
    }
}

namespace {

// `value` with `digits` after the point, independent of the C locale.
std::string fixed(double value, int digits) {
    std::array<char, 64> text{};
    const auto end = std::to_chars(text.data(), text.data() + text.size(), value,
                                   std::chars_format::fixed, digits).ptr;
    return {text.data(), end};
}

// Text on a body of this fill: near-black on a light one, white on a dark one.
render::Rgba label_color(const render::Rgba& fill) {
    const float luminance = 0.2126f * fill.r + 0.7152f * fill.g + 0.0722f * fill.b;
    return luminance > 0.5f ? render::Rgba{0.08f, 0.08f, 0.1f, 1} : render::Rgba{1, 1, 1, 1};
}

// How far a body's outline is from its centre at the nearest: a disc's radius, a shape's
// distance to its nearest side (plus its rounding).
double inner_radius(const scene::Body& b) {
    if (!b.shape || b.shape->vertices.size() < 2) return b.radius;
    const std::vector<Vec2>& v = b.shape->vertices;
    double nearest = HUGE_VAL;
    for (std::size_t k = 0; k < v.size(); ++k) {
        const Vec2 p = v[k], q = v[(k + 1) % v.size()];
        const double length = std::hypot(q.x - p.x, q.y - p.y);
        if (length > 0) nearest = std::min(nearest, std::abs(p.x * q.y - p.y * q.x) / length);
    }
    return (std::isfinite(nearest) ? nearest : 0.0) + b.shape->radius;
}

// A label's em height: a fraction of its body's inner radius, so a short label fits across it.
constexpr double kLabelSize = 0.35;
// An anchored overlay's distance from the frame's edges, a fraction of its height.
constexpr double kOverlayMargin = 0.04;

}  // namespace

std::string FrameSceneBuilder::filled(const std::vector<scene::TextPart>& text, int frame,
                                      std::span<const physics::BodyState> discs) const {
    using Kind = scene::Readout::Kind;
    std::string out;
    for (const scene::TextPart& part : text) {
        out += part.literal;
        if (!part.readout) continue;
        const scene::Readout& r = *part.readout;
        double value = 0;
        switch (r.kind) {
        case Kind::time: value = static_cast<double>(frame) / scene_.video.fps; break;
        case Kind::frame: out += std::to_string(frame); continue;
        case Kind::energy:
        case Kind::kinetic:
        case Kind::momentum: {
            // Over the moving bodies, as the physics' own measures.
            double kinetic = 0, potential = 0;
            Vec2 momentum{};
            const Vec2 g = scene_.physics.gravity;
            for (std::size_t i = 0; i < discs.size() && i < scene_.bodies.size(); ++i) {
                const scene::Body& b = scene_.bodies[i];
                if (b.is_static) continue;
                const physics::BodyState& s = discs[i];
                kinetic += 0.5 * b.mass * (s.velocity.x * s.velocity.x + s.velocity.y * s.velocity.y) +
                           0.5 * b.inertia * s.angular_velocity * s.angular_velocity;
                potential -= b.mass * (g.x * s.position.x + g.y * s.position.y);
                momentum.x += b.mass * s.velocity.x;
                momentum.y += b.mass * s.velocity.y;
            }
            value = r.kind == Kind::kinetic  ? kinetic
                    : r.kind == Kind::energy ? kinetic + potential
                                             : std::hypot(momentum.x, momentum.y);
            break;
        }
        case Kind::speed:
        case Kind::x:
        case Kind::y:
        case Kind::angle: {
            if (r.body >= discs.size()) continue;
            const physics::BodyState& s = discs[r.body];
            value = r.kind == Kind::speed ? std::hypot(s.velocity.x, s.velocity.y)
                    : r.kind == Kind::x   ? s.position.x
                    : r.kind == Kind::y   ? s.position.y
                                          : s.angle;
            break;
        }
        }
        out += fixed(value, r.precision);
    }
    return out;
}

void FrameSceneBuilder::add_text(int frame, std::span<const physics::BodyState> discs) {
    frame_.labels.clear();
    for (std::size_t i = 0; i < discs.size() && i < scene_.bodies.size(); ++i) {
        const scene::Body& b = scene_.bodies[i];
        if (b.label.empty()) continue;
        render::TextLabel label;
        label.text = filled(b.label, frame, discs);
        label.world = true;
        label.x = discs[i].position.x;
        label.y = discs[i].position.y;
        label.size = kLabelSize * inner_radius(b);
        label.anchor = render::Anchor::center;
        label.color = label_color(fill_[i]);
        label.outline = fill_[i];
        if (b.label_turns) label.angle = discs[i].angle;
        frame_.labels.push_back(std::move(label));
    }
    const double now = static_cast<double>(frame) / scene_.video.fps;
    const double end = static_cast<double>(scene_.video.frame_count()) / scene_.video.fps;
    for (const scene::Overlay& o : scene_.overlays) {
        const double to = o.to.value_or(end);
        if (now < o.from || now >= to) continue;
        // Faded in over `fade` after `from` and out over `fade` before `to`.
        double shown = 1;
        if (o.fade > 0) shown = std::clamp(std::min(now - o.from, to - now) / o.fade, 0.0, 1.0);
        render::TextLabel label;
        label.text = filled(o.text, frame, discs);
        label.anchor = static_cast<render::Anchor>(o.anchor);
        label.size = o.size;
        const render::Rgba color = to_rgba(o.color);
        label.color = {color.r, color.g, color.b, color.a * static_cast<float>(shown)};
        if (o.at) {
            label.world = true;
            label.x = o.at->x;
            label.y = o.at->y;
        } else {
            // The frame's point named by the anchor, kOverlayMargin of its height inside.
            const int column = static_cast<int>(o.anchor) % 3, row = static_cast<int>(o.anchor) / 3;
            const double aspect =
                static_cast<double>(scene_.video.height) / scene_.video.width;
            const double mx = kOverlayMargin * aspect, my = kOverlayMargin;
            label.x = column == 0 ? mx : column == 1 ? 0.5 : 1 - mx;
            label.y = row == 0 ? my : row == 1 ? 0.5 : 1 - my;
        }
        frame_.labels.push_back(std::move(label));
    }
}

void FrameSceneBuilder::add_clock(int frame) {
    frame_.texts.clear();
    const scene::Clock& style = scene_.style.clock;
    if (!style.enabled) return;
    const std::string frame_text = "frame " + std::to_string(frame);
    const std::string time = time_text(static_cast<double>(frame) / scene_.video.fps);
    std::string text = style.format == scene::ClockFormat::time    ? time
                       : style.format == scene::ClockFormat::frame ? frame_text
                                                                   : time + "  " + frame_text;
    // 7 dots tall: 7 pixels at 180 rows, 28 at 720, 42 at 1080.
    const int dot = std::max(1, scene_.video.height / 180);
    frame_.texts.push_back({std::move(text), to_render(style.corner), dot, to_rgba(style.color)});
}

}  // namespace discreel::job
