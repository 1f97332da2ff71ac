#pragma once
// SIGINT/SIGTERM ask the run to write a checkpoint and stop at the end of the current step.
namespace eulerfsi {

void install_stop_handlers();
// The signal received (0: none).
int stop_requested();

}  // namespace eulerfsi
