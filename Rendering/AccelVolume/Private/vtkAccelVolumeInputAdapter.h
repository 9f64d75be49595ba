// vtkAccelVolumeInputAdapter: turns what VTK's volume mappers accept into what the AccelVolume
// engines take (one-component point scalars of a vtkImageData whose active scalars are the
// rendered array). Not installed.
//
// - point scalars of a vtkImageData in a type the engines read: passed through untouched;
// - another point array than the active scalars (SelectScalarArray): an image sharing the
//   structure, with that array as its active scalars (so the octree classifies what is drawn);
// - cell scalars: an image with one point per cell, at the cell centres, like the texture
//   VTK's GPU mapper samples (the picture ends half a cell inside the point bounds);
// - unsigned int and 64-bit integers: a float copy (as VTK's GPU mapper samples them);
// - a vtkRectilinearGrid with evenly spaced coordinates: the equivalent image; with uneven
//   (increasing) coordinates and point scalars: resampled trilinearly onto a regular grid as
//   fine as its smallest step (at most 4x its points per axis and 2^26 samples).
// The adapted image is rebuilt only when its source changes, so the mappers' caches (keyed on
// MTimes) stay valid between frames.
#ifndef vtkAccelVolumeInputAdapter_h
#define vtkAccelVolumeInputAdapter_h

#include "vtkNew.h"          // For vtkNew
#include "vtkSmartPointer.h" // For vtkSmartPointer

#include <string> // For std::string
#include <vector> // For std::vector

#include <string>

class vtkDataArray;
class vtkDataSet;
class vtkImageData;
class vtkVolumeMapper;

class vtkAccelVolumeInputAdapter
{
public:
  vtkAccelVolumeInputAdapter();
  ~vtkAccelVolumeInputAdapter();

  /**
   * Updates the mapper's input and returns the image and scalars to render (the mapper's
   * scalar mode and array). False with a user-facing message when the input cannot be
   * rendered; `image` may then still point to the input (or be null).
   */
  bool Fetch(
    vtkVolumeMapper* mapper, vtkImageData*& image, vtkDataArray*& scalars, std::string& error);

  /** Same, for a data set the caller already holds (null: no input). */
  bool Adapt(vtkVolumeMapper* mapper, vtkDataSet* input, vtkImageData*& image,
    vtkDataArray*& scalars, std::string& error);

  /** Most scalar components the mapper renders (default 1; the slice mapper takes 4). */
  void SetMaximumComponents(int components) { this->MaximumComponents = components; }

private:
  int MaximumComponents = 1;
  vtkAccelVolumeInputAdapter(const vtkAccelVolumeInputAdapter&) = delete;
  void operator=(const vtkAccelVolumeInputAdapter&) = delete;

  // The image geometry of `input` (an image, or an evenly spaced rectilinear grid); false with
  // a message otherwise.
  bool Structure(vtkDataSet* input, std::string& error);

  // An unevenly spaced rectilinear grid is resampled (trilinear, as VTK's GPU mapper samples
  // it through its coordinate tables) onto a regular grid as fine as its smallest step: per
  // axis, each regular sample's source interval and weight.
  struct AxisMap
  {
    std::vector<vtkIdType> Index;
    std::vector<double> Weight;
  };
  bool PlanResampling(vtkDataArray* const axes[3], double origin[3], double spacing[3], int dims[3],
    std::string& error);
  vtkSmartPointer<vtkDataArray> Resample(vtkDataArray* scalars) const;
  bool Resampled = false;
  AxisMap Axes[3];
  int SourceDimensions[3] = { 0, 0, 0 };

  vtkNew<vtkImageData> Adapted;
  vtkSmartPointer<vtkDataArray> Converted;
  // What Adapted reflects.
  vtkDataSet* Source = nullptr;
  vtkDataArray* SourceArray = nullptr;
  unsigned long SourceTime = 0;
  unsigned long ArrayTime = 0;
  int CellFlag = -1;
};

#endif
