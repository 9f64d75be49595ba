// MapperSetup: the volume mapper --mapper names, configured from the options, and what it
// reports after the frames (its own render time and acceleration counters) for --stats.
#ifndef accelvolume_cli_MapperSetup_h
#define accelvolume_cli_MapperSetup_h

#include "Options.h"
#include "Render.h"

#include <vtkSmartPointer.h>
#include <vtkVolumeMapper.h>

class vtkAccelVolumeRayCastMapper;
class vtkAccelVolumeShearWarpMapper;
class vtkAccelVolumeSliceMapper;
class vtkAccelVolumeSmartMapper;
class vtkCamera;
class vtkAccelVolumeMPIExchange;
class vtkImageData;

namespace accelvolume::cli
{

// The mapper and typed views of it (null where it is not of that kind); for --mapper smart the
// views are the smart mapper's owned mappers, each configured as its own --mapper would be.
struct MapperSet
{
  vtkSmartPointer<vtkVolumeMapper> Mapper;
  vtkAccelVolumeSliceMapper* Slice = nullptr;
  vtkAccelVolumeRayCastMapper* RayCast = nullptr;
  vtkAccelVolumeShearWarpMapper* ShearWarp = nullptr;
  vtkAccelVolumeSmartMapper* Smart = nullptr;
};

// Creates and configures the mapper (blend mode, input and cropping are set by the caller).
// result.sampleDistance / sampleDistanceSource must already hold the requested distance. mpi
// (--mpi, else null): the shear-warp mapper renders on its controller's ranks.
MapperSet CreateMapper(
  const Options& options, RenderResult& result, vtkAccelVolumeMPIExchange* mpi);

// After the warm-up frame: what that frame built (ray caster prepare, shear-warp encoding).
void ReadFirstFrame(const MapperSet& set, RenderResult& result);

// After the last frame: the mapper's own render time, and for AccelVolume's mappers their
// settings and counters (for the smart mapper: its choice and the chosen mapper's counters).
// Collective under MPI (every rank calls it; bounded like the mapper's exchanges).
void ReadMapperResults(const MapperSet& set, vtkImageData* image, vtkCamera* camera,
  vtkAccelVolumeMPIExchange* mpi, RenderResult& result);

} // namespace accelvolume::cli

#endif
