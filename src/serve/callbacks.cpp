#include "callbacks.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <fcntl.h>

#include <nlohmann/json.hpp>

#include "jobs.hpp"

namespace discreel::serve {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t max_pending = 10'000;   // deliveries waiting, retries included

// A connected socket to host:port within `timeout`, or -1.
int connect_within(const std::string& host, int port, std::chrono::milliseconds timeout) {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0) return -1;
    int fd = -1;
    for (addrinfo* a = found; a != nullptr && fd < 0; a = a->ai_next) {
        fd = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC | SOCK_NONBLOCK, a->ai_protocol);
        if (fd < 0) continue;
        if (connect(fd, a->ai_addr, a->ai_addrlen) != 0 && errno != EINPROGRESS) {
            close(fd);
            fd = -1;
            continue;
        }
        pollfd p{fd, POLLOUT, 0};
        int error = 0;
        socklen_t length = sizeof error;
        if (poll(&p, 1, static_cast<int>(timeout.count())) != 1 ||
            getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &length) != 0 || error != 0) {
            close(fd);
            fd = -1;
        }
    }
    freeaddrinfo(found);
    if (fd >= 0) fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK);
    return fd;
}

}  // namespace

std::string lower_host(std::string host) {
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
        host = host.substr(1, host.size() - 2);
    }
    for (char& c : host) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return host;
}

Expected<CallbackUrl> parse_callback_url(const std::string& url) {
    const std::string scheme = "http://";
    if (url.rfind(scheme, 0) != 0) {
        return Error{"'" + url + "' is not an http:// URL (callbacks are sent over plain HTTP; "
                     "put a proxy in front of an https receiver)"};
    }
    const std::string rest = url.substr(scheme.size());
    const auto slash = rest.find('/');
    const std::string authority = rest.substr(0, slash);
    CallbackUrl out;
    out.path = slash == std::string::npos ? "/" : rest.substr(slash);
    std::string host = authority;
    if (!authority.empty() && authority.front() == '[') {   // [v6]:port
        const auto close = authority.find(']');
        if (close == std::string::npos) return Error{"'" + url + "' has an unclosed '['"};
        host = authority.substr(1, close - 1);
        const std::string after = authority.substr(close + 1);
        if (!after.empty()) {
            if (after.front() != ':') return Error{"'" + url + "' is not host:port"};
            out.port = std::atoi(after.c_str() + 1);
        }
    } else if (const auto colon = authority.rfind(':'); colon != std::string::npos) {
        host = authority.substr(0, colon);
        const std::string port = authority.substr(colon + 1);
        if (port.empty() || port.size() > 5 ||
            !std::all_of(port.begin(), port.end(), [](char c) { return c >= '0' && c <= '9'; })) {
            return Error{"'" + url + "' has no valid port"};
        }
        out.port = std::stoi(port);
    }
    if (host.empty() || out.port < 1 || out.port > 65535 ||
        host.find_first_of("@ \t\r\n") != std::string::npos ||
        out.path.find_first_of(" \t\r\n") != std::string::npos) {
        return Error{"'" + url + "' is not a valid callback URL"};
    }
    out.host = lower_host(host);
    return out;
}

Callbacks::Callbacks(CallbackPolicy policy) : policy_(policy) {
    thread_ = std::thread([this] { run(); });
}

Callbacks::~Callbacks() { stop(); }

void Callbacks::stop() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
        pending_.clear();
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void Callbacks::post(const CallbackUrl& url, std::string body, std::string job_id) {
    {
        std::lock_guard lock(mutex_);
        if (stopping_) return;
        // Receivers that never answer could otherwise grow the queue without end.
        if (pending_.size() >= max_pending) {
            log_line("callback_dropped", {{"id", job_id}, {"reason", "too many pending"}});
            return;
        }
        pending_.push_back({url, std::move(body), std::move(job_id), 0, Clock::now()});
    }
    wake_.notify_all();
}

int Callbacks::send(const Delivery& d) const {
    const int fd = connect_within(d.url.host, d.url.port, policy_.timeout);
    if (fd < 0) return 0;
    timeval limit{static_cast<time_t>(policy_.timeout.count() / 1000),
                  static_cast<suseconds_t>(policy_.timeout.count() % 1000 * 1000)};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
    const std::string host = d.url.host.find(':') != std::string::npos ? "[" + d.url.host + "]"
                                                                       : d.url.host;
    const std::string request = "POST " + d.url.path + " HTTP/1.1\r\nHost: " + host + ":" +
                                std::to_string(d.url.port) +
                                "\r\nContent-Type: application/json\r\nContent-Length: " +
                                std::to_string(d.body.size()) +
                                "\r\nUser-Agent: discreel\r\nConnection: close\r\n\r\n" + d.body;
    std::size_t sent = 0;
    while (sent < request.size()) {
        const ssize_t n = ::send(fd, request.data() + sent, request.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) {
            close(fd);
            return 0;
        }
        sent += static_cast<std::size_t>(n);
    }
    // The status line is all that matters: "HTTP/1.1 204 ...".
    char head[64] = {};
    std::size_t got = 0;
    while (got < sizeof head - 1) {
        const ssize_t n = recv(fd, head + got, sizeof head - 1 - got, 0);
        if (n <= 0) break;
        got += static_cast<std::size_t>(n);
        if (std::find(head, head + got, '\n') != head + got) break;
    }
    close(fd);
    const std::string line(head, got);
    if (line.rfind("HTTP/1.", 0) != 0 || line.size() < 12) return 0;
    return std::atoi(line.c_str() + 9);
}

void Callbacks::run() {
    std::unique_lock lock(mutex_);
    while (!stopping_) {
        if (pending_.empty()) {
            wake_.wait(lock, [&] { return stopping_ || !pending_.empty(); });
            continue;
        }
        auto next = std::min_element(pending_.begin(), pending_.end(),
                                     [](const Delivery& a, const Delivery& b) { return a.due < b.due; });
        if (next->due > Clock::now()) {
            wake_.wait_until(lock, next->due);
            continue;
        }
        Delivery d = std::move(*next);
        pending_.erase(next);
        lock.unlock();
        const int status = send(d);
        ++d.attempt;
        const bool delivered = status >= 200 && status < 300;
        log_line("callback", {{"id", d.job_id},
                              {"attempt", d.attempt},
                              {"status", status},
                              {"delivered", delivered}});
        lock.lock();
        if (delivered || stopping_) continue;
        if (d.attempt >= policy_.attempts) {
            log_line("callback_dropped", {{"id", d.job_id}, {"attempts", d.attempt}});
            continue;
        }
        d.due = Clock::now() + policy_.first_wait * (1 << (d.attempt - 1));
        pending_.push_back(std::move(d));
    }
}

}  // namespace discreel::serve
