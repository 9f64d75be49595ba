// Hardware-independent work per frame and the no-op driver's CPU cost, for the composite
// benchmark: what a frame costs whatever GPU runs it.
#ifndef AccelVolumeCompositeCounts_h
#define AccelVolumeCompositeCounts_h

#include <string>
#include <vector>

class vtkRenderWindow;
class vtkRenderer;

namespace accelvolume::benchmark
{

// GL query results over one Render(): -1 where the query is not available.
struct FrameCounts
{
  long long FragmentsShaded = -1; // GL_FRAGMENT_SHADER_INVOCATIONS_ARB (pipeline statistics)
  long long SamplesPassed = -1;   // GL_SAMPLES_PASSED: fragments that reached blending
};

// Renders `window` once between the two queries.
FrameCounts CountFrame(vtkRenderWindow* window);

// A ray caster's work at the renderer's camera: pixels whose ray crosses `bounds` and, summed over
// them, the samples at `sampleDistance` along the crossed chord (no early termination, no
// skipping: VTK 9.1's GPU ray caster has neither empty-space skipping nor a data-dependent bound).
struct RaySamples
{
  long long Pixels = 0;
  long long Samples = 0;
};
RaySamples CountRaySamples(
  vtkRenderer* renderer, const double bounds[6], int size, double sampleDistance);

// The accelvolume CLI beside this program (or $ACCELVOLUME_CLI); empty when not found.
std::string FindCli();

// Median ms per frame of `accelvolume render ARGS --frames N` on EGL under Mesa's no-op driver
// (GALLIUM_NOOP=1: every draw dropped, so application + driver CPU work remains); -1 when the
// child fails.
double NoOpMsPerFrame(const std::string& cli, const std::vector<std::string>& args, int frames);

} // namespace accelvolume::benchmark

#endif
