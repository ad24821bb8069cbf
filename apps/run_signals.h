#pragma once
// SIGINT/SIGTERM during `rtsph run`: the handlers only record the signal; the run loop polls
// stop_signal() after each step, then checkpoints, prints the summary and exits 128 + signal.
namespace rtsph::app {

/// Installs the recording handlers for SIGINT and SIGTERM (idempotent).
void install_stop_handlers();
/// Puts the default actions back (a second Ctrl-C then kills the process at once).
void restore_default_stop_handlers();
/// The first SIGINT/SIGTERM received since install_stop_handlers(), or 0.
int stop_signal();

}  // namespace rtsph::app
