// Ctrl-C and `kill` (SIGINT, SIGTERM) end a run as a stop condition would: the step under way is finished, a
// checkpoint written and the status set to "interrupted", so `run --resume OUT.h5` continues it bit for bit. A
// second signal kills at once (the default action), for a step that takes too long to wait for.
#pragma once

namespace mc {

// Catches SIGINT and SIGTERM from now on (the command line's `run`; a library caller may leave them alone).
void catch_interrupts();
// The signal that asked the run to end (SIGINT or SIGTERM), or 0. Safe to call every step: one relaxed load.
int interrupt_signal();
// Asks the run to end as a signal would (a caller that is not the command line: a test, a front end).
void request_interrupt(int signal);

}  // namespace mc
