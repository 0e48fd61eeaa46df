#include "studies/interrupt.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace mc {

namespace {

std::atomic<int> asked{0};

// Only what is async-signal-safe: an atomic store, write(2), signal(2).
extern "C" void on_interrupt(int sig) {
  asked.store(sig, std::memory_order_relaxed);
  static const char note[] =
      "\ninterrupt: finishing the step, then a checkpoint and `run --resume` can continue it (again to kill now)\n";
  [[maybe_unused]] const auto n = write(STDERR_FILENO, note, sizeof note - 1);
  std::signal(sig, SIG_DFL);
}

}  // namespace

void catch_interrupts() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

int interrupt_signal() { return asked.load(std::memory_order_relaxed); }

void request_interrupt(int signal) { asked.store(signal, std::memory_order_relaxed); }

}  // namespace mc
