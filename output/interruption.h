#pragma once
// Interruption: SIGINT (Ctrl-C) and SIGTERM as a request to stop at the next frame or trial
// boundary, so a long `run`, `sim`, `render` or `bench` finishes its outputs instead of dying
// with files cut mid-row.
//
//   {
//     output::InterruptionHandlers handlers;   // SIGINT/SIGTERM now set the flag
//     for (...each frame...) {
//       if (output::InterruptionRequested()) break;   // at a frame boundary
//       ...
//     }
//   }                                          // previous handlers back; the flag stays set
//   ...close the files as usual...             // RunAndWriteSummary: "status": "interrupted"
//
// The handler only stores the signal number in a lock-free atomic and gives SIGINT and SIGTERM
// back their default action (both async-signal-safe): a second signal ends the process at once.
// The flag stays set once raised (a process stops once); main() exits with InterruptedExitCode():
// 128 + the signal (130 for SIGINT, 143 for SIGTERM), as shells do.
namespace aperture::output {

// While alive, SIGINT and SIGTERM set the interruption flag instead of ending the process (the
// first one; see above), unless the process ignores that signal (SIG_IGN, e.g. SIGINT in a
// background job of a script): then it stays ignored. Restores the handlers it replaced on
// destruction. Nest freely (the outermost one installs).
class InterruptionHandlers {
 public:
  InterruptionHandlers();
  ~InterruptionHandlers();
  InterruptionHandlers(const InterruptionHandlers&) = delete;
  InterruptionHandlers& operator=(const InterruptionHandlers&) = delete;

 private:
  bool outermost_;
};

// The signal that asked to stop (SIGINT or SIGTERM), 0 when none.
int InterruptionSignal();
inline bool InterruptionRequested() { return InterruptionSignal() != 0; }
// 128 + InterruptionSignal() (130 for SIGINT, 143 for SIGTERM); 0 when none.
int InterruptedExitCode();

// What the handler does, for tests of the code that checks the flag: RequestInterruption(SIGINT)
// raises it as Ctrl-C would, ClearInterruption() lowers it.
void RequestInterruption(int signal_number);
void ClearInterruption();

}  // namespace aperture::output
