#pragma once
// A small HTTP/1.1 server on Boost.Asio with Boost.Beast's request parser, bounded by design:
// every connection is a few kilobytes of state on two I/O threads (no thread per connection),
// the request head has a byte, field-count and time limit, a body has a byte limit that
// chunked bodies count against too, all bodies being read or handled share one budget, and
// connections beyond the cap wait in the kernel's accept queue. What the routes mean is the
// Handler's; this file only moves bytes.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "discreel/expected.hpp"

namespace discreel::serve::http {

struct Limits {
    std::uint32_t header_bytes = 16384;          // request line and fields; 431 beyond
    std::size_t header_count = 100;              // fields; 431 beyond
    std::size_t target_bytes = 8192;             // the request target; 414 beyond
    std::uint64_t body_bytes = 1 << 20;          // one body, chunked ones too; 413 beyond
    std::uint64_t bodies_in_flight = 64 << 20;   // all bodies read or handled at once; 503
    std::chrono::milliseconds head_time{5000};   // to read a whole head; 408 beyond
    std::chrono::milliseconds idle_time{5000};   // a kept-alive connection waits this long
    std::chrono::milliseconds body_time{30000};  // to read a whole body; 408 beyond
    std::chrono::milliseconds write_time{10000}; // for each write to the client
    int max_connections = 512;                   // more wait in the accept queue
    int requests_per_connection = 100;
    int io_threads = 2;                          // read, write and answer cheap routes
    int blocking_threads = 4;                    // Handler::handle of blocking routes
};

struct Field {
    std::string name;    // lower case
    std::string value;
};

struct Request {
    std::string method;                // "GET", ...; HEAD is answered as GET without a body
    std::string target;                // as sent
    std::string path;                  // the target before any '?'
    int version = 11;                  // 10 or 11: HTTP/1.0 or 1.1
    std::vector<Field> fields;
    std::string body;
    std::size_t body_bytes = 0;        // the body's size as read (body is freed before answered)
    std::string remote;                // the peer's address
    std::chrono::steady_clock::time_point started{};   // when its head was complete

    // The first field of that (lower-case) name, or "".
    std::string_view field(std::string_view name) const;
};

// A body sent from an open file; the descriptor is closed when the last copy goes.
struct FileBody {
    std::shared_ptr<const int> fd;     // owns the descriptor
    std::uint64_t offset = 0;
    std::uint64_t length = 0;
    std::function<void(std::uint64_t)> sent;   // bytes written, after each write
};

// An endless body (text/event-stream), sent in chunks as it has something to say.
class EventSource {
public:
    virtual ~EventSource() = default;
    // What to send now ("" when nothing is new); sets `ended` when nothing will follow.
    virtual std::string next(bool& ended) = 0;
    // Calls `wake`, from any thread, whenever next() may have something new; until destroyed.
    virtual void watch(std::function<void()> wake) = 0;
    // Sent after `quiet` without anything new, so proxies keep the connection.
    std::string keep_alive = ": waiting\n\n";
    std::chrono::milliseconds quiet{15000};
};

struct Response {
    int status = 200;
    std::vector<Field> fields;         // Content-Length and Connection are added
    std::string body;
    std::optional<FileBody> file;      // instead of body
    std::shared_ptr<EventSource> events;   // instead of body: chunked, until it ends

    void set(std::string name, std::string value);
};

class Handler {
public:
    virtual ~Handler() = default;
    // Called once the head is read: a response sent at once, without reading the body (the
    // connection is closed after it), or nullopt to read the body and handle the request.
    virtual std::optional<Response> check_head(const Request& head) = 0;
    // Whether handle() may block (disk writes, scene loading): then it runs on the blocking
    // threads, never on an I/O thread.
    virtual bool blocking(const Request& request) const = 0;
    virtual Response handle(Request& request) = 0;
    // Every response, refusals of the server's own included (request fields may be empty).
    virtual void answered(const Request& request, int status) = 0;
};

class Server {
public:
    // Binds host:port (port 0: any free one); `host` is a numeric IPv4 or IPv6 address.
    static Expected<std::unique_ptr<Server>> bind(const std::string& host, int port,
                                                  const Limits& limits, Handler& handler);
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    int port() const;
    void run();    // serves until stop()
    void stop();   // safe from any thread, also before run()

    struct Impl;   // http.cpp's: the connections see it

private:
    explicit Server(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

const char* reason_phrase(int status);

}  // namespace discreel::serve::http
