// The registry is read by a signal handler, which may not lock or allocate. Registration
// locks a mutex and stores a heap copy of the path in a slot; the handler only loads slot
// pointers. Slots live in chunks of doubling size that are never freed or moved, so a slot's
// address stays valid for the handler however many files come and go (a PNG sequence makes
// one per frame).
#include "discreel/temporary_files.hpp"

#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

namespace discreel {
namespace {

constexpr std::size_t first_chunk_size = 64;
constexpr std::size_t chunk_count = 40;   // 64 * (2^40 - 1) slots: more than memory holds

struct Registry {
    std::array<std::atomic<std::atomic<char*>*>, chunk_count> chunks{};
    std::mutex mutex;                   // guards everything below, and writes to the slots
    std::size_t used = 0;               // slots handed out so far, free or not
    std::vector<std::size_t> free_slots;
};

Registry& registry() {
    // Never destroyed: a crash during static destruction still finds it.
    static Registry* const instance = new Registry;
    return *instance;
}

// Slot `index` is the (index - (2^k - 1) 64)th of chunk k, whose size is 2^k 64.
std::atomic<char*>* slot_of(Registry& r, std::size_t index, bool create) {
    std::size_t chunk = 0, start = 0, size = first_chunk_size;
    while (index >= start + size) {
        start += size;
        size *= 2;
        ++chunk;
    }
    std::atomic<char*>* slots = r.chunks[chunk].load(std::memory_order_acquire);
    if (!slots && create) {
        slots = new std::atomic<char*>[size]();
        r.chunks[chunk].store(slots, std::memory_order_release);
    }
    return slots ? slots + (index - start) : nullptr;
}

std::array<struct sigaction, NSIG> previous_actions{};

void delete_registered_files() {
    Registry& r = registry();
    std::size_t size = first_chunk_size;
    for (auto& chunk : r.chunks) {
        std::atomic<char*>* slots = chunk.load(std::memory_order_acquire);
        if (!slots) break;
        for (std::size_t k = 0; k < size; ++k) {
            if (char* path = slots[k].load(std::memory_order_acquire)) unlink(path);
        }
        size *= 2;
    }
}

void on_crash(int signal_number, siginfo_t* info, void* context) {
    delete_registered_files();
    const struct sigaction& previous = previous_actions[static_cast<std::size_t>(signal_number)];
    if ((previous.sa_flags & SA_SIGINFO) != 0 && previous.sa_sigaction != nullptr) {
        previous.sa_sigaction(signal_number, info, context);
        return;
    }
    if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN &&
        previous.sa_handler != nullptr) {
        previous.sa_handler(signal_number);
        return;
    }
    // The default action: die of this signal, with its exit status and core dump.
    signal(signal_number, SIG_DFL);
    raise(signal_number);
}

}  // namespace

std::size_t register_temporary_file(const std::string& path) {
    Registry& r = registry();
    char* copy = new char[path.size() + 1];
    std::memcpy(copy, path.c_str(), path.size() + 1);
    const std::lock_guard lock(r.mutex);
    std::size_t index;
    if (!r.free_slots.empty()) {
        index = r.free_slots.back();
        r.free_slots.pop_back();
    } else {
        index = r.used++;
    }
    slot_of(r, index, true)->store(copy, std::memory_order_release);
    return index;
}

void unregister_temporary_file(std::size_t handle) {
    Registry& r = registry();
    const std::lock_guard lock(r.mutex);
    std::atomic<char*>* slot = slot_of(r, handle, false);
    if (!slot) return;
    // A crash in another thread at this very moment may still read the old path: deleting
    // a file that is being committed or discarded anyway is harmless.
    delete[] slot->exchange(nullptr, std::memory_order_acq_rel);
    r.free_slots.push_back(handle);
}

void delete_temporary_files_now() { delete_registered_files(); }

void delete_temporary_files_on_crash() {
    registry();   // created now, not in the handler
    for (const int signal_number : {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT}) {
        struct sigaction action {};
        action.sa_sigaction = on_crash;
        action.sa_flags = SA_SIGINFO | SA_RESETHAND | SA_NODEFER;
        sigemptyset(&action.sa_mask);
        sigaction(signal_number, &action,
                  &previous_actions[static_cast<std::size_t>(signal_number)]);
    }
}

}  // namespace discreel
