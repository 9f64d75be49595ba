// Stats: the --stats JSON document and the one-line summary of a render.
#ifndef accelvolume_cli_Stats_h
#define accelvolume_cli_Stats_h

#include "Options.h"
#include "Render.h"

#include <vtkImageData.h>

#include <ostream>
#include <string>

namespace accelvolume::cli
{

// `"text"` with JSON escapes (quotes, backslashes, control characters).
// Writes one JSON object (see the keys in the code; README of the CLI in --help).
void WriteStats(std::ostream& stream, const Options& options, vtkImageData* image,
  const RenderResult& result, int warnings);

// "slice mip 512x512 vessels 128x128x128 float32: 12.3 ms/frame (median of 1), ..."
std::string Summary(const Options& options, vtkImageData* image, const RenderResult& result);

} // namespace accelvolume::cli

#endif
