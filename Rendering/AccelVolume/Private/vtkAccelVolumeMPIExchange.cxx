// Bounded point-to-point exchanges between MPI ranks (see the header).
#include "vtkAccelVolumeMPIExchange.h"

#include "vtkMultiProcessController.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <sstream>
#include <thread>
#include <type_traits>
#include <vector>

namespace
{
// Tags of the exchanges (large, so they do not meet an application's own tags).
constexpr int RowsTag = 78231;
constexpr int StatusTag = 78232;
constexpr int VerdictTag = 78233;
constexpr int SumTag = 78234;
constexpr int SumResultTag = 78235;

// One status or verdict message: fixed size, so it is one Send / Receive.
struct StatusWire
{
  std::int32_t Rank;
  std::int32_t Code;
  char Text[504];
};
static_assert(std::is_trivially_copyable<StatusWire>::value, "sent as bytes");

std::atomic<vtkAccelVolumeMPIExchange::AbortFunction> TheAbortFunction{ nullptr };

// GetPendingWait(): two buffers, the one not published is written, then published with one
// atomic store, so a signal handler always reads a complete string.
char PendingBuffers[2][160];
std::atomic<const char*> Pending{ "" };
int NextPendingBuffer = 0;

void Publish(const std::string& text)
{
  char* buffer = PendingBuffers[NextPendingBuffer];
  NextPendingBuffer = 1 - NextPendingBuffer;
  const std::size_t length = std::min(text.size(), sizeof(PendingBuffers[0]) - 1);
  std::memcpy(buffer, text.data(), length);
  buffer[length] = '\0';
  Pending.store(buffer);
}

[[noreturn]] void EndJob(const std::string& message)
{
  const vtkAccelVolumeMPIExchange::AbortFunction function = TheAbortFunction.load();
  if (function)
  {
    function(message.c_str());
  }
  else
  {
    std::fprintf(stderr, "vtkAccelVolumeMPIExchange: %s; ending this process\n", message.c_str());
    std::fflush(stderr);
  }
  // The rendering thread is blocked in MPI and cannot be unblocked: end the process (mpiexec
  // then ends the other ranks).
  std::_Exit(1);
}

std::string Seconds(double seconds)
{
  std::ostringstream text;
  text << seconds;
  return text.str();
}
}

class vtkAccelVolumeMPIExchange::Watchdog
{
public:
  ~Watchdog()
  {
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Stop = true;
    }
    this->Wake.notify_one();
    if (this->Thread.joinable())
    {
      this->Thread.join();
    }
  }
  void Arm(Clock::time_point deadline, const std::string& message)
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (!this->Thread.joinable())
    {
      this->Thread = std::thread(&Watchdog::Run, this);
    }
    this->Deadline = deadline;
    this->Message = message;
    this->Armed = true;
    this->Wake.notify_one();
  }
  void Disarm()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Armed = false;
  }

private:
  void Run()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    while (!this->Stop)
    {
      if (!this->Armed)
      {
        this->Wake.wait(lock);
      }
      else if (Clock::now() < this->Deadline)
      {
        this->Wake.wait_until(lock, this->Deadline); // re-checked: re-armed, disarmed or due
      }
      else
      {
        const std::string message = this->Message;
        lock.unlock();
        EndJob(message);
      }
    }
  }

  std::mutex Mutex;
  std::condition_variable Wake;
  std::thread Thread;
  bool Stop = false;
  bool Armed = false;
  Clock::time_point Deadline;
  std::string Message;
};

vtkAccelVolumeMPIExchange::vtkAccelVolumeMPIExchange()
  : Dog(new Watchdog)
{
}

vtkAccelVolumeMPIExchange::~vtkAccelVolumeMPIExchange() = default;

int vtkAccelVolumeMPIExchange::GetRank() const
{
  return this->Controller ? this->Controller->GetLocalProcessId() : 0;
}

int vtkAccelVolumeMPIExchange::GetNumberOfRanks() const
{
  return this->Controller ? std::max(1, this->Controller->GetNumberOfProcesses()) : 1;
}

void vtkAccelVolumeMPIExchange::SetAbortFunction(AbortFunction function)
{
  TheAbortFunction.store(function);
}

const char* vtkAccelVolumeMPIExchange::GetPendingWait()
{
  return Pending.load();
}

vtkAccelVolumeMPIExchange::Bound vtkAccelVolumeMPIExchange::Within(double factor) const
{
  const double seconds = factor * this->Timeout;
  return { Clock::now() +
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds)),
    seconds };
}

void vtkAccelVolumeMPIExchange::Arm(
  const Bound& bound, const std::string& message, const std::string& waitingFor)
{
  Publish(waitingFor);
  if (bound.Seconds > 0)
  {
    this->Dog->Arm(bound.At, message);
  }
}

void vtkAccelVolumeMPIExchange::Disarm()
{
  this->Dog->Disarm();
  Pending.store("");
}

template <typename T>
void vtkAccelVolumeMPIExchange::Receive(
  T* data, vtkIdType length, int peer, int tag, const Bound& bound, const char* what)
{
  const int rank = this->GetRank();
  const std::string peerName = "rank " + std::to_string(peer);
  this->Arm(bound,
    peerName + " sent no " + what + " to rank " + std::to_string(rank) + " within " +
      Seconds(bound.Seconds) + " s (the MPI communication timeout): it hung or died" +
      (peer == 0 ? ", or waits for a rank that did" : ""),
    std::string(what) + " from " + peerName);
  const int received = this->Controller->Receive(data, length, peer, tag);
  this->Disarm();
  if (!received)
  {
    EndJob("rank " + std::to_string(rank) + " could not receive the " + what + " of " + peerName +
      " (the controller reported an error)");
  }
}

template <typename T>
void vtkAccelVolumeMPIExchange::Send(
  const T* data, vtkIdType length, int peer, int tag, const Bound& bound, const char* what)
{
  const int rank = this->GetRank();
  const std::string peerName = "rank " + std::to_string(peer);
  // Small messages leave at once; large ones wait until the peer receives them.
  this->Arm(bound,
    peerName + " took no " + what + " from rank " + std::to_string(rank) + " within " +
      Seconds(bound.Seconds) + " s (the MPI communication timeout): it hung or died" +
      (peer == 0 ? ", or waits for a rank that did" : ""),
    peerName + " to take " + what);
  const int sent = this->Controller->Send(data, length, peer, tag);
  this->Disarm();
  if (!sent)
  {
    EndJob("rank " + std::to_string(rank) + " could not send its " + what + " to " + peerName +
      " (the controller reported an error)");
  }
}

vtkAccelVolumeMPIExchange::Failure vtkAccelVolumeMPIExchange::AgreeOnFailure(
  int code, const std::string& message, const char* what)
{
  const int ranks = this->GetNumberOfRanks();
  const int rank = this->GetRank();
  Failure failure;
  if (code != 0)
  {
    failure.Rank = rank;
    failure.Code = code;
    failure.Message = message;
  }
  if (ranks < 2)
  {
    return failure;
  }
  const auto toWire = [](const Failure& from, StatusWire& wire)
  {
    std::memset(&wire, 0, sizeof(wire));
    wire.Rank = from.Rank;
    wire.Code = from.Code;
    std::strncpy(wire.Text, from.Message.c_str(), sizeof(wire.Text) - 1);
  };
  StatusWire wire;
  const vtkIdType bytes = static_cast<vtkIdType>(sizeof(wire));
  if (rank == 0)
  {
    // Every rank's status, in rank order; the lowest failing rank wins.
    const Bound deadline = this->Within(1);
    for (int other = 1; other < ranks; ++other)
    {
      this->Receive(reinterpret_cast<char*>(&wire), bytes, other, StatusTag, deadline, what);
      wire.Text[sizeof(wire.Text) - 1] = '\0';
      if (failure.Rank < 0 && wire.Code != 0)
      {
        failure.Rank = other;
        failure.Code = wire.Code;
        failure.Message = wire.Text;
      }
    }
    toWire(failure, wire);
    const std::string verdict = std::string(what) + " verdict";
    for (int other = 1; other < ranks; ++other)
    {
      this->Send(reinterpret_cast<const char*>(&wire), bytes, other, VerdictTag, this->Within(1),
        verdict.c_str());
    }
    return failure;
  }
  toWire(failure, wire);
  wire.Rank = rank;
  this->Send(reinterpret_cast<const char*>(&wire), bytes, 0, StatusTag, this->Within(2), what);
  const std::string verdict = std::string(what) + " verdict";
  this->Receive(
    reinterpret_cast<char*>(&wire), bytes, 0, VerdictTag, this->Within(2), verdict.c_str());
  wire.Text[sizeof(wire.Text) - 1] = '\0';
  failure.Rank = wire.Rank;
  failure.Code = wire.Code;
  failure.Message = wire.Text;
  return failure;
}

template <typename T>
void vtkAccelVolumeMPIExchange::SumImpl(const T* local, T* total, vtkIdType count, const char* what)
{
  std::copy(local, local + count, total);
  const int ranks = this->GetNumberOfRanks();
  if (ranks < 2 || count <= 0)
  {
    return;
  }
  const std::string result = std::string(what) + " sums";
  if (this->GetRank() == 0)
  {
    std::vector<T> other(static_cast<std::size_t>(count));
    const Bound deadline = this->Within(1);
    for (int from = 1; from < ranks; ++from)
    {
      this->Receive(other.data(), count, from, SumTag, deadline, what);
      for (vtkIdType i = 0; i < count; ++i)
      {
        total[i] += other[i];
      }
    }
    for (int to = 1; to < ranks; ++to)
    {
      this->Send(total, count, to, SumResultTag, this->Within(1), result.c_str());
    }
    return;
  }
  this->Send(local, count, 0, SumTag, this->Within(2), what);
  this->Receive(total, count, 0, SumResultTag, this->Within(2), result.c_str());
}

void vtkAccelVolumeMPIExchange::Sum(
  const double* local, double* total, vtkIdType count, const char* what)
{
  this->SumImpl(local, total, count, what);
}

void vtkAccelVolumeMPIExchange::Sum(
  const long long* local, long long* total, vtkIdType count, const char* what)
{
  this->SumImpl(local, total, count, what);
}

void vtkAccelVolumeMPIExchange::GatherToRoot(
  float* data, const vtkIdType* offsets, const char* what)
{
  const int ranks = this->GetNumberOfRanks();
  const int rank = this->GetRank();
  if (ranks < 2)
  {
    return;
  }
  if (rank == 0)
  {
    const Bound deadline = this->Within(1);
    for (int from = 1; from < ranks; ++from)
    {
      if (offsets[from + 1] > offsets[from])
      {
        this->Receive(
          data + offsets[from], offsets[from + 1] - offsets[from], from, RowsTag, deadline, what);
      }
    }
  }
  else if (offsets[rank + 1] > offsets[rank])
  {
    this->Send(
      data + offsets[rank], offsets[rank + 1] - offsets[rank], 0, RowsTag, this->Within(2), what);
  }
}

vtkAccelVolumeMPIExchange::Guard::Guard(vtkAccelVolumeMPIExchange& exchange, double seconds,
  const std::string& message, const std::string& waitingFor)
  : Exchange(exchange)
{
  const double bounded = seconds > 0 ? seconds : 0;
  exchange.Arm(
    { Clock::now() +
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(bounded)),
      bounded },
    message, waitingFor);
}

vtkAccelVolumeMPIExchange::Guard::~Guard()
{
  this->Exchange.Disarm();
}
