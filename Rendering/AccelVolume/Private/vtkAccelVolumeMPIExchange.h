// vtkAccelVolumeMPIExchange: the shear-warp mapper's (and the accelvolume CLI's) exchanges between
// the ranks of a vtkMultiProcessController, each bounded in time. Not installed, not wrapped.
//
// Only point-to-point messages with rank 0 at the centre (no collectives), so every wait knows
// the one rank it waits for and can name it. Every blocking Send / Receive runs under a watchdog
// thread: when it has not returned by its deadline, the watchdog calls the process-wide abort
// function with a one-line message naming that rank (default: the message on stderr, then the
// process exits with status 1, which makes mpiexec end the other ranks). A rank blocked in MPI
// cannot be unblocked, so ending the job is the only way out; an MPI application sets an abort
// function that calls MPI_Abort.
//
// Deadlines: rank 0 waits at most Timeout for all other ranks in one exchange; the other ranks
// wait up to twice that for rank 0, which may itself be waiting for a hung rank: so a hung rank
// is reported by rank 0, by name. Timeout 0 waits forever.
//
// The watchdog thread starts on the first bounded wait (never in a single process) and costs one
// mutex and one condition-variable notify per wait. One thread at a time may use the exchanges
// of a process (the rendering thread): GetPendingWait is process-wide.
#ifndef vtkAccelVolumeMPIExchange_h
#define vtkAccelVolumeMPIExchange_h

#include "vtkRenderingAccelVolumeModule.h" // For export macro
#include "vtkType.h"                       // For vtkIdType

#include <chrono>
#include <memory>
#include <string>

class vtkMultiProcessController;

class VTKRENDERINGACCELVOLUME_EXPORT vtkAccelVolumeMPIExchange
{
public:
  using Clock = std::chrono::steady_clock;
  // Ends the job after a wait ran out; called on the watchdog thread with a one-line message.
  using AbortFunction = void (*)(const char* message);

  vtkAccelVolumeMPIExchange();
  ~vtkAccelVolumeMPIExchange();
  vtkAccelVolumeMPIExchange(const vtkAccelVolumeMPIExchange&) = delete;
  vtkAccelVolumeMPIExchange& operator=(const vtkAccelVolumeMPIExchange&) = delete;

  // Not owned. Null or one process: every exchange is local (no waits).
  void SetController(vtkMultiProcessController* controller) { this->Controller = controller; }
  vtkMultiProcessController* GetController() const { return this->Controller; }
  int GetRank() const;
  int GetNumberOfRanks() const;

  // Seconds (>= 0; 0 = wait forever), default 60.
  void SetTimeout(double seconds) { this->Timeout = seconds > 0 ? seconds : 0; }
  double GetTimeout() const { return this->Timeout; }

  // The lowest rank whose code was non-zero (-1: none), its code and message.
  struct Failure
  {
    int Rank = -1;
    int Code = 0;
    std::string Message;
  };
  // Every rank passes its code (0 = fine) and message; every rank gets the same Failure. `what`
  // names the exchange in timeout messages ("frame status").
  Failure AgreeOnFailure(int code, const std::string& message, const char* what);

  // Element-wise sums over the ranks, added in rank order on rank 0 and sent back to every rank,
  // so every rank holds the same bits.
  void Sum(const double* local, double* total, vtkIdType count, const char* what);
  void Sum(const long long* local, long long* total, vtkIdType count, const char* what);

  // Rank r owns data[offsets[r], offsets[r + 1]) (offsets has ranks + 1 entries): rank 0
  // receives every other rank's range into its data, the others send theirs.
  void GatherToRoot(float* data, const vtkIdType* offsets, const char* what);

  // Bounds one blocking call made outside this class (a collective, MPI_Finalize): if the scope
  // is not left within `seconds` (0: never), the abort function gets `message`. `waitingFor`
  // describes the wait for GetPendingWait().
  class Guard
  {
  public:
    Guard(vtkAccelVolumeMPIExchange& exchange, double seconds, const std::string& message,
      const std::string& waitingFor);
    ~Guard();
    Guard(const Guard&) = delete;
    Guard& operator=(const Guard&) = delete;

  private:
    vtkAccelVolumeMPIExchange& Exchange;
  };

  // Process-wide; null restores the default (stderr, then exit status 1).
  static void SetAbortFunction(AbortFunction function);
  // What this process is blocked on right now ("band rows from rank 1"; "" when not waiting).
  // Async-signal-safe: a SIGTERM handler may print it (mpiexec sends SIGTERM to the surviving
  // ranks when one dies).
  static const char* GetPendingWait();

private:
  class Watchdog;
  // A deadline and the bound it stands for (reported in the timeout message).
  struct Bound
  {
    Clock::time_point At;
    double Seconds;
  };
  void Arm(const Bound& bound, const std::string& message, const std::string& waitingFor);
  void Disarm();
  Bound Within(double factor) const; // factor x Timeout from now
  template <typename T>
  void Receive(T* data, vtkIdType length, int peer, int tag, const Bound& bound, const char* what);
  template <typename T>
  void Send(
    const T* data, vtkIdType length, int peer, int tag, const Bound& bound, const char* what);
  template <typename T>
  void SumImpl(const T* local, T* total, vtkIdType count, const char* what);

  vtkMultiProcessController* Controller = nullptr;
  double Timeout = 60;
  std::unique_ptr<Watchdog> Dog;
};

#endif
