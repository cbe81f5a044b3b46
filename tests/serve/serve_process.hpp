#pragma once
// A `discreel serve` process for tests: started on 127.0.0.1 with a free port and the test's
// data directory, its port read from its first line, stopped by pid (SIGTERM, then SIGKILL
// after a bound) when the test ends or asks.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <poll.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace discreel::testing {

class ServeProcess {
public:
    // `prefix`: words before the binary (e.g. {"prlimit", "--fsize=..."}).
    ServeProcess(const std::string& bin, const std::vector<std::string>& args,
                 const std::string& log_path, const std::vector<std::string>& prefix = {}) {
        int out[2];
        if (pipe(out) != 0) throw std::runtime_error("pipe");
        std::vector<std::string> argv = prefix;
        argv.push_back(bin);
        argv.push_back("serve");
        if (std::find(args.begin(), args.end(), "--listen") == args.end()) {
            argv.push_back("--listen");
            argv.push_back("127.0.0.1:0");
        }
        argv.insert(argv.end(), args.begin(), args.end());
        pid_ = fork();
        if (pid_ == 0) {
            dup2(out[1], STDOUT_FILENO);
            const int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
            if (log >= 0) dup2(log, STDERR_FILENO);
            close(out[0]);
            close(out[1]);
            std::vector<char*> raw;
            for (auto& word : argv) raw.push_back(word.data());
            raw.push_back(nullptr);
            execvp(raw[0], raw.data());
            _exit(127);
        }
        close(out[1]);
        out_ = out[0];
        log_path_ = log_path;
        try {
            port_ = read_port();
        } catch (...) {
            stop(SIGKILL);
            close(out_);
            throw;
        }
    }
    ~ServeProcess() {
        stop(SIGTERM);
        if (out_ >= 0) close(out_);
    }
    ServeProcess(const ServeProcess&) = delete;
    ServeProcess& operator=(const ServeProcess&) = delete;

    int port() const { return port_; }
    const std::string& first_line() const { return line_; }
    pid_t pid() const { return pid_; }

    // Sends `signal` and waits for the exit (10 s, then SIGKILL); the exit status, or -1.
    int stop(int signal) {
        if (pid_ <= 0) return -1;
        kill(pid_, signal);
        int status = 0;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
        while (waitpid(pid_, &status, WNOHANG) == 0) {
            if (std::chrono::steady_clock::now() > deadline) {
                kill(pid_, SIGKILL);
                waitpid(pid_, &status, 0);
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        pid_ = -1;
        return status;
    }

private:
    // "listening on http://127.0.0.1:PORT", within 20 s.
    int read_port() {
        std::string line;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (line.find('\n') == std::string::npos) {
            pollfd fd{out_, POLLIN, 0};
            if (std::chrono::steady_clock::now() > deadline || poll(&fd, 1, 200) < 0) break;
            if ((fd.revents & (POLLIN | POLLHUP)) == 0) continue;
            char c = 0;
            if (read(out_, &c, 1) != 1) break;
            line += c;
        }
        while (!line.empty() && line.back() == '\n') line.pop_back();
        line_ = line;
        const auto colon = line.rfind(':');
        if (line.rfind("listening on http://", 0) != 0 || colon == std::string::npos) {
            // What it said instead, from its log, for the test's message.
            throw std::runtime_error("discreel serve did not start: '" + line + "' " +
                                     log_tail());
        }
        return std::stoi(line.substr(colon + 1));
    }

    std::string log_tail() const {
        std::ifstream log(log_path_);
        std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
        return text.size() > 2000 ? text.substr(text.size() - 2000) : text;
    }

    pid_t pid_ = -1;
    int out_ = -1;
    int port_ = 0;
    std::string line_, log_path_;
};

}  // namespace discreel::testing
