#pragma once
// Webhooks: a job's final state POSTed to the URL its request gave ("callback"), from a thread
// of its own so no worker ever waits on a client's server, retried with backoff until that
// server answers 2xx or the tries run out. Plain HTTP to hosts the operator allowed
// (serve --callback-allow); a callback pending when the server stops is not sent.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "discreel/expected.hpp"

namespace discreel::serve {

struct CallbackUrl {
    std::string host;      // as written, lower case
    int port = 80;
    std::string path;      // "/..." with any query
};

// A host as callbacks compare it: lower case, an IPv6 address without its brackets.
std::string lower_host(std::string host);

// "http://host[:port][/path]"; an error names what is wrong with it.
Expected<CallbackUrl> parse_callback_url(const std::string& url);

struct CallbackPolicy {
    int attempts = 6;                                    // the first try and the retries
    std::chrono::milliseconds first_wait{1000};          // doubled after each failure
    std::chrono::milliseconds timeout{5000};             // to connect, send and hear back
};

class Callbacks {
public:
    explicit Callbacks(CallbackPolicy policy = {});
    ~Callbacks();
    Callbacks(const Callbacks&) = delete;
    Callbacks& operator=(const Callbacks&) = delete;

    // Queues `body` (JSON) for `url`; returns at once.
    void post(const CallbackUrl& url, std::string body, std::string job_id);
    void stop();   // pending deliveries are dropped; one under way ends within its timeout

private:
    struct Delivery {
        CallbackUrl url;
        std::string body;
        std::string job_id;
        int attempt = 0;
        std::chrono::steady_clock::time_point due;
    };
    void run();
    // One try: the status the server answered, or 0 when there was none.
    int send(const Delivery& delivery) const;

    CallbackPolicy policy_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<Delivery> pending_;
    bool stopping_ = false;
    std::thread thread_;
};

}  // namespace discreel::serve
