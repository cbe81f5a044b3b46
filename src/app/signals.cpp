#include "signals.hpp"

#include <csignal>

#include <atomic>

namespace discreel::app {
namespace {

// Only lock-free atomics may be touched from a signal handler.
std::atomic<int> received{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void record_signal(int signal) { received.store(signal, std::memory_order_relaxed); }

}  // namespace

void install_stop_handlers() {
    struct sigaction action {};
    action.sa_handler = record_signal;
    sigemptyset(&action.sa_mask);
    // SA_RESETHAND: the first signal asks politely; the next one gets the default action.
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

void ignore_file_size_signal() {
    // Past a file-size limit (ulimit -f, a quota) the default SIGXFSZ kills the process and
    // leaves its temporary file behind; ignored, the write fails with EFBIG and the usual
    // clean-up runs: an error, exit 3, nothing written.
    std::signal(SIGXFSZ, SIG_IGN);
}

int stop_signal() { return received.load(std::memory_order_relaxed); }

}  // namespace discreel::app
