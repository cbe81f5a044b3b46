// discreel serve: options to a serve::Server, run until SIGINT or SIGTERM.
#include <atomic>
#include <csignal>
#include <thread>

#include "commands.hpp"
#include "discreel/read_file.hpp"
#include "discreel/serve.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace discreel::app {
namespace {

// "HOST:PORT" with a numeric address; the port 0..65535.
bool split_listen(const std::string& text, std::string& host, int& port) {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) return false;
    host = text.substr(0, colon);
    const std::string digits = text.substr(colon + 1);
    if (digits.empty() || digits.size() > 5 ||
        digits.find_first_not_of("0123456789") != std::string::npos) {
        return false;
    }
    port = std::stoi(digits);
    return port <= 65535;
}

}  // namespace

int run_serve(const ServeOptions& o, std::ostream& out, std::ostream& err) {
    serve::ServeDef def;
    def.data_dir = o.data_dir;
    def.workers = o.workers;
    def.max_queue = o.max_queue;
    def.limits = o.limits;
    def.job_timeout = o.job_timeout;
    def.version = o.version;
    if (!split_listen(o.listen, def.host, def.port)) {
        report_error(err, "--listen takes ADDRESS:PORT, e.g. 127.0.0.1:8080, got '" + o.listen +
                              "'");
        return exit_bad_input;
    }
    if (o.token_file) {
        auto read = read_file_bounded(*o.token_file, 4096);
        if (!read) {
            report_error(err, read.error().message);
            return exit_bad_input;
        }
        std::string token = read->bytes;
        while (!token.empty() && (token.back() == '\n' || token.back() == '\r' ||
                                  token.back() == ' ' || token.back() == '\t')) {
            token.pop_back();
        }
        if (token.empty() || token.find_first_of(" \t\r\n") != std::string::npos) {
            report_error(err, "the token file '" + *o.token_file +
                                  "' must hold one token: no spaces, not empty");
            return exit_bad_input;
        }
        def.token = std::move(token);
    }
    auto server = serve::Server::open(def);
    if (!server) {
        report_error(err, server.error().message);
        return exit_runtime_failure;
    }
    // A client that goes away must not look like a request to stop.
    std::signal(SIGPIPE, SIG_IGN);
    out << "listening on http://" << def.host << ':' << server->port() << std::endl;
    std::atomic<bool> finished{false};
    std::thread watcher([&] {
        while (!finished && stop_signal() == 0) {
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        server->stop();
    });
    const Status served = server->run();
    finished = true;
    watcher.join();
    if (!served) {
        report_error(err, served.error().message);
        return exit_runtime_failure;
    }
    return exit_ok;
}

}  // namespace discreel::app
