// Proves that a sanitizer build reports what it must, so that a clean run means something: each
// case commits one deliberate error in a child process, and passes only when the child is
// stopped with the sanitizers' exit code (86, AccelVolumeSanitizerOptions.cxx) and its report
// names the error. Catches builds where the flags, the options or the backend switch are lost.
//   SanitizerSelfTest expect <case>    (what ctest runs: label "sanitizer")
//   SanitizerSelfTest <case>           (the deliberate error itself)
#include "vtkSMPTools.h"

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/wait.h>
#include <thread>

namespace
{
constexpr int SanitizerExitCode = 86;

struct Case
{
  const char* Name;
  const char* Report; // text the sanitizer's report must contain
  void (*Run)();
};

void* volatile Sink = nullptr;
volatile int Index = 8;
volatile int Big = INT_MAX;
volatile double Huge = 1e300;
int Shared = 0; // raced on

void HeapOverflow()
{
  // Volatile: the store must stay, and UBSan's object-size check must not see the size first.
  char* volatile bytes = new char[8];
  static_cast<volatile char*>(bytes)[Index] = 1;
  delete[] bytes;
}

void Leak()
{
  Sink = std::malloc(64);
  Sink = nullptr;
}

void SignedOverflow()
{
  Sink = reinterpret_cast<void*>(static_cast<long>(Big + 1));
}

void FloatCastOverflow()
{
  Sink = reinterpret_cast<void*>(static_cast<long>(static_cast<int>(Huge)));
}

void ThreadRace()
{
  std::thread other([] { ++Shared; });
  ++Shared;
  other.join();
}

// The race inside a vtkSMPTools loop body: only visible if vtkSMPTools runs on a backend TSan
// can follow (STDThread) with at least two threads.
void SMPToolsRace()
{
  vtkSMPTools::For(0, 1 << 16, 1,
    [](vtkIdType begin, vtkIdType end)
    {
      for (vtkIdType i = begin; i < end; ++i)
      {
        ++Shared;
      }
    });
}

const Case Cases[] = {
  { "heap-buffer-overflow", "AddressSanitizer: heap-buffer-overflow", HeapOverflow },
  { "leak", "LeakSanitizer: detected memory leaks", Leak },
  { "signed-integer-overflow", "runtime error: signed integer overflow", SignedOverflow },
  { "float-cast-overflow", "runtime error: 1e+300 is outside the range", FloatCastOverflow },
  { "thread-race", "ThreadSanitizer: data race", ThreadRace },
  { "smptools-race", "ThreadSanitizer: data race", SMPToolsRace },
};

const Case* Find(const char* name)
{
  for (const Case& c : Cases)
  {
    if (std::strcmp(c.Name, name) == 0)
    {
      return &c;
    }
  }
  return nullptr;
}
}

int main(int argc, char* argv[])
{
  const bool expect = argc == 3 && std::strcmp(argv[1], "expect") == 0;
  const Case* c = argc == 2 ? Find(argv[1]) : (expect ? Find(argv[2]) : nullptr);
  if (!c)
  {
    std::fprintf(stderr, "usage: %s [expect] <case>\n", argv[0]);
    return 2;
  }
  if (!expect)
  {
    c->Run();
    std::printf("%s: no sanitizer stopped the program\n", c->Name);
    return 0;
  }
  const std::string command = std::string("'") + argv[0] + "' " + c->Name + " 2>&1";
  FILE* child = popen(command.c_str(), "r");
  if (!child)
  {
    std::perror("popen");
    return 1;
  }
  std::string output;
  char chunk[4096];
  for (std::size_t n; (n = std::fread(chunk, 1, sizeof(chunk), child)) > 0;)
  {
    output.append(chunk, n);
  }
  const int status = pclose(child);
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const bool reported = output.find(c->Report) != std::string::npos;
  std::printf("%s: exit code %d (want %d), report \"%s\" %s\n", c->Name, code, SanitizerExitCode,
    c->Report, reported ? "found" : "missing");
  if (code != SanitizerExitCode || !reported)
  {
    std::printf("child output:\n%s\n", output.c_str());
    return 1;
  }
  return 0;
}
