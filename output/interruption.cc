#include "output/interruption.h"

#include <atomic>
#include <csignal>

namespace aperture::output {
namespace {

std::atomic<int> interruption_signal{0};
static_assert(std::atomic<int>::is_always_lock_free,
              "the signal handler may only touch a lock-free atomic");

// Installed handlers, so that nested InterruptionHandlers install and restore once. Touched by the
// thread that runs the command only.
int handler_depth = 0;
struct sigaction previous_sigint, previous_sigterm;
// Which of the two carry the handler (an ignored one does not); read by the handler.
std::atomic<bool> handling_sigint{false}, handling_sigterm{false};

void StoreInterruptionSignal(int signal_number) {
  int none = 0;  // the first signal wins
  interruption_signal.compare_exchange_strong(none, signal_number);
}

// The handler: records the signal and gives the signals it handles back their default action, so a
// second one (SIGINT or SIGTERM) ends the process at once. Only async-signal-safe calls.
extern "C" void HandleInterruptionSignal(int signal_number) {
  StoreInterruptionSignal(signal_number);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  if (handling_sigint.load()) sigaction(SIGINT, &default_action, nullptr);
  if (handling_sigterm.load()) sigaction(SIGTERM, &default_action, nullptr);
}

}  // namespace

InterruptionHandlers::InterruptionHandlers() : outermost_(handler_depth++ == 0) {
  if (!outermost_) return;
  struct sigaction action {};
  action.sa_handler = &HandleInterruptionSignal;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: reads and writes the signal interrupted resume (the loops poll the flag).
  action.sa_flags = SA_RESTART;
  // A signal the process was started ignoring stays ignored (a command run in the background of
  // a script ignores SIGINT): the convention of interactive programs.
  sigaction(SIGINT, nullptr, &previous_sigint);
  sigaction(SIGTERM, nullptr, &previous_sigterm);
  handling_sigint = previous_sigint.sa_handler != SIG_IGN;
  handling_sigterm = previous_sigterm.sa_handler != SIG_IGN;
  if (handling_sigint) sigaction(SIGINT, &action, nullptr);
  if (handling_sigterm) sigaction(SIGTERM, &action, nullptr);
}

InterruptionHandlers::~InterruptionHandlers() {
  --handler_depth;
  if (!outermost_) return;
  handling_sigint = false;
  handling_sigterm = false;
  sigaction(SIGINT, &previous_sigint, nullptr);
  sigaction(SIGTERM, &previous_sigterm, nullptr);
}

int InterruptionSignal() { return interruption_signal.load(); }

int InterruptedExitCode() {
  const int signal_number = InterruptionSignal();
  return signal_number == 0 ? 0 : 128 + signal_number;
}

void RequestInterruption(int signal_number) { StoreInterruptionSignal(signal_number); }

void ClearInterruption() { interruption_signal.store(0); }

}  // namespace aperture::output
