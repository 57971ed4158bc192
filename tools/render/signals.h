// SPDX-License-Identifier: Apache-2.0
// SIGINT and SIGTERM handled as ordinary code: the handler only writes the signal number to
// a pipe (async-signal safe), and a watcher thread reading that pipe runs the reaction
// (cancelling the running pass). Blocking the signals and calling sigwait() is not enough:
// some libraries start threads with an empty signal mask, which would take the default
// action and kill the process. A second signal ends the process at once.
#pragma once

#include <atomic>
#include <functional>
#include <thread>

namespace ppm_render {

class SignalWatcher {
public:
    SignalWatcher();
    ~SignalWatcher();
    // Starts watching; `on_signal` runs on the watcher thread at the first signal.
    void start(std::function<void()> on_signal);
    bool interrupted() const;
    int signal_number() const;

private:
    std::function<void()> on_signal_;
    std::thread thread_;
};

} // namespace ppm_render
