#pragma once
// A child process run by a bench and timed: wall and CPU seconds, and the peak memory the
// discreel binary reports with --verbose. Benches may read the clock; the simulation never does.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

extern char** environ;

namespace discreel::bench {

struct ChildRun {
    double seconds = 0;       // wall
    double cpu_seconds = 0;   // user + system of the child and its own children
    double peak_mib = 0;      // the last "peak memory: X" it printed (discreel --verbose); 0: none
};

inline double children_cpu_seconds() {
    rusage usage{};
    getrusage(RUSAGE_CHILDREN, &usage);
    const auto seconds = [](const timeval& t) { return t.tv_sec + t.tv_usec / 1e6; };
    return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Runs `args` (args[0] found on the PATH), standard input and output /dev/null, standard error
// into `err_path`, and waits. A failure ends the bench, naming `err_path`.
inline ChildRun run_child(const std::vector<std::string>& args, const std::string& err_path) {
    std::vector<char*> argv;
    argv.reserve(args.size() + 1);
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const double cpu_before = children_cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = -1;
    int status = 0;
    if (posix_spawnp(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ) != 0 ||
        waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::cerr << args[0] << " failed; see " << err_path << '\n';
        std::exit(1);
    }
    posix_spawn_file_actions_destroy(&actions);
    ChildRun run{.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                                          start).count(),
                 .cpu_seconds = children_cpu_seconds() - cpu_before};
    std::ifstream err(err_path);
    const std::string marker = "peak memory: ";
    for (std::string line; std::getline(err, line);) {
        if (auto at = line.find(marker); at != std::string::npos) {
            run.peak_mib = std::stod(line.substr(at + marker.size()));
        }
    }
    return run;
}

}  // namespace discreel::bench
