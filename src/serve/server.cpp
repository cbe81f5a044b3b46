// The HTTP side of discreel serve: routes, authentication, limits, logs and metrics. Jobs
// live in jobs.cpp; this file only translates between HTTP and them.
#include <httplib.h>
#include <sys/socket.h>

#include <cstdio>
#include <memory>
#include <semaphore>

#include "discreel/render.hpp"
#include "discreel/serve.hpp"
#include "discreel_web.hpp"
#include "jobs.hpp"
#include "metrics.hpp"
#include "request.hpp"

namespace discreel::serve {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

constexpr const char* id_pattern = "([0-9a-f]{32})";
// Each open event stream holds one of the connection threads; the rest stay for other requests.
constexpr int http_threads = 64;
constexpr int max_event_streams = 48;
// Scenes loaded at once by the connection threads (validation before a job is accepted): each
// may take up to the scene limits' memory (docs/reliability.md), so only a few at a time.
constexpr std::ptrdiff_t concurrent_loads = 2;
constexpr auto keep_alive_wait = std::chrono::seconds(15);   // between comments on a quiet stream

void reply(httplib::Response& res, int status, const json& body) {
    res.status = status;
    res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n",
                    "application/json");
}

void reply(httplib::Response& res, const Refusal& refused) {
    reply(res, refused.status, refused.body);
}

json error_body(const std::string& message) { return {{"error", {{"message", message}}}}; }

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

const char* reason_for(int status) {
    switch (status) {
        case 400: return "the request is malformed";
        case 401: return "a valid bearer token is required";
        case 404: return "no such resource";
        case 405: return "method not allowed";
        case 413: return "the request body is over the scene size limit";
        default: return "the request failed";
    }
}

thread_local Clock::time_point request_started;

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};

}  // namespace

struct Server::Impl {
    ServeDef def;
    Metrics metrics;
    std::unique_ptr<Jobs> jobs;
    httplib::Server http;
    int port = 0;
    std::atomic<int> streams{0};
    std::counting_semaphore<concurrent_loads> loading{concurrent_loads};

    // plan_job with at most concurrent_loads scenes in memory at once.
    std::variant<PlannedJob, Refusal> plan(const JobRequest& request) {
        loading.acquire();
        struct Release {
            std::counting_semaphore<concurrent_loads>& semaphore;
            ~Release() { semaphore.release(); }
        } release{loading};
        return plan_job(request, def.limits);
    }

    void routes();
    void post_render(const httplib::Request& req, httplib::Response& res);
    void post_validate(const httplib::Request& req, httplib::Response& res);
    void get_output(const httplib::Request& req, httplib::Response& res);
    void get_events(const httplib::Request& req, httplib::Response& res);
};

void Server::Impl::post_render(const httplib::Request& req, httplib::Response& res) {
    auto parsed = parse_job_request(req.body, def.limits, def.version);
    if (auto* refused = std::get_if<Refusal>(&parsed)) return reply(res, *refused);
    const JobRequest& request = std::get<JobRequest>(parsed);
    auto planned = plan(request);
    if (auto* refused = std::get_if<Refusal>(&planned)) return reply(res, *refused);
    const PlannedJob& resolved = std::get<PlannedJob>(planned);
    const Submission done = jobs->submit(
        request, resolved.plan.frames.last - resolved.plan.frames.first + 1, resolved.warnings);
    switch (done.what) {
        case Submitted::accepted:
        case Submitted::existing:
            res.set_header("Location", "/v1/renders/" + request.id);
            return reply(res, 202, done.job);
        case Submitted::cached:
            res.set_header("Location", "/v1/renders/" + request.id);
            return reply(res, 200, done.job);
        case Submitted::busy:
            res.set_header("Retry-After", std::to_string(done.retry_after));
            return reply(res, 429, error_body("the queue is full (" +
                                              std::to_string(def.max_queue) +
                                              " jobs); try again later"));
        case Submitted::store_failed:
            return reply(res, 503, error_body("cannot accept the job: " + done.error));
    }
}

void Server::Impl::post_validate(const httplib::Request& req, httplib::Response& res) {
    auto parsed = parse_job_request(req.body, def.limits, def.version);
    if (auto* refused = std::get_if<Refusal>(&parsed)) return reply(res, *refused);
    auto planned = plan(std::get<JobRequest>(parsed));
    if (auto* refused = std::get_if<Refusal>(&planned)) return reply(res, *refused);
    reply(res, 200, {{"ok", true}, {"warnings", std::get<PlannedJob>(planned).warnings}});
}

void Server::Impl::get_output(const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    const auto output = jobs->output(id);
    if (!output) {
        if (!jobs->get(id)) return reply(res, 404, error_body("no job " + id));
        return reply(res, 409, error_body("the job has no output (yet): see its status"));
    }
    const std::string etag = "\"" + output->info.sha256 + "\"";
    res.set_header("ETag", etag);
    // The bytes of an id never change: clients may keep them.
    res.set_header("Cache-Control", "private, max-age=31536000, immutable");
    if (req.get_header_value("If-None-Match") == etag) {
        res.status = 304;
        return;
    }
    // cpp-httplib 0.11 slices a streamed body by the ranges it parsed as they are, past the end
    // of the file too (announcing lengths the body does not have): a range that starts past the
    // end is 416 here, and one that ends past it is cut at the end (RFC 9110, 14.1.2). The
    // request is this connection's own object, made const only for handlers.
    const auto size = static_cast<std::int64_t>(output->info.bytes);
    for (auto& [first, last] : const_cast<httplib::Request&>(req).ranges) {
        const bool suffix = first < 0;
        if ((suffix && last <= 0) || (!suffix && first >= size)) {
            res.status = 416;
            res.set_header("Content-Range", "bytes */" + std::to_string(size));
            return;
        }
        if (suffix) last = std::min<std::int64_t>(last, size);
        if (!suffix && last >= size) last = size - 1;
    }
    std::shared_ptr<std::FILE> file(std::fopen(output->path.c_str(), "rb"), FileCloser{});
    if (!file) return reply(res, 500, error_body("the output of job " + id + " is missing"));
    res.set_header("Content-Disposition",
                   "inline; filename=\"" + id + "." + output->info.extension + "\"");
    res.set_content_provider(
        static_cast<std::size_t>(output->info.bytes), content_type_of(output->info.extension),
        [this, file](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
            char buffer[1 << 16];
            const std::size_t want = std::min(length, sizeof buffer);
            if (std::fseek(file.get(), static_cast<long>(offset), SEEK_SET) != 0) return false;
            const std::size_t got = std::fread(buffer, 1, want, file.get());
            if (got == 0) return false;
            metrics.served(got);
            return sink.write(buffer, got);
        });
}

void Server::Impl::get_events(const httplib::Request& req, httplib::Response& res) {
    const std::string id = req.matches[1];
    if (!jobs->get(id)) return reply(res, 404, error_body("no job " + id));
    if (streams.fetch_add(1) >= max_event_streams) {
        --streams;
        res.set_header("Retry-After", "5");
        return reply(res, 503, error_body("too many event streams are open; poll "
                                          "GET /v1/renders/" + id + " instead"));
    }
    res.set_header("Cache-Control", "no-store");
    std::uint64_t seen = 0;
    bool ended = false;
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, id, seen, ended](std::size_t, httplib::DataSink& sink) mutable {
            if (ended) {
                sink.done();
                return true;
            }
            const auto snapshot = jobs->wait_change(id, seen, keep_alive_wait);
            if (!snapshot || jobs->stopping()) {
                sink.done();
                return true;
            }
            if (snapshot->version == seen) {   // quiet: a comment keeps proxies from closing
                static constexpr char comment[] = ": waiting\n\n";
                return sink.write(comment, sizeof comment - 1);
            }
            seen = snapshot->version;
            const std::string event = "event: job\ndata: " + snapshot->job.dump() + "\n\n";
            ended = snapshot->final;
            return sink.write(event.data(), event.size());
        },
        [this](bool) { --streams; });
}

void Server::Impl::routes() {
    http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
        request_started = Clock::now();
        if (!def.token || req.path.rfind("/v1/", 0) != 0) {
            return httplib::Server::HandlerResponse::Unhandled;
        }
        const std::string header = req.get_header_value("Authorization");
        const std::string_view prefix = "Bearer ";
        const bool bearer = header.size() > prefix.size() && header.rfind(prefix, 0) == 0;
        if (!bearer || !same_token(std::string_view(header).substr(prefix.size()), *def.token)) {
            res.set_header("WWW-Authenticate", "Bearer");
            reply(res, 401, error_body(reason_for(401)));
            return httplib::Server::HandlerResponse::Handled;
        }
        return httplib::Server::HandlerResponse::Unhandled;
    });
    http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        // 304 and 416 carry no body (a 416's would be cut by the range it refuses).
        if (res.body.empty() && res.status != 304 && res.status != 416) {
            reply(res, res.status, error_body(reason_for(res.status)));
        }
    });
    http.set_exception_handler(
        [](const httplib::Request&, httplib::Response& res, const std::exception_ptr& failure) {
            std::string what = "unknown";
            try {
                std::rethrow_exception(failure);
            } catch (const std::exception& e) {
                what = e.what();
            } catch (...) {
            }
            log_line("exception", {{"message", what}});
            reply(res, 500, error_body("internal error"));
        });
    http.set_logger([this](const httplib::Request& req, const httplib::Response& res) {
        metrics.answered(res.status);
        if (!def.log_requests) return;
        const double ms =
            std::chrono::duration<double, std::milli>(Clock::now() - request_started).count();
        log_line("request", {{"method", req.method},
                             {"path", req.path},
                             {"status", res.status},
                             {"ms", std::round(ms * 10) / 10},
                             {"remote", req.remote_addr}});
    });

    http.Get("/", [](const httplib::Request&, httplib::Response& res) {
        res.set_header("Content-Security-Policy",
                       "default-src 'none'; script-src 'unsafe-inline'; style-src "
                       "'unsafe-inline'; connect-src 'self'; img-src blob:; media-src blob:");
        res.set_content(std::string(discreel_web::index_html), "text/html; charset=utf-8");
    });
    http.Get("/healthz", [this](const httplib::Request&, httplib::Response& res) {
        reply(res, 200, {{"ok", true}, {"queued", jobs->queued()}, {"running", jobs->running()}});
    });
    http.Get("/metrics", [this](const httplib::Request&, httplib::Response& res) {
        res.set_content(metrics.text(jobs->queued(), jobs->running(), def.workers),
                        "text/plain; version=0.0.4; charset=utf-8");
    });
    http.Post("/v1/renders", [this](const httplib::Request& req, httplib::Response& res) {
        post_render(req, res);
    });
    http.Post("/v1/validate", [this](const httplib::Request& req, httplib::Response& res) {
        post_validate(req, res);
    });
    const std::string job_path = std::string("/v1/renders/") + id_pattern;
    http.Get(job_path, [this](const httplib::Request& req, httplib::Response& res) {
        const std::string id = req.matches[1];
        if (auto job = jobs->get(id)) return reply(res, 200, *job);
        reply(res, 404, error_body("no job " + id));
    });
    http.Delete(job_path, [this](const httplib::Request& req, httplib::Response& res) {
        const auto [status, body] = jobs->cancel(req.matches[1]);
        reply(res, status, body);
    });
    http.Get(job_path + "/output", [this](const httplib::Request& req, httplib::Response& res) {
        get_output(req, res);
    });
    http.Get(job_path + "/events", [this](const httplib::Request& req, httplib::Response& res) {
        get_events(req, res);
    });
}

Server::Server(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Server::~Server() {
    if (impl_) stop();
}
Server::Server(Server&&) noexcept = default;
Server& Server::operator=(Server&&) noexcept = default;

Expected<Server> Server::open(const ServeDef& def) {
    // Before any thread: llvmpipe draws on the calling thread, as in every render.
    render::set_rasterizer_threads(0);
    auto impl = std::make_unique<Impl>();
    impl->def = def;
    auto jobs = Jobs::open(def, impl->metrics);
    if (!jobs) return jobs.error();
    impl->jobs = std::move(*jobs);
    httplib::Server& http = impl->http;
    http.new_task_queue = [] { return new httplib::ThreadPool(http_threads); };
    // A JSON body escapes the scene's text (a newline becomes \n): room for that, then the
    // scene itself is held to the limit when parsed. Past this, 413 before the body is read.
    http.set_payload_max_length(2 * def.limits.file_bytes + 65536);
    http.set_read_timeout(5);          // each read of a slow client
    http.set_write_timeout(10);
    http.set_keep_alive_timeout(5);
    http.set_keep_alive_max_count(100);
    impl->routes();
    // Debian's build of cpp-httplib listens with a backlog of 5: a burst of clients connecting
    // at once overflows it and some of their connections are reset. The listening socket passes
    // through this hook before it is bound; listen() again afterwards raises the backlog.
    int listening = -1;
    http.set_socket_options([&listening](socket_t fd) {
        listening = fd;
        httplib::default_socket_options(fd);
    });
    if (def.port == 0) {
        impl->port = http.bind_to_any_port(def.host);
        if (impl->port < 0) return Error{"cannot listen on " + def.host + ": no free port"};
    } else {
        if (!http.bind_to_port(def.host, def.port)) {
            return Error{"cannot listen on " + def.host + ":" + std::to_string(def.port) +
                         " (in use, or not an address of this machine)"};
        }
        impl->port = def.port;
    }
    if (listening >= 0) ::listen(listening, SOMAXCONN);
    http.set_socket_options(httplib::default_socket_options);
    return Server(std::move(impl));
}

int Server::port() const { return impl_->port; }

Status Server::run() {
    impl_->jobs->start_workers();
    const bool served = impl_->http.listen_after_bind();
    impl_->jobs->stop();
    if (!served && !impl_->jobs->stopping()) return Error{"the HTTP server stopped on an error"};
    return {};
}

void Server::stop() {
    impl_->jobs->stop();
    impl_->http.stop();
}

}  // namespace discreel::serve
