#include "CompositeCounts.h"
#include "BenchmarkHarness.h"

#include <vtkCamera.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkRenderer.h>
#include <vtk_glew.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace accelvolume::benchmark
{

FrameCounts CountFrame(vtkRenderWindow* window)
{
  FrameCounts counts;
  window->MakeCurrent();
  const bool statistics = GLEW_ARB_pipeline_statistics_query != 0;
  GLuint queries[2] = { 0, 0 };
  glGenQueries(2, queries);
  if (statistics)
  {
    glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, queries[0]);
  }
  glBeginQuery(GL_SAMPLES_PASSED, queries[1]);
  window->Render();
  window->MakeCurrent();
  glEndQuery(GL_SAMPLES_PASSED);
  if (statistics)
  {
    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
  }
  GLuint64 value = 0;
  if (statistics)
  {
    glGetQueryObjectui64v(queries[0], GL_QUERY_RESULT, &value);
    counts.FragmentsShaded = static_cast<long long>(value);
  }
  glGetQueryObjectui64v(queries[1], GL_QUERY_RESULT, &value);
  counts.SamplesPassed = static_cast<long long>(value);
  glDeleteQueries(2, queries);
  return counts;
}

namespace
{

// The chord of the ray p + t d (t in [0, 1]) inside the box, in world units.
double Chord(const double p[3], const double d[3], const double bounds[6])
{
  double t0 = 0.0;
  double t1 = 1.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double lo = bounds[2 * axis];
    const double hi = bounds[2 * axis + 1];
    if (d[axis] == 0.0)
    {
      if (p[axis] < lo || p[axis] > hi)
      {
        return 0.0;
      }
      continue;
    }
    double a = (lo - p[axis]) / d[axis];
    double b = (hi - p[axis]) / d[axis];
    if (a > b)
    {
      std::swap(a, b);
    }
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  if (t1 <= t0)
  {
    return 0.0;
  }
  return (t1 - t0) * std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

void Unproject(vtkMatrix4x4* inverse, double x, double y, double z, double out[3])
{
  const double in[4] = { x, y, z, 1.0 };
  double world[4];
  inverse->MultiplyPoint(in, world);
  for (int i = 0; i < 3; ++i)
  {
    out[i] = world[i] / world[3];
  }
}

} // namespace

RaySamples CountRaySamples(
  vtkRenderer* renderer, const double bounds[6], int size, double sampleDistance)
{
  vtkNew<vtkMatrix4x4> inverse;
  inverse->DeepCopy(
    renderer->GetActiveCamera()->GetCompositeProjectionTransformMatrix(1.0, -1.0, 1.0));
  inverse->Invert();
  RaySamples work;
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const double nx = 2.0 * (x + 0.5) / size - 1.0;
      const double ny = 2.0 * (y + 0.5) / size - 1.0;
      double nearPoint[3], farPoint[3], direction[3];
      Unproject(inverse, nx, ny, -1.0, nearPoint);
      Unproject(inverse, nx, ny, 1.0, farPoint);
      for (int i = 0; i < 3; ++i)
      {
        direction[i] = farPoint[i] - nearPoint[i];
      }
      const double chord = Chord(nearPoint, direction, bounds);
      if (chord > 0.0)
      {
        ++work.Pixels;
        work.Samples += 1 + static_cast<long long>(chord / sampleDistance);
      }
    }
  }
  return work;
}

std::string FindCli()
{
  if (const char* cli = std::getenv("ACCELVOLUME_CLI"))
  {
    return cli;
  }
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec)
  {
    return std::string();
  }
  const fs::path cli = self.parent_path() / "accelvolume";
  return fs::exists(cli, ec) ? cli.string() : std::string();
}

double NoOpMsPerFrame(const std::string& cli, const std::vector<std::string>& args, int frames)
{
  const fs::path stats =
    fs::temp_directory_path() / ("accelvolume-noop-" + std::to_string(::getpid()) + ".json");
  std::ostringstream command;
  command << "GALLIUM_NOOP=1 ACCELVOLUME_GL=egl " << ShellQuote(cli) << " render";
  for (const std::string& arg : args)
  {
    command << ' ' << ShellQuote(arg);
  }
  command << " --gl egl --frames " << frames << " --stats " << ShellQuote(stats.string())
          << " >/dev/null 2>&1";
  double ms = -1.0;
  if (std::system(command.str().c_str()) == 0)
  {
    std::ifstream in(stats);
    const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
    if (!json.is_discarded() && json.contains("ms_per_frame") &&
      json["ms_per_frame"]["median"].is_number())
    {
      ms = json["ms_per_frame"]["median"].get<double>();
    }
  }
  std::error_code ec;
  fs::remove(stats, ec);
  return ms;
}

} // namespace accelvolume::benchmark
