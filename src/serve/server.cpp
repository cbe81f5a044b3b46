// The HTTP side of discreel serve: routes, authentication, host and content checks, ranges,
// logs and metrics. Jobs live in jobs.cpp and the HTTP connections in http.cpp; this file only
// translates between them.
#include <fcntl.h>
#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <semaphore>

#include <boost/asio/ip/address.hpp>

#include "discreel/render.hpp"
#include "discreel/serve.hpp"
#include "digest.hpp"
#include "discreel_web.hpp"
#include "http.hpp"
#include "jobs.hpp"
#include "metrics.hpp"
#include "request.hpp"
#include "studio.hpp"

namespace discreel::serve {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// Event streams hold no thread, only a connection; the cap keeps them from taking all.
constexpr int max_event_streams = 128;
// Scenes loaded at once for checking: each may take up to the scene limits' memory
// (docs/reliability.md), so only a few at a time.
constexpr std::ptrdiff_t concurrent_loads = 2;
// A scene text at least this long is worth giving its memory back to the system after loading.
constexpr std::size_t large_scene = std::size_t{256} * 1024;

http::Response reply(int status, const json& body) {
    http::Response res;
    res.status = status;
    res.set("Content-Type", "application/json");
    res.body = body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
    return res;
}

http::Response reply(const Refusal& refused) { return reply(refused.status, refused.body); }

json error_body(const std::string& message) { return {{"error", {{"message", message}}}}; }

http::Response refuse(int status, const std::string& message) {
    return reply(status, error_body(message));
}

// Compares in time that depends only on the expected token's length, never on where the first
// difference is.
bool same_token(std::string_view given, std::string_view expected) {
    unsigned difference = given.size() == expected.size() ? 0 : 1;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        const unsigned char g = i < given.size() ? static_cast<unsigned char>(given[i]) : 0;
        difference |= g ^ static_cast<unsigned char>(expected[i]);
    }
    return difference == 0;
}

std::string lower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

// "name", "name:port", "[v6]" or "[v6]:port" -> name (brackets kept off) and port (-1: none);
// nullopt when malformed.
std::optional<std::pair<std::string, int>> split_host(std::string_view host) {
    std::string name;
    std::string_view rest;
    if (!host.empty() && host.front() == '[') {
        const auto close = host.find(']');
        if (close == std::string_view::npos) return std::nullopt;
        name = std::string(host.substr(1, close - 1));
        rest = host.substr(close + 1);
    } else {
        const auto colon = host.find(':');
        name = std::string(host.substr(0, colon));
        rest = colon == std::string_view::npos ? std::string_view() : host.substr(colon);
    }
    if (name.empty()) return std::nullopt;
    int port = -1;
    if (!rest.empty()) {
        if (rest.front() != ':' || rest.size() < 2 || rest.size() > 6) return std::nullopt;
        port = 0;
        for (const char c : rest.substr(1)) {
            if (c < '0' || c > '9') return std::nullopt;
            port = port * 10 + (c - '0');
        }
    }
    return std::pair{lower(name), port};
}

bool is_ip_literal(const std::string& name) {
    boost::system::error_code failed;
    (void)boost::asio::ip::make_address(name, failed);
    return !failed;
}

// A Range header against a file of `size` bytes (RFC 9110, 14.2): one part to send, the whole
// file (no header, one the server ignores, or parts that do not coalesce into one), or
// nothing satisfiable (416).
struct RangeAnswer {
    enum Kind { whole, part, unsatisfiable } kind = whole;
    std::uint64_t first = 0, last = 0;   // inclusive, for part
};

std::optional<std::uint64_t> digits_value(std::string_view text) {
    if (text.empty() || text.size() > 18) return std::nullopt;   // 18 digits fit, with room
    std::uint64_t value = 0;
    for (const char c : text) {
        if (c < '0' || c > '9') return std::nullopt;
        value = value * 10 + static_cast<std::uint64_t>(c - '0');
    }
    return value;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
    return text;
}

RangeAnswer resolve_range(std::string_view header, std::uint64_t size) {
    constexpr std::size_t max_parts = 16;   // more: the header is ignored
    header = trimmed(header);
    if (header.size() < 6 || lower(header.substr(0, 6)) != "bytes=" || size == 0) return {};
    header.remove_prefix(6);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> parts;
    std::size_t specs = 0;
    while (!header.empty()) {
        const auto comma = header.find(',');
        const std::string_view spec = trimmed(header.substr(0, comma));
        header = comma == std::string_view::npos ? std::string_view() : header.substr(comma + 1);
        if (spec.empty()) continue;
        if (++specs > max_parts) return {};
        const auto dash = spec.find('-');
        if (dash == std::string_view::npos) return {};
        const std::string_view from = spec.substr(0, dash), to = spec.substr(dash + 1);
        if (from.empty()) {   // the last N bytes
            const auto n = digits_value(to);
            if (!n) return {};
            if (*n == 0) continue;
            parts.emplace_back(size - std::min(*n, size), size - 1);
            continue;
        }
        const auto first = digits_value(from);
        if (!first) return {};
        std::uint64_t last = size - 1;
        if (!to.empty()) {
            const auto given = digits_value(to);
            if (!given || *given < *first) return {};
            last = std::min(*given, size - 1);
        }
        if (*first >= size) continue;   // unsatisfiable on its own
        parts.emplace_back(*first, last);
    }
    if (specs == 0) return {};
    if (parts.empty()) return {RangeAnswer::unsatisfiable};
    std::sort(parts.begin(), parts.end());
    std::pair<std::uint64_t, std::uint64_t> merged = parts.front();
    for (std::size_t i = 1; i < parts.size(); ++i) {
        if (parts[i].first > merged.second + 1) return {};   // disjoint: the whole file
        merged.second = std::max(merged.second, parts[i].second);
    }
    return {RangeAnswer::part, merged.first, merged.second};
}

struct FdCloser {
    void operator()(const int* fd) const {
        if (*fd >= 0) ::close(*fd);
        delete fd;
    }
};

}  // namespace

struct Server::Impl final : http::Handler {
    ServeDef def;
    Metrics metrics;
    std::unique_ptr<Jobs> jobs;
    std::unique_ptr<Studio> studio;
    std::unique_ptr<http::Server> http;
    std::atomic<int> streams{0};
    std::counting_semaphore<concurrent_loads> loading{concurrent_loads};
    static constexpr std::ptrdiff_t studio_at_once = 2;
    std::counting_semaphore<studio_at_once> studio_slots{studio_at_once};

    // plan_job with at most concurrent_loads scenes in memory at once; a large scene's memory
    // goes back to the system afterwards (glibc keeps freed memory in per-thread arenas).
    std::variant<PlannedJob, Refusal> plan(const JobRequest& request) {
        loading.acquire();
        struct Release {
            std::counting_semaphore<concurrent_loads>& semaphore;
            bool trim;
            ~Release() {
                if (trim) malloc_trim(0);
                semaphore.release();
            }
        } release{loading, request.scene.size() >= large_scene};
        return plan_job(request, def.limits);
    }

    bool allowed_host(std::string_view host) const;
    bool allowed_origin(std::string_view origin) const;
    void add_cors(const http::Request& request, http::Response& res) const;
    std::optional<http::Response> preflight(const http::Request& head) const;
    std::optional<http::Response> check_request_head(const http::Request& head);
    std::optional<http::Response> check_head(const http::Request& head) override;
    bool blocking(const http::Request& request) const override;
    http::Response handle(http::Request& request) override;
    void answered(const http::Request& request, int status) override;

    http::Response route(http::Request& request);
    http::Response post_render(const http::Request& req);
    http::Response post_validate(const http::Request& req);
    http::Response get_output(const http::Request& req, const std::string& id,
                              const std::string& name);
    http::Response list_renders(const http::Request& req);
    http::Response get_events(const std::string& id);
    http::Response post_studio(const http::Request& req, std::string_view what);
};

bool Server::Impl::allowed_host(std::string_view host) const {
    const auto split = split_host(host);
    if (!split) return false;
    const auto& [name, port] = *split;
    if (port != -1 && port != http->port()) return false;
    if (port == -1 && http->port() != 80) return false;
    for (const std::string& allowed : def.allow_hosts) {
        if (lower(allowed) == name) return true;
    }
    boost::system::error_code failed;
    const auto listening = boost::asio::ip::make_address(def.host, failed);
    if (failed) return false;
    const bool wildcard = listening.is_unspecified();
    if (name == "localhost") return wildcard || listening.is_loopback();
    if (!is_ip_literal(name)) return false;
    // An address: the one listened on, or any for a wildcard listen (a name that resolves to
    // it, the rebinding attack, is not an address).
    return wildcard || boost::asio::ip::make_address(name) == listening;
}

bool Server::Impl::allowed_origin(std::string_view origin) const {
    return !origin.empty() && std::find(def.cors_origins.begin(), def.cors_origins.end(),
                                        origin) != def.cors_origins.end();
}

// An allowed origin's page may read the answer (and these headers of it); any other origin's
// gets no CORS header, so its browser keeps the answer from it.
void Server::Impl::add_cors(const http::Request& request, http::Response& res) const {
    if (def.cors_origins.empty()) return;
    res.set("Vary", "Origin");
    const std::string_view origin = request.field("origin");
    if (!allowed_origin(origin)) return;
    res.set("Access-Control-Allow-Origin", std::string(origin));
    res.set("Access-Control-Expose-Headers",
            "Location, ETag, Content-Range, Content-Disposition, Retry-After, X-Discreel-Frame, "
            "X-Discreel-Frames, X-Discreel-Fps, X-Discreel-Steps");
}

// A browser's preflight (OPTIONS with Access-Control-Request-Method) for a /v1 route, answered
// before authentication: it never carries the token. Nullopt: not one, or no --cors given (then
// OPTIONS is answered as any unknown method).
std::optional<http::Response> Server::Impl::preflight(const http::Request& head) const {
    if (def.cors_origins.empty() || head.method != "OPTIONS" ||
        head.field("access-control-request-method").empty()) {
        return std::nullopt;
    }
    const std::string_view origin = head.field("origin");
    if (!allowed_origin(origin)) {
        http::Response res = refuse(403, "origin '" + std::string(origin) +
                                             "' may not call this server (serve --cors ORIGIN "
                                             "allows one)");
        res.set("Vary", "Origin");
        return res;
    }
    http::Response res;
    res.status = 204;
    res.set("Access-Control-Allow-Origin", std::string(origin));
    res.set("Access-Control-Allow-Methods", "GET, HEAD, POST, DELETE");
    res.set("Access-Control-Allow-Headers", "Authorization, Content-Type, Range, If-None-Match");
    res.set("Access-Control-Max-Age", "600");
    res.set("Vary", "Origin");
    return res;
}

std::optional<http::Response> Server::Impl::check_head(const http::Request& head) {
    auto res = check_request_head(head);
    if (res) add_cors(head, *res);   // a refusal the page should be able to read (401, 415)
    return res;
}

std::optional<http::Response> Server::Impl::check_request_head(const http::Request& head) {
    // HTTP/1.0 may leave Host out (the container's health check does); browsers, which DNS
    // rebinding works through, always send it.
    const std::string_view host = head.field("host");
    if (host.empty() && head.version != 10) {
        return refuse(400, "the request has no Host header");
    }
    if (!host.empty() && !allowed_host(host)) {
        return refuse(421, "this server does not answer for host '" + std::string(host) +
                               "' (serve --allow-host NAME adds names)");
    }
    if (auto answer = preflight(head)) return answer;
    if (def.token && head.path.rfind("/v1/", 0) == 0) {
        const std::string_view header = head.field("authorization");
        const std::string_view prefix = "Bearer ";
        const bool bearer = header.size() > prefix.size() && header.substr(0, 7) == prefix;
        if (!bearer || !same_token(header.substr(prefix.size()), *def.token)) {
            http::Response res = refuse(401, "a valid bearer token is required");
            res.set("WWW-Authenticate", "Bearer");
            return res;
        }
    }
    if (head.method == "POST") {
        const std::string type = lower(head.field("content-type"));
        const std::string_view media = trimmed(std::string_view(type).substr(0, type.find(';')));
        if (media != "application/json") {
            return refuse(415, "send the body as JSON, with Content-Type: application/json");
        }
    }
    return std::nullopt;
}

bool Server::Impl::blocking(const http::Request& request) const {
    // Scene loading, store writes and waiting for a cancelled job.
    return request.method == "POST" || request.method == "DELETE";
}

void Server::Impl::answered(const http::Request& req, int status) {
    metrics.answered(status);
    if (!def.log_requests) return;
    const double ms = req.started == Clock::time_point{}
                          ? 0.0
                          : std::chrono::duration<double, std::milli>(Clock::now() - req.started)
                                .count();
    log_line("request", {{"method", req.method},
                         {"path", req.path},
                         {"status", status},
                         {"ms", std::round(ms * 10) / 10},
                         {"remote", req.remote}});
}

http::Response Server::Impl::handle(http::Request& request) {
    // A large body and what was made of it are freed when this returns: back to the system with
    // them (glibc keeps freed memory in the arena of the thread that used it). Large bodies come
    // only with POSTs, which run on the blocking threads.
    struct Trim {
        bool large;
        ~Trim() {
            if (large) malloc_trim(0);
        }
    } trim{request.body.size() >= large_scene};
    request.body_bytes = request.body.size();
    try {
        http::Response res = route(request);
        // The page and every answer: never inside another site's frame.
        res.set("X-Frame-Options", "DENY");
        res.set("X-Content-Type-Options", "nosniff");
        add_cors(request, res);
        return res;
    } catch (const std::exception& e) {
        log_line("exception", {{"message", e.what()}});
        return refuse(500, "internal error");
    }
}

http::Response Server::Impl::route(http::Request& req) {
    const std::string& path = req.path;
    const bool get = req.method == "GET" || req.method == "HEAD";
    const auto only = [&](const char* allow) {
        http::Response res = refuse(405, "method not allowed");
        res.set("Allow", allow);
        return res;
    };
    if (path == "/") {
        if (!get) return only("GET, HEAD");
        http::Response res;
        res.set("Content-Type", "text/html; charset=utf-8");
        res.set("Content-Security-Policy",
                "default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                "connect-src 'self'; img-src blob:; media-src blob:; frame-ancestors 'none'");
        res.body = std::string(discreel_web::index_html);
        return res;
    }
    if (path == "/healthz") {
        if (!get) return only("GET, HEAD");
        return reply(200, {{"ok", true}, {"queued", jobs->queued()}, {"running", jobs->running()}});
    }
    if (path == "/metrics") {
        if (!get) return only("GET, HEAD");
        http::Response res;
        res.set("Content-Type", "text/plain; version=0.0.4; charset=utf-8");
        res.body = metrics.text(jobs->queued(), jobs->running(), def.workers,
                                studio->timelines_playing());
        return res;
    }
    if (path == "/v1/renders") {
        if (get) return list_renders(req);
        if (req.method != "POST") return only("GET, HEAD, POST");
        return post_render(req);
    }
    if (path == "/v1/validate") {
        if (req.method != "POST") return only("POST");
        return post_validate(req);
    }
    for (const std::string_view what : {"frame", "timeline", "body"}) {
        if (path == "/v1/studio/" + std::string(what)) {
            if (req.method != "POST") return only("POST");
            return post_studio(req, what);
        }
    }
    // /v1/renders/<32 lowercase hex digits>[/output|/events]; anything else is no resource.
    constexpr std::string_view prefix = "/v1/renders/";
    if (path.rfind(prefix, 0) != 0 || path.size() < prefix.size() + 32) {
        return refuse(404, "no such resource");
    }
    const std::string id = path.substr(prefix.size(), 32);
    if (!std::all_of(id.begin(), id.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); })) {
        return refuse(404, "no such resource");
    }
    const std::string_view rest = std::string_view(path).substr(prefix.size() + 32);
    if (rest.empty()) {
        if (get) {
            if (auto job = jobs->get(id)) return reply(200, *job);
            return refuse(404, "no job " + id);
        }
        if (req.method == "DELETE") {
            const auto [status, body] = jobs->cancel(id);
            return reply(status, body);
        }
        return only("GET, HEAD, DELETE");
    }
    if (rest == "/output") return get ? get_output(req, id, "output") : only("GET, HEAD");
    // /events is two things: the job's progress as server-sent events (what EventSource asks
    // for), and the contact events' CSV of a job that asked for that output.
    if (rest == "/events" &&
        (req.field("accept").find("text/event-stream") != std::string_view::npos ||
         !jobs->has_output(id, "events"))) {
        return get ? get_events(id) : only("GET");
    }
    for (const char* side : side_outputs) {
        if (rest.substr(1) == side && rest.front() == '/') {
            return get ? get_output(req, id, side) : only("GET, HEAD");
        }
    }
    return refuse(404, "no such resource");
}

// A callback only to a host the operator allowed: else any client could make the server
// send requests into networks only it reaches.
std::optional<http::Response> refuse_callback(const JobRequest& request, const ServeDef& def) {
    if (!request.callback) return std::nullopt;
    for (const std::string& allowed : def.callback_allow) {
        if (lower_host(allowed) == request.callback->host) return std::nullopt;
    }
    if (def.callback_allow.empty()) {
        return refuse(400, "field 'callback': this server sends no callbacks (serve "
                           "--callback-allow HOST allows one)");
    }
    return refuse(400, "field 'callback': the host '" + request.callback->host +
                           "' is not one this server calls back (serve --callback-allow)");
}

http::Response Server::Impl::post_render(const http::Request& req) {
    auto parsed = parse_job_request(req.body, def.limits, def.version);
    if (auto* refused = std::get_if<Refusal>(&parsed)) return reply(*refused);
    const JobRequest& request = std::get<JobRequest>(parsed);
    if (auto refused = refuse_callback(request, def)) return *refused;
    auto planned = plan(request);
    if (auto* refused = std::get_if<Refusal>(&planned)) return reply(*refused);
    const PlannedJob& resolved = std::get<PlannedJob>(planned);
    const Submission done = jobs->submit(
        request, resolved.plan.frames.last - resolved.plan.frames.first + 1, resolved.warnings);
    http::Response res;
    switch (done.what) {
        case Submitted::accepted:
        case Submitted::existing:
            res = reply(202, done.job);
            res.set("Location", "/v1/renders/" + request.id);
            return res;
        case Submitted::cached:
            res = reply(200, done.job);
            res.set("Location", "/v1/renders/" + request.id);
            return res;
        case Submitted::busy:
            res = refuse(429, "the queue is full (" + std::to_string(def.max_queue) +
                                  " jobs); try again later");
            res.set("Retry-After", std::to_string(done.retry_after));
            return res;
        case Submitted::store_failed:
            return refuse(503, "cannot accept the job: " + done.error);
    }
    return refuse(500, "internal error");
}

http::Response Server::Impl::post_validate(const http::Request& req) {
    auto parsed = parse_job_request(req.body, def.limits, def.version);
    if (auto* refused = std::get_if<Refusal>(&parsed)) return reply(*refused);
    if (auto refused = refuse_callback(std::get<JobRequest>(parsed), def)) return *refused;
    auto planned = plan(std::get<JobRequest>(parsed));
    if (auto* refused = std::get_if<Refusal>(&planned)) return reply(*refused);
    return reply(200, {{"ok", true}, {"warnings", std::get<PlannedJob>(planned).warnings}});
}

// A studio request: a still's request (scene, set, size, frame or at) and, for "body", the
// pixel "pick": [x, y] of the preview. Answered from the scene's studio session.
http::Response Server::Impl::post_studio(const http::Request& req, std::string_view what) {
    json body = json::parse(req.body, nullptr, false);
    std::optional<std::pair<int, int>> pick;
    std::string tab;   // the page's name for itself: its newer scene stops its older timelines
    if (body.is_object()) {
        if (const auto found = body.find("tab"); found != body.end()) {
            const json& t = *found;
            const auto plain = [](const std::string& text) {
                return !text.empty() && text.size() <= 64 &&
                       std::all_of(text.begin(), text.end(), [](char c) {
                           return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' ||
                                  c == '_';
                       });
            };
            if (!t.is_string() || !plain(t.get<std::string>())) {
                return refuse(400,
                              "field 'tab' must be 1 to 64 letters, digits, '-' or '_', the "
                              "page's name for itself");
            }
            tab = t.get<std::string>();
            body.erase(found);
        }
        if (body.contains("output")) {
            return refuse(400, "field 'output': the studio answers PNG previews; leave it out");
        }
        if (const auto found = body.find("pick"); found != body.end()) {
            const json& p = *found;
            const auto pixel = [](const json& v) {
                return v.is_number_integer() && v.get<std::int64_t>() >= -(1 << 20) &&
                       v.get<std::int64_t>() <= (1 << 20);
            };
            if (!p.is_array() || p.size() != 2 || !pixel(p[0]) || !pixel(p[1])) {
                return refuse(400, "field 'pick' must be [x, y], a pixel of the preview");
            }
            pick = std::pair{p[0].get<int>(), p[1].get<int>()};
            body.erase(found);
        }
        body["output"] = "png";
    }
    if (what == "body" && body.is_object() && !pick) {
        return refuse(400, "field 'pick' is missing: [x, y], a pixel of the preview");
    }
    auto parsed = parse_job_request(body.is_object() ? body.dump() : req.body, def.limits,
                                    def.version);
    if (auto* refused = std::get_if<Refusal>(&parsed)) return reply(*refused);
    const JobRequest& request = std::get<JobRequest>(parsed);
    if (request.callback || !request.extras.empty()) {
        return refuse(400, "the studio takes no 'callback' or 'outputs'");
    }
    // The session is the scene with its overrides and size, whatever the frame.
    json options = request.options;
    options.erase("frame");
    options.erase("at");
    const std::string key = sha256_hex(options.dump() + "\n" + request.scene);
    // Before the wait for a place: the tab's older timelines may be what holds them. (A pick
    // is of the preview shown, which may be of the text before the one the tab shows next.)
    if (!tab.empty() && what != "body") studio->moved_on(tab, key);
    // Two at once: the other blocking threads stay free for renders, validation and cancels.
    if (!studio_slots.try_acquire()) {
        http::Response res = refuse(429, "the studio is busy with other previews; try again");
        res.set("Retry-After", "1");
        return res;
    }
    struct Release {
        std::counting_semaphore<studio_at_once>& slots;
        ~Release() { slots.release(); }
    } release{studio_slots};
    auto planned = plan(request);
    if (auto* refused = std::get_if<Refusal>(&planned)) return reply(*refused);
    job::RenderPlan& plan = std::get<PlannedJob>(planned).plan;
    if (what == "frame") {
        auto frame = studio->frame(key, std::move(plan));
        if (!frame) return refuse(422, frame.error().message);
        http::Response res;
        res.set("Content-Type", "image/png");
        res.set("Cache-Control", "no-store");
        res.set("X-Discreel-Frame", std::to_string(frame->frame));
        res.set("X-Discreel-Frames", std::to_string(frame->frames));
        res.set("X-Discreel-Fps", std::to_string(frame->fps));
        res.set("X-Discreel-Steps", std::to_string(frame->steps));
        res.body.assign(frame->png.begin(), frame->png.end());
        return res;
    }
    auto answer = what == "timeline"
                      ? studio->timeline(key, std::move(plan), tab)
                      : studio->body_at(key, std::move(plan), pick->first, pick->second);
    if (!answer) {
        const std::string& message = answer.error().message;
        const bool stopped =
            message == Studio::superseded_message || message == Studio::dropped_message;
        return refuse(stopped ? 409 : 422, message);
    }
    return reply(200, *answer);
}

// The query's parameters, in order; nullopt when one is not name=value.
std::optional<std::vector<std::pair<std::string, std::string>>> query_of(const std::string& target) {
    std::vector<std::pair<std::string, std::string>> out;
    const auto mark = target.find('?');
    if (mark == std::string::npos) return out;
    std::string_view rest = std::string_view(target).substr(mark + 1);
    while (!rest.empty()) {
        const auto amp = rest.find('&');
        const std::string_view part = rest.substr(0, amp);
        rest = amp == std::string_view::npos ? std::string_view() : rest.substr(amp + 1);
        if (part.empty()) continue;
        const auto eq = part.find('=');
        if (eq == std::string_view::npos) return std::nullopt;
        out.emplace_back(std::string(part.substr(0, eq)), std::string(part.substr(eq + 1)));
    }
    return out;
}

http::Response Server::Impl::list_renders(const http::Request& req) {
    const auto query = query_of(req.target);
    if (!query) return refuse(400, "the query is name=value pairs: state, limit and before");
    std::optional<JobStatus> state;
    std::size_t limit = 50;
    std::optional<std::string> before;
    for (const auto& [name, value] : *query) {
        if (name == "state") {
            bool known = false;
            for (const JobStatus s : {JobStatus::queued, JobStatus::running, JobStatus::succeeded,
                                      JobStatus::failed, JobStatus::cancelled}) {
                if (value == to_string(s)) {
                    state = s;
                    known = true;
                }
            }
            if (!known) {
                return refuse(400, "state must be queued, running, succeeded, failed or "
                                   "cancelled, not '" + value + "'");
            }
        } else if (name == "limit") {
            const auto n = digits_value(value);
            if (!n || *n < 1 || *n > 1000) return refuse(400, "limit must be from 1 to 1000");
            limit = static_cast<std::size_t>(*n);
        } else if (name == "before") {
            before = value;
        } else {
            return refuse(400, "unknown parameter '" + name + "'; the parameters are state, "
                               "limit and before");
        }
    }
    json page = jobs->list(state, limit, before);
    if (page.is_null()) {
        return refuse(400, "no job '" + *before + "' to list after (it may have been deleted "
                           "by the sweeper); start again from the first page");
    }
    return reply(200, page);
}

http::Response Server::Impl::get_output(const http::Request& req, const std::string& id,
                                        const std::string& name) {
    // Opened under the jobs' lock: the sweeper cannot take the file between here and the read.
    auto output = jobs->open_output(id, name);
    if (!output) {
        const auto job = jobs->get(id);
        if (!job) return refuse(404, "no job " + id);
        if ((*job)["status"] == "succeeded") {
            return refuse(404, "job " + id + " has no " + name + ": ask for it in \"outputs\"");
        }
        return refuse(409, "the job has no output (yet): see its status");
    }
    if (output->fd < 0) return refuse(500, "the output of job " + id + " is missing");
    const std::shared_ptr<const int> owned(new int(output->fd), FdCloser{});
    const std::string etag = "\"" + output->info.sha256 + "\"";
    http::Response res;
    res.set("ETag", etag);
    // The bytes of an id never change: clients may keep them.
    res.set("Cache-Control", "private, max-age=31536000, immutable");
    res.set("Accept-Ranges", "bytes");
    if (req.field("if-none-match") == etag) {
        res.status = 304;
        return res;
    }
    const auto size = static_cast<std::uint64_t>(output->info.bytes);
    // Ranges are a GET's (RFC 9110, 14.2): HEAD describes the whole file.
    const RangeAnswer range =
        req.method == "GET" ? resolve_range(req.field("range"), size) : RangeAnswer{};
    if (range.kind == RangeAnswer::unsatisfiable) {
        res.status = 416;
        res.set("Content-Range", "bytes */" + std::to_string(size));
        return res;
    }
    res.set("Content-Type", content_type_of(output->info.extension));
    res.set("Content-Disposition",
            "inline; filename=\"" + id + (name == "output" ? "" : "." + name) + "." +
                output->info.extension + "\"");
    http::FileBody file{.fd = owned,
                        .offset = 0,
                        .length = size,
                        .sent = [this](std::uint64_t bytes) { metrics.served(bytes); }};
    if (range.kind == RangeAnswer::part) {
        res.status = 206;
        res.set("Content-Range", "bytes " + std::to_string(range.first) + "-" +
                                     std::to_string(range.last) + "/" + std::to_string(size));
        file.offset = range.first;
        file.length = range.last - range.first + 1;
    }
    res.file = std::move(file);
    return res;
}

namespace {

// One job's changes as server-sent events: its state at once, then at every change, ending
// after a final status or when the server stops.
class JobEvents final : public http::EventSource {
public:
    JobEvents(Jobs& jobs, std::string id, std::atomic<int>& streams)
        : jobs_(jobs), id_(std::move(id)), streams_(streams) {}
    ~JobEvents() override {
        if (handle_ != 0) jobs_.unwatch(handle_);
        --streams_;
    }
    JobEvents(const JobEvents&) = delete;
    JobEvents& operator=(const JobEvents&) = delete;

    std::string next(bool& ended) override {
        const auto snapshot = jobs_.snapshot(id_);
        if (!snapshot || jobs_.stopping()) {
            ended = true;
            return {};
        }
        if (snapshot->version == seen_) return {};
        seen_ = snapshot->version;
        ended = snapshot->final;
        return "event: job\ndata: " +
               snapshot->job.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) +
               "\n\n";
    }
    void watch(std::function<void()> wake) override { handle_ = jobs_.watch(id_, std::move(wake)); }

private:
    Jobs& jobs_;
    std::string id_;
    std::atomic<int>& streams_;
    std::uint64_t seen_ = 0, handle_ = 0;
};

}  // namespace

http::Response Server::Impl::get_events(const std::string& id) {
    if (!jobs->get(id)) return refuse(404, "no job " + id);
    if (streams.fetch_add(1) >= max_event_streams) {
        --streams;
        http::Response res = refuse(503, "too many event streams are open; poll "
                                         "GET /v1/renders/" + id + " instead");
        res.set("Retry-After", "5");
        return res;
    }
    http::Response res;
    res.set("Content-Type", "text/event-stream");
    res.set("Cache-Control", "no-store");
    res.events = std::make_shared<JobEvents>(*jobs, id, streams);
    return res;
}

Server::Server(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Server::~Server() {
    if (impl_) {
        stop();
        impl_->http.reset();   // its threads end before the jobs they call go
    }
}
Server::Server(Server&&) noexcept = default;
Server& Server::operator=(Server&&) noexcept = default;

Expected<Server> Server::open(const ServeDef& def) {
    // Before any thread: llvmpipe draws on the calling thread, as in every render.
    render::set_rasterizer_threads(0);
    auto impl = std::make_unique<Impl>();
    impl->def = def;
    // A JSON body escapes the scene's text (a newline becomes \n): room for that, then the
    // scene itself is held to the limit when parsed.
    http::Limits limits;
    limits.body_bytes = 2 * static_cast<std::uint64_t>(def.limits.file_bytes) + 65536;
    limits.bodies_in_flight = std::max<std::uint64_t>(64u << 20, 8 * limits.body_bytes);
    // The store first: its lock decides whether this server may run at all.
    auto jobs = Jobs::open(def, impl->metrics);
    if (!jobs) return jobs.error();
    impl->jobs = std::move(*jobs);
    impl->studio = std::make_unique<Studio>(
        StudioDef{.sessions = def.studio_sessions,
                  .timeout = std::min(def.job_timeout, 60.0),
                  .checkpoint_bytes = 256.0 * (1 << 20)});
    auto bound = http::Server::bind(def.host, def.port, limits, *impl);
    if (!bound) return bound.error();
    impl->http = std::move(*bound);
    return Server(std::move(impl));
}

int Server::port() const { return impl_->http->port(); }

Status Server::run() {
    impl_->jobs->start_workers();
    impl_->http->run();
    impl_->jobs->stop();
    return {};
}

void Server::stop() {
    impl_->jobs->stop();
    impl_->http->stop();
}

}  // namespace discreel::serve
