// SPDX-License-Identifier: Apache-2.0
#include "signals.h"

#include <csignal>
#include <unistd.h>

namespace ppm_render {

namespace {

int pipe_fds[2] = {-1, -1};
volatile std::sig_atomic_t received_signal = 0;

extern "C" void on_signal(int signal) {
    if (received_signal != 0) {
        static const char message[] = "\nppm-render: second interrupt, exiting without saving\n";
        (void)!write(STDERR_FILENO, message, sizeof message - 1);
        _exit(128 + signal);
    }
    received_signal = signal;
    const unsigned char byte = static_cast<unsigned char>(signal);
    (void)!write(pipe_fds[1], &byte, 1);
}

} // namespace

SignalWatcher::SignalWatcher() {
    if (pipe(pipe_fds) != 0) return; // no pipe: signals keep their default action
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

SignalWatcher::~SignalWatcher() {
    if (thread_.joinable()) {
        const unsigned char stop = 0;
        (void)!write(pipe_fds[1], &stop, 1);
        thread_.join();
    }
}

void SignalWatcher::start(std::function<void()> on_signal_callback) {
    if (pipe_fds[0] < 0) return;
    on_signal_ = std::move(on_signal_callback);
    thread_ = std::thread([this] {
        for (;;) {
            unsigned char byte = 0;
            const ssize_t n = read(pipe_fds[0], &byte, 1);
            if (n < 0) continue; // EINTR
            if (n == 0 || byte == 0) return;
            if (on_signal_) on_signal_();
        }
    });
}

bool SignalWatcher::interrupted() const { return received_signal != 0; }
int SignalWatcher::signal_number() const { return received_signal; }

} // namespace ppm_render
