#include "http.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/asio/thread_pool.hpp>
#include <boost/asio/write.hpp>
#include <boost/beast/core/flat_buffer.hpp>
#include <boost/beast/http/error.hpp>
#include <boost/beast/http/parser.hpp>
#include <boost/beast/http/read.hpp>
#include <boost/beast/http/string_body.hpp>
#include <cctype>
#include <ctime>
#include <mutex>
#include <optional>
#include <thread>

namespace discreel::serve::http {
namespace {

namespace asio = boost::asio;
namespace bhttp = boost::beast::http;
using tcp = asio::ip::tcp;
using boost::system::error_code;
using Clock = std::chrono::steady_clock;

std::string lower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

std::string status_line(int status) {
    return "HTTP/1.1 " + std::to_string(status) + " " + reason_phrase(status) + "\r\n";
}

// The response's Date (RFC 9110, 6.6.1): IMF-fixdate, as "Sun, 06 Nov 1994 08:49:37 GMT".
std::string http_date() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[64];
    std::strftime(text, sizeof text, "%a, %d %b %Y %H:%M:%S GMT", &utc);
    return text;
}

Response plain(int status, const std::string& message) {
    Response response;
    response.status = status;
    response.set("Content-Type", "application/json");
    // The message is one of this file's own, with nothing to escape.
    response.body = "{\"error\":{\"message\":\"" + message + "\"}}\n";
    return response;
}

// Enough descriptors for the connection cap: the soft limit raised towards the hard one.
int descriptor_room() {
    rlimit limit{};
    if (getrlimit(RLIMIT_NOFILE, &limit) != 0) return 1024;
    if (limit.rlim_cur < limit.rlim_max && limit.rlim_cur < 65536) {
        limit.rlim_cur = std::min<rlim_t>(limit.rlim_max, 65536);
        (void)setrlimit(RLIMIT_NOFILE, &limit);
        (void)getrlimit(RLIMIT_NOFILE, &limit);
    }
    return static_cast<int>(std::min<rlim_t>(limit.rlim_cur, 1 << 20));
}

}  // namespace

std::string_view Request::field(std::string_view name) const {
    for (const Field& f : fields) {
        if (f.name == name) return f.value;
    }
    return {};
}

void Response::set(std::string name, std::string value) {
    const std::string key = lower(name);
    for (Field& f : fields) {
        if (lower(f.name) == key) {
            f.value = std::move(value);
            return;
        }
    }
    fields.push_back({std::move(name), std::move(value)});
}

const char* reason_phrase(int status) {
    switch (status) {
        case 100: return "Continue";
        case 200: return "OK";
        case 202: return "Accepted";
        case 204: return "No Content";
        case 206: return "Partial Content";
        case 304: return "Not Modified";
        case 400: return "Bad Request";
        case 401: return "Unauthorized";
        case 403: return "Forbidden";
        case 404: return "Not Found";
        case 405: return "Method Not Allowed";
        case 408: return "Request Timeout";
        case 409: return "Conflict";
        case 413: return "Content Too Large";
        case 414: return "URI Too Long";
        case 415: return "Unsupported Media Type";
        case 416: return "Range Not Satisfiable";
        case 421: return "Misdirected Request";
        case 422: return "Unprocessable Content";
        case 429: return "Too Many Requests";
        case 431: return "Request Header Fields Too Large";
        case 500: return "Internal Server Error";
        case 501: return "Not Implemented";
        case 503: return "Service Unavailable";
        case 505: return "HTTP Version Not Supported";
        default: return "Unknown";
    }
}

struct Server::Impl {
    // What a session touches as it is destroyed comes before `io`, so it outlives the
    // sessions that io_context's destructor destroys with their pending handlers.
    Limits limits;
    Handler& handler;
    std::atomic<int> connections{0};
    std::atomic<std::uint64_t> bodies{0};          // bytes reserved by bodies in flight
    std::atomic<bool> stopped{false};
    int port = 0;
    asio::io_context io;
    asio::strand<asio::io_context::executor_type> accepting{io.get_executor()};
    tcp::acceptor acceptor{io};
    bool accept_paused = false;                   // on `accepting`
    // Keeps io.run() going while no operation is pending (every connection's request on the
    // blocking threads, accepting paused at the cap): the server ends only at stop().
    std::optional<asio::executor_work_guard<asio::io_context::executor_type>> working;
    asio::thread_pool blocking;

    Impl(const Limits& l, Handler& h)
        : limits(l), handler(h), io(std::max(1, l.io_threads)),
          blocking(static_cast<std::size_t>(std::max(1, l.blocking_threads))) {}

    void accept();
    void connection_ended();

    bool reserve(std::uint64_t bytes) {
        std::uint64_t now = bodies.load();
        do {
            if (now + bytes > limits.bodies_in_flight) return false;
        } while (!bodies.compare_exchange_weak(now, now + bytes));
        return true;
    }
    void release(std::uint64_t bytes) { bodies -= bytes; }
};

namespace {

// Bytes read ahead of the parser beyond the head's limit. The buffer holds what is read and not
// yet parsed; a body is moved out of it as it is parsed, so only a line the parser cannot end (a
// chunk's size line or trailer without its CRLF) can fill it, and that is refused.
constexpr std::size_t read_room = 65536;

// Handler::handle, with anything it throws answered 500: an exception must not leave an I/O
// thread's run loop, which would end the server.
Response handled(Handler& handler, Request& request) {
    try {
        return handler.handle(request);
    } catch (const std::exception&) {
        return plain(500, "internal error");
    }
}

class Session : public std::enable_shared_from_this<Session> {
public:
    Session(Server::Impl& server, tcp::socket socket)
        : server_(server), limits_(server.limits), socket_(std::move(socket)),
          deadline_(socket_.get_executor()), quiet_(socket_.get_executor()),
          buffer_(limits_.header_bytes + read_room) {
        error_code ignored;
        const auto peer = socket_.remote_endpoint(ignored);
        if (!ignored) remote_ = peer.address().to_string();
    }
    ~Session() {
        if (reserved_ > 0) server_.release(reserved_);
        server_.connection_ended();
    }

    void start() {
        asio::dispatch(socket_.get_executor(), [self = shared_from_this()] {
            self->read_head(true);
        });
    }

private:
    // After `after`, the pending read or write is cancelled and timed_out_ is set. A wait that
    // had already expired when it was re-armed or disarmed (its handler queued, too late to
    // cancel) carries an older generation and does nothing.
    void arm(std::chrono::milliseconds after) {
        timed_out_ = false;
        const std::uint64_t armed = ++generation_;
        deadline_.expires_after(after);
        deadline_.async_wait([self = shared_from_this(), armed](error_code ec) {
            if (ec || armed != self->generation_) return;   // re-armed or disarmed
            self->timed_out_ = true;
            error_code ignored;
            self->socket_.cancel(ignored);
        });
    }
    void disarm() {
        ++generation_;
        deadline_.cancel();
    }

    void read_head(bool first) {
        if (server_.stopped) return close();
        request_ = Request{};
        request_.remote = remote_;
        parser_.emplace();
        parser_->header_limit(limits_.header_bytes);
        parser_->body_limit(limits_.body_bytes);
        // A new connection's first head, and a kept-alive one's next, each get the head time;
        // a kept-alive connection may first sit idle for idle_time.
        arm(first ? limits_.head_time : limits_.idle_time + limits_.head_time);
        bhttp::async_read_header(socket_, buffer_, *parser_,
                                 [self = shared_from_this()](error_code ec, std::size_t) {
                                     self->on_head(ec);
                                 });
    }

    void on_head(error_code ec) {
        disarm();
        if (ec) {
            const bool some = parser_->got_some() || buffer_.size() > 0;
            if (timed_out_) {
                if (!some) return close();
                return refuse(408, "the request's head did not arrive in time");
            }
            if (ec == bhttp::error::header_limit || ec == bhttp::error::buffer_overflow) {
                return refuse(431, "the request's head is over its size limit");
            }
            if (ec == bhttp::error::body_limit) {
                return refuse(413, "the request body is over the size limit");
            }
            if (!some || ec == bhttp::error::end_of_stream || ec == asio::error::eof ||
                ec == asio::error::connection_reset || ec == asio::error::operation_aborted) {
                return close();
            }
            return refuse(400, "the request is malformed");
        }
        const auto& head = parser_->get();
        request_.method.assign(head.method_string().data(), head.method_string().size());
        request_.target.assign(head.target().data(), head.target().size());
        request_.path = request_.target.substr(0, request_.target.find('?'));
        request_.version = static_cast<int>(head.version());
        request_.started = Clock::now();
        std::size_t count = 0;
        for (const auto& field : head) {
            if (++count > limits_.header_count) {
                return refuse(431, "the request has too many header fields");
            }
            const auto name = field.name_string();
            const auto value = field.value();
            request_.fields.push_back({lower(std::string_view(name.data(), name.size())),
                                       std::string(value.data(), value.size())});
        }
        if (request_.target.size() > limits_.target_bytes) {
            return refuse(414, "the request target is too long");
        }
        if (head.version() != 11 && head.version() != 10) {
            return refuse(505, "only HTTP/1.0 and 1.1 are served");
        }
        keep_alive_ = head.keep_alive();
        std::optional<Response> refused;
        try {
            refused = server_.handler.check_head(request_);
        } catch (const std::exception&) {
            refused = plain(500, "internal error");
        }
        if (refused) {
            keep_alive_ = false;
            return respond(std::move(*refused));
        }
        if (parser_->is_done()) return dispatch();
        if (request_.version == 11 && lower(request_.field("expect")) == "100-continue") {
            continue_ = status_line(100) + "\r\n";
            arm(limits_.write_time);
            asio::async_write(socket_, asio::buffer(continue_),
                              [self = shared_from_this()](error_code failed, std::size_t) {
                                  self->disarm();
                                  if (failed) return self->close();
                                  self->read_body();
                              });
            return;
        }
        read_body();
    }

    void read_body() {
        body_deadline_ = std::chrono::steady_clock::now() + limits_.body_time;
        read_more();
    }

    // A piece of the body at a time, its memory taken from the shared budget as it arrives:
    // a connection that declares a large body and sends nothing holds nothing.
    void read_more() {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            body_deadline_ - std::chrono::steady_clock::now());
        arm(std::max(left, std::chrono::milliseconds(0)));
        bhttp::async_read_some(socket_, buffer_, *parser_,
                               [self = shared_from_this()](error_code ec, std::size_t) {
                                   self->on_body(ec);
                               });
    }

    void on_body(error_code ec) {
        disarm();
        if (!ec) {
            const std::uint64_t held = parser_->get().body().capacity();
            if (held > reserved_) {
                if (!server_.reserve(held - reserved_)) {
                    Response busy = plain(503, "the server is reading too many request bodies");
                    busy.set("Retry-After", "1");
                    keep_alive_ = false;
                    return respond(std::move(busy));
                }
                reserved_ = held;
            }
            if (!parser_->is_done()) return read_more();
        }
        if (ec) {
            keep_alive_ = false;
            if (timed_out_) return refuse(408, "the request body did not arrive in time");
            if (ec == bhttp::error::body_limit) {
                return refuse(413, "the request body is over the size limit");
            }
            if (ec == bhttp::error::buffer_overflow) {
                return refuse(413, "the request body's framing is over its size limit");
            }
            if (ec == bhttp::error::end_of_stream || ec == asio::error::eof ||
                ec == asio::error::connection_reset) {
                return close();
            }
            return refuse(400, "the request body is malformed");
        }
        request_.body = std::move(parser_->get().body());
        request_.body_bytes = request_.body.size();
        dispatch();
    }

    void dispatch() {
        parser_.reset();
        if (!server_.handler.blocking(request_)) return respond(handled(server_.handler, request_));
        asio::post(server_.blocking, [self = shared_from_this()] {
            auto response =
                std::make_shared<Response>(handled(self->server_.handler, self->request_));
            asio::post(self->socket_.get_executor(),
                       [self, response] { self->respond(std::move(*response)); });
        });
    }

    void refuse(int status, const std::string& message) {
        keep_alive_ = false;
        respond(plain(status, message));
    }

    void respond(Response response) {
        request_.body.clear();
        request_.body.shrink_to_fit();
        if (reserved_ > 0) {
            server_.release(reserved_);
            reserved_ = 0;
        }
        server_.handler.answered(request_, response.status);
        const bool head_only = request_.method == "HEAD";
        if (server_.stopped || ++served_ >= limits_.requests_per_connection) keep_alive_ = false;
        std::string text = status_line(response.status);
        for (const Field& f : response.fields) text += f.name + ": " + f.value + "\r\n";
        text += "Date: " + http_date() + "\r\n";
        if (response.events) {
            // HTTP/1.0 has no chunked coding: the stream then ends when the connection does.
            chunked_ = request_.version == 11;
            text += chunked_ ? "Transfer-Encoding: chunked\r\nConnection: close\r\n\r\n"
                             : "Connection: close\r\n\r\n";
            events_ = std::move(response.events);
            keep_alive_ = false;
            return write(std::move(text), [self = shared_from_this()] {
                if (!self->head_only()) return self->start_events();
                self->finish();
            });
        }
        std::uint64_t length = response.file ? response.file->length : response.body.size();
        const bool bodiless = response.status == 304 || response.status == 204;
        if (!bodiless) text += "Content-Length: " + std::to_string(length) + "\r\n";
        text += keep_alive_ ? "Connection: keep-alive\r\n\r\n" : "Connection: close\r\n\r\n";
        if (head_only || bodiless) return write(std::move(text), [self = shared_from_this()] {
            self->finish();
        });
        if (response.file) {
            file_ = std::move(*response.file);
            return write(std::move(text), [self = shared_from_this()] { self->send_file(); });
        }
        text += response.body;
        write(std::move(text), [self = shared_from_this()] { self->finish(); });
    }

    bool head_only() const { return request_.method == "HEAD"; }

    // Writes `text` within the write time, then calls `then`; a failed write closes.
    void write(std::string text, std::function<void()> then) {
        out_ = std::move(text);
        arm(limits_.write_time);
        asio::async_write(socket_, asio::buffer(out_),
                          [self = shared_from_this(), then = std::move(then)](error_code ec,
                                                                              std::size_t) {
                              self->disarm();
                              if (ec) return self->close();
                              then();
                          });
    }

    void send_file() {
        if (!file_ || file_->length == 0) return finish();
        const std::size_t n = static_cast<std::size_t>(
            std::min<std::uint64_t>(file_->length, std::uint64_t{1} << 16));
        std::string chunk(n, '\0');
        const ssize_t got = pread(*file_->fd, chunk.data(), n, static_cast<off_t>(file_->offset));
        if (got <= 0) return close();   // the length was announced: a short body must end it
        chunk.resize(static_cast<std::size_t>(got));
        file_->offset += static_cast<std::uint64_t>(got);
        file_->length -= static_cast<std::uint64_t>(got);
        if (file_->sent) file_->sent(static_cast<std::uint64_t>(got));
        write(std::move(chunk), [self = shared_from_this()] { self->send_file(); });
    }

    // After a whole response: the next request, or a graceful close.
    void finish() {
        file_.reset();
        if (keep_alive_) return read_head(false);
        linger();
    }

    // Ends sending, then reads (and drops) what the client still sends, for a bounded time
    // and amount, so that closing does not reset the connection before the client has read
    // the response.
    void linger() {
        error_code ignored;
        socket_.shutdown(tcp::socket::shutdown_send, ignored);
        arm(std::chrono::milliseconds(2000));
        drain();
    }

    void drain() {
        scratch_.resize(16384);
        socket_.async_read_some(asio::buffer(scratch_),
                                [self = shared_from_this()](error_code ec, std::size_t n) {
                                    self->drained_ += n;
                                    if (ec || self->drained_ > (1u << 20)) {
                                        self->disarm();
                                        return self->close();
                                    }
                                    self->drain();
                                });
    }

    void close() {
        closed_ = true;
        disarm();
        quiet_.cancel();
        error_code ignored;
        socket_.close(ignored);
        events_.reset();
    }

    // text/event-stream: the source's chunks as they come; a client that closes (or sends
    // anything) ends the stream at once.
    void start_events() {
        std::weak_ptr<Session> weak = weak_from_this();
        auto executor = socket_.get_executor();
        events_->watch([weak, executor] {
            asio::post(executor, [weak] {
                if (auto self = weak.lock()) self->quiet_.cancel();
            });
        });
        scratch_.resize(256);
        socket_.async_read_some(asio::buffer(scratch_),
                                [self = shared_from_this()](error_code, std::size_t) {
                                    self->close();
                                });
        pump();
    }

    void pump() {
        if (closed_ || writing_ || !events_) return;
        bool ended = false;
        std::string text;
        try {
            text = events_->next(ended);
        } catch (const std::exception&) {
            ended = true;
        }
        if (server_.stopped) ended = true;
        if (!text.empty() || ended) return send_chunk(text, ended);
        quiet_.expires_after(events_->quiet);
        quiet_.async_wait([self = shared_from_this()](error_code ec) {
            if (self->closed_) return;
            if (ec) return self->pump();   // woken: something may be new
            self->send_chunk(self->events_->keep_alive, false);
        });
    }

    void send_chunk(const std::string& text, bool last) {
        std::string framed;
        if (!chunked_) {
            framed = text;
        } else if (!text.empty()) {
            char size[32];
            std::snprintf(size, sizeof size, "%zx\r\n", text.size());
            framed = size + text + "\r\n";
        }
        if (last && chunked_) framed += "0\r\n\r\n";
        writing_ = true;
        out_ = std::move(framed);
        arm(limits_.write_time);
        asio::async_write(socket_, asio::buffer(out_),
                          [self = shared_from_this(), last](error_code ec, std::size_t) {
                              self->disarm();
                              self->writing_ = false;
                              if (ec || self->closed_) return self->close();
                              if (last) {
                                  // The watch on the socket's read side closes it when the
                                  // client does, or at this deadline.
                                  self->events_.reset();
                                  error_code ignored;
                                  self->socket_.shutdown(tcp::socket::shutdown_send, ignored);
                                  return self->arm(std::chrono::milliseconds(2000));
                              }
                              self->pump();
                          });
    }

    Server::Impl& server_;
    const Limits& limits_;
    tcp::socket socket_;
    asio::steady_timer deadline_, quiet_;
    boost::beast::flat_buffer buffer_;
    std::chrono::steady_clock::time_point body_deadline_{};
    std::optional<bhttp::request_parser<bhttp::string_body>> parser_;
    Request request_;
    std::string remote_, out_, continue_, scratch_;
    std::optional<FileBody> file_;
    std::shared_ptr<EventSource> events_;
    std::uint64_t reserved_ = 0;
    std::uint64_t generation_ = 0;   // of the deadline's wait (arm)
    std::size_t drained_ = 0;
    int served_ = 0;
    bool keep_alive_ = false, timed_out_ = false, closed_ = false, writing_ = false;
    bool chunked_ = true;
};

}  // namespace

void Server::Impl::accept() {
    if (stopped) return;
    if (connections.load() >= limits.max_connections) {
        accept_paused = true;   // the kernel's queue holds the rest until one ends
        return;
    }
    acceptor.async_accept(asio::make_strand(io), [this](error_code ec, tcp::socket socket) {
        asio::post(accepting, [this, ec, socket = std::move(socket)]() mutable {
            if (ec == asio::error::operation_aborted || stopped) return;
            if (!ec) {
                ++connections;
                std::make_shared<Session>(*this, std::move(socket))->start();
            } else {
                // Out of descriptors, say: wait a moment rather than spin.
                std::this_thread::sleep_for(std::chrono::milliseconds(10));
            }
            accept();
        });
    });
}

void Server::Impl::connection_ended() {
    --connections;
    if (stopped) return;
    asio::post(accepting, [this] {
        if (accept_paused && connections.load() < limits.max_connections) {
            accept_paused = false;
            accept();
        }
    });
}

Server::Server(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Server::~Server() {
    stop();
    // Requests still queued for the blocking threads are dropped, not handled for nobody.
    impl_->blocking.stop();
    impl_->blocking.join();
}

Expected<std::unique_ptr<Server>> Server::bind(const std::string& host, int port,
                                               const Limits& limits, Handler& handler) {
    error_code ec;
    const auto address = asio::ip::make_address(host, ec);
    if (ec) return Error{"'" + host + "' is not a numeric IPv4 or IPv6 address"};
    auto impl = std::make_unique<Impl>(limits, handler);
    impl->limits.max_connections =
        std::min(limits.max_connections, std::max(16, descriptor_room() / 2 - 32));
    const tcp::endpoint endpoint(address, static_cast<std::uint16_t>(port));
    tcp::acceptor& acceptor = impl->acceptor;
    const std::string where = address.is_v6() ? "[" + host + "]:" + std::to_string(port)
                                              : host + ":" + std::to_string(port);
    acceptor.open(endpoint.protocol(), ec);
    if (!ec) acceptor.set_option(asio::socket_base::reuse_address(true), ec);
    if (!ec) acceptor.bind(endpoint, ec);
    if (ec) {
        return Error{"cannot listen on " + where + ": " + ec.message() +
                     (port == 0 ? "" : " (in use, or not an address of this machine)")};
    }
    acceptor.listen(asio::socket_base::max_listen_connections, ec);
    if (ec) return Error{"cannot listen on " + where + ": " + ec.message()};
    impl->port = acceptor.local_endpoint().port();
    return std::unique_ptr<Server>(new Server(std::move(impl)));
}

int Server::port() const { return impl_->port; }

void Server::run() {
    if (impl_->stopped) return;
    impl_->working.emplace(impl_->io.get_executor());
    asio::post(impl_->accepting, [impl = impl_.get()] { impl->accept(); });
    std::vector<std::thread> threads;
    for (int i = 1; i < std::max(1, impl_->limits.io_threads); ++i) {
        threads.emplace_back([this] { impl_->io.run(); });
    }
    impl_->io.run();
    for (std::thread& thread : threads) thread.join();
}

void Server::stop() {
    if (impl_->stopped.exchange(true)) return;
    // The listening socket closes first, on its strand, then the I/O threads end; before
    // run(), nothing runs, and run() returns at once.
    asio::post(impl_->accepting, [impl = impl_.get()] {
        error_code ignored;
        impl->acceptor.close(ignored);
        impl->working.reset();
        impl->io.stop();
    });
}

}  // namespace discreel::serve::http
