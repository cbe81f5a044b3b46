#include "signals.hpp"

#include <unistd.h>

#include <csignal>

#include <atomic>

#include "discreel/commit.hpp"
#include "discreel/temporary_files.hpp"

namespace discreel::app {
namespace {

// Only lock-free atomics may be touched from a signal handler.
std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free);

// A run still going this long after its first stop signal is ended as by a second one: a
// call that no signal interrupts (a write to a pipe nobody reads) cannot keep it alive.
constexpr unsigned grace_seconds = 10;

extern "C" void on_stop_signal(int signal_number) {
    int none = 0;
    const bool first = received.compare_exchange_strong(none, signal_number,
                                                        std::memory_order_relaxed);
    if (first) {
        alarm(grace_seconds);
        return;
    }
    if (signal_number == SIGPIPE) return;
    if (commit_in_progress()) {
        alarm(1);   // the commit ends in moments; then the grace's end comes again
        return;
    }
    // The grace's end (SIGALRM) ends the run with the signal that asked for the stop.
    const int ending = signal_number == SIGALRM ? received.load(std::memory_order_relaxed)
                                                : signal_number;
    delete_temporary_files_now();
    std::signal(ending, SIG_DFL);
    std::raise(ending);
}

void catch_signal(int signal_number) {
    struct sigaction current {};
    // A signal the parent set to be ignored (nohup, a shell's background job) stays ignored.
    if (sigaction(signal_number, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) return;
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigfillset(&action.sa_mask);   // one handler at a time: the second-signal test is exact
    action.sa_flags = SA_RESTART;
    sigaction(signal_number, &action, nullptr);
}

}  // namespace

void install_stop_handlers() {
    for (const int signal_number : {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGUSR1, SIGUSR2, SIGPIPE,
                                    SIGALRM, SIGVTALRM, SIGPROF, SIGXCPU, SIGIO, SIGPWR,
                                    SIGSTKFLT}) {
        catch_signal(signal_number);
    }
    for (int signal_number = SIGRTMIN; signal_number <= SIGRTMAX; ++signal_number) {
        catch_signal(signal_number);
    }
}

void ignore_file_size_signal() {
    // Past a file-size limit (ulimit -f, a quota) the default SIGXFSZ kills the process and
    // leaves its temporary file behind; ignored, the write fails with EFBIG and the usual
    // clean-up runs: an error, exit 3, nothing written.
    std::signal(SIGXFSZ, SIG_IGN);
}

int stop_signal() { return received.load(std::memory_order_relaxed); }

}  // namespace discreel::app
