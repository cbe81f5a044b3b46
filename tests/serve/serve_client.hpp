#pragma once
// What the service's tests share: an HTTP client with bounded waits, raw sockets for what no
// well-behaved client sends, a small scene, and the server process's memory.
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <httplib.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

namespace discreel::testing {

// A small scene; `seed` changes the job id (a comment is part of the scene's text) and, through
// the physics seed, nothing else that a still at frame 0 shows.
inline std::string scene_text(int seed = 1, double duration = 1.0) {
    return "# seed " + std::to_string(seed) +
           "\nversion: 1\nvideo:\n  size: [320, 180]\n  fps: 30\n  duration: " +
           std::to_string(duration) +
           "\nphysics:\n  restitution: 0.7\nwalls:\n  - box: [[0, 0], [3.2, 1.8]]\n"
           "discs:\n  - random:\n      count: 40\n      region: [[0.2, 0.2], [3.0, 1.6]]\n"
           "      radius: [0.05, 0.12]\n      speed: [0, 3]\n";
}

inline httplib::Client client_for(int port) {
    httplib::Client client("127.0.0.1", port);
    client.set_connection_timeout(5);
    client.set_read_timeout(30);
    client.set_write_timeout(5);
    return client;
}

inline httplib::Result post(httplib::Client& client, const std::string& path,
                            const nlohmann::json& body, const httplib::Headers& headers = {}) {
    return client.Post(path, headers, body.dump(), "application/json");
}

// Polls the job until it is final, at most `seconds`; the last answer.
inline nlohmann::json wait_final(httplib::Client& client, const std::string& id,
                                 double seconds = 60, const httplib::Headers& headers = {}) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    nlohmann::json job;
    while (std::chrono::steady_clock::now() < deadline) {
        auto got = client.Get("/v1/renders/" + id, headers);
        if (got && got->status == 200) {
            job = nlohmann::json::parse(got->body);
            const std::string status = job["status"];
            if (status == "succeeded" || status == "failed" || status == "cancelled") return job;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return job;
}

// A connection to 127.0.0.1:port whose reads give up after `seconds`; -1 if refused.
inline int connect_to(int port, int seconds = 10) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    timeval timeout{seconds, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
        close(fd);
        return -1;
    }
    return fd;
}

// Reads until the head of a response is in (or the peer closes, or 100 reads), then closes.
inline std::string read_head(int fd) {
    std::string got;
    char buffer[4096];
    for (int reads = 0; reads < 100; ++reads) {
        const ssize_t n = recv(fd, buffer, sizeof buffer, 0);
        if (n <= 0) break;
        got.append(buffer, static_cast<std::size_t>(n));
        if (got.find("\r\n\r\n") != std::string::npos) break;
    }
    close(fd);
    return got;
}

inline std::string exchange(int fd, const std::string& sent) {
    (void)send(fd, sent.data(), sent.size(), MSG_NOSIGNAL);
    return read_head(fd);
}

// Whether the peer has sent something (or closed) within `ms`.
inline bool readable(int fd, int ms = 0) {
    pollfd p{fd, POLLIN, 0};
    return poll(&p, 1, ms) > 0;
}

// A field of /proc/PID/status, kB ("VmRSS", "VmHWM"); -1 when not found.
inline long memory_kb(pid_t pid, const std::string& field) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(field + ":", 0) == 0) return std::stol(line.substr(field.size() + 1));
    }
    return -1;
}

inline std::string metric(const std::string& text, const std::string& name) {
    const auto at = text.find("\n" + name + " ");
    if (at == std::string::npos) return "";
    const auto start = at + name.size() + 2;
    return text.substr(start, text.find('\n', start) - start);
}

}  // namespace discreel::testing
