/**
 * @file   vtkAccelVolumeSliceDraw.h
 * @brief  The slice mapper's proxy geometry drawn into the accumulation target (internal).
 */
#ifndef vtkAccelVolumeSliceDraw_h
#define vtkAccelVolumeSliceDraw_h

#include <string>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkAccelVolumeSliceResources;
struct vtkAccelVolumeSliceFrame;

/**
 * The frame's textures, tables, lights and mask uniforms on a slice, cut-face or compute-slice
 * program (vtkShaderProgram or vtkAccelVolumeComputeProgram, which share the setters).
 */
template <class Program>
void vtkAccelVolumeSliceSetFrameUniforms(Program* program,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame);

/**
 * Every brick in drawing order: its texture acquired (uploaded when streamed), its slices (in
 * early-termination batches for composite), then its cut faces. False with `error` set when a
 * program does not compile or a brick cannot be uploaded.
 */
bool vtkAccelVolumeSliceDrawBricks(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  std::string& error);

#endif
