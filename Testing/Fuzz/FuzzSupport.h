// FuzzSupport: what both fuzz targets share: a private scratch folder, file writing, and the
// invariants every LoadVolume result must satisfy (the CLI's promise for bad input).
#ifndef accelvolume_FuzzSupport_h
#define accelvolume_FuzzSupport_h

#include "VolumeIO.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace accelvolume::fuzz
{

// A folder of its own under $TMPDIR (or /tmp), removed at exit.
inline const std::filesystem::path& Folder()
{
  static const std::filesystem::path folder = []
  {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/accelvolume-fuzz-XXXXXX";
    if (!mkdtemp(&pattern[0]))
    {
      std::perror("mkdtemp");
      std::abort();
    }
    std::atexit([] { std::filesystem::remove_all(Folder()); });
    return std::filesystem::path(pattern);
  }();
  return folder;
}

inline void Write(const std::string& name, const std::string& bytes)
{
  std::ofstream stream(Folder() / name, std::ios::binary | std::ios::trunc);
  stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// Loads request and checks the CLI's contract: either a usable one-component volume with one
// value per voxel and positive finite spacing, or no volume and a one-line error. A broken
// contract aborts, which libFuzzer reports as a crash with the input saved.
inline void LoadAndCheck(const cli::VolumeRequest& request)
{
  std::string error;
  vtkSmartPointer<vtkImageData> image = cli::LoadVolume(request, error);
  const char* broken = nullptr;
  if (!image)
  {
    broken = error.empty()                    ? "no volume and no error"
      : error.find('\n') != std::string::npos ? "a multi-line error"
                                              : nullptr;
  }
  else
  {
    vtkDataArray* scalars = image->GetPointData()->GetScalars();
    const double* spacing = image->GetSpacing();
    broken = !error.empty()                                        ? "a volume and an error"
      : !scalars || scalars->GetNumberOfComponents() != 1          ? "no single-component scalars"
      : scalars->GetNumberOfTuples() != image->GetNumberOfPoints() ? "values != voxels"
      : !(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0)      ? "non-positive spacing"
                                                                   : nullptr;
  }
  if (broken)
  {
    std::fprintf(
      stderr, "LoadVolume broke its contract: %s (error: '%s')\n", broken, error.c_str());
    std::abort();
  }
}

} // namespace accelvolume::fuzz

#endif
