/**
 * @file   vtkAccelVolumeSliceResolve.h
 * @brief  The slice mapper's resolve and scene-depth passes, and the shader-variant helpers
 *         its passes share (internal).
 */
#ifndef vtkAccelVolumeSliceResolve_h
#define vtkAccelVolumeSliceResolve_h

#include <string>

class vtkOpenGLRenderWindow;
class vtkAccelVolumeSliceResources;
struct vtkAccelVolumeSliceFrame;

/** A shader's source with the frame's variant #defines inserted after its #version. */
std::string vtkAccelVolumeSliceShaderVariant(
  const char* source, const vtkAccelVolumeSliceFrame& frame, int slabSamples, bool boundaryFace);
/** The frame's variant #defines alone (a short string: the key of a program variant). */
std::string vtkAccelVolumeSliceShaderPrelude(
  const vtkAccelVolumeSliceFrame& frame, int slabSamples, bool boundaryFace);
/** A slice shader's source with the shared sampling (and multi-component) parts inserted. */
std::string vtkAccelVolumeSliceInsertSampling(const char* source);
/** A fragment source with a prelude from vtkAccelVolumeSliceShaderPrelude inserted. */
std::string vtkAccelVolumeSliceAssembleShader(const char* source, const std::string& prelude);
/** An accumulation target smaller than the viewport (image sample distance above 1). */
bool vtkAccelVolumeSliceReducedTarget(const vtkAccelVolumeSliceFrame& frame);
/** The average of 3-4 independent components needs 8 channels: a second target. */
bool vtkAccelVolumeSliceSecondAccumulation(const vtkAccelVolumeSliceFrame& frame);

/**
 * Colours the accumulated values as VTK's GPU ray caster does for the blend mode and blends
 * them (premultiplied) over what is bound, the viewport at `lowerLeft`. False when the shader
 * did not compile.
 */
bool vtkAccelVolumeSliceResolve(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame,
  const int lowerLeft[2]);
/** RenderToImage: the resolve into the image target (cleared to transparent), read back. */
bool vtkAccelVolumeSliceResolveToImage(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame);
/**
 * The scene's depth at the target's size: copied, or (reduced target) copied at the viewport's
 * size and sampled down by a pass that writes the target's depth buffer.
 */
bool vtkAccelVolumeSliceCopySceneDepth(vtkOpenGLRenderWindow* window,
  vtkAccelVolumeSliceResources& resources, const vtkAccelVolumeSliceFrame& frame, int depthFormat);

#endif
