// discreel serve: options to a serve::Server, run until SIGINT or SIGTERM.
#include <sys/stat.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <thread>

#include "commands.hpp"
#include "discreel/printable.hpp"
#include "discreel/read_file.hpp"
#include "discreel/serve.hpp"
#include "exit_codes.hpp"
#include "run_support.hpp"
#include "signals.hpp"

namespace discreel::app {
namespace {

// "ADDRESS:PORT" or "[IPV6]:PORT"; the port 0..65535. An error says what is wrong.
Status split_listen(const std::string& text, std::string& host, int& port) {
    const std::string usage = "--listen takes ADDRESS:PORT, e.g. 127.0.0.1:8080 or [::1]:8080, "
                              "got '" + text + "'";
    std::string digits;
    if (!text.empty() && text.front() == '[') {
        const auto close = text.find("]:");
        if (close == std::string::npos) return Error{usage};
        host = text.substr(1, close - 1);
        digits = text.substr(close + 2);
    } else {
        const auto colon = text.rfind(':');
        if (colon == std::string::npos || colon == 0) return Error{usage};
        host = text.substr(0, colon);
        if (host.find(':') != std::string::npos) {
            return Error{"--listen: write an IPv6 address in brackets, e.g. [" + host + "]:" +
                         text.substr(colon + 1) + ", got '" + text + "'"};
        }
        digits = text.substr(colon + 1);
    }
    if (host.empty() || digits.empty() || digits.size() > 5 ||
        digits.find_first_not_of("0123456789") != std::string::npos ||
        std::stoi(digits) > 65535) {
        return Error{usage};
    }
    port = std::stoi(digits);
    return {};
}

// The token file: one token of visible ASCII, at most 4 KiB, a final newline ignored.
Expected<std::string> read_token(const std::string& path) {
    constexpr std::size_t max_token_file = 4096;
    const auto named = [&](const std::string& problem) {
        return Error{"the token file '" + printable(path) + "' " + problem};
    };
    struct stat info {};
    if (stat(path.c_str(), &info) != 0) return named(std::string("cannot be read: ") +
                                                    std::strerror(errno));
    if (!S_ISREG(info.st_mode)) return named("is not a regular file");
    auto read = read_file_bounded(path, max_token_file);
    if (!read) return named("cannot be read: " + read.error().message);
    if (read->too_large) return named("is over 4 KiB: it must hold one token");
    std::string token = read->bytes;
    while (!token.empty() && (token.back() == '\n' || token.back() == '\r')) token.pop_back();
    if (token.empty()) return named("is empty: it must hold one token");
    for (const char c : token) {
        if (c <= ' ' || c > '~') {
            return named("must hold one token of visible ASCII characters: no spaces, control "
                         "or NUL bytes");
        }
    }
    return token;
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
    def.allow_hosts = o.allow_hosts;
    def.cors_origins = o.cors_origins;
    def.keep_seconds = o.keep_seconds;
    def.keep_bytes = o.keep_bytes;
    def.callback_allow = o.callback_allow;
    if (Status listen = split_listen(o.listen, def.host, def.port); !listen) {
        report_error(err, listen.error().message);
        return exit_bad_input;
    }
    if (Status data = serve::check_data_dir(def.data_dir); !data) {
        report_error(err, data.error().message);
        return exit_bad_input;
    }
    if (o.token_file) {
        auto token = read_token(*o.token_file);
        if (!token) {
            report_error(err, token.error().message);
            return exit_bad_input;
        }
        def.token = std::move(*token);
    }
    auto server = serve::Server::open(def);
    if (!server) {
        report_error(err, server.error().message);
        return exit_runtime_failure;
    }
    // A client that goes away must not look like a request to stop.
    std::signal(SIGPIPE, SIG_IGN);
    const bool v6 = def.host.find(':') != std::string::npos;
    out << "listening on http://" << (v6 ? "[" + def.host + "]" : def.host) << ':'
        << server->port() << std::endl;
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
