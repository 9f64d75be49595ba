// vtkAccelVolumeDepthPeeling: what a mapper does when the renderer peels volumes with its
// translucent geometry (vtkRenderer::UseDepthPeelingForVolumes; private to the module).
//
// vtkDualDepthPeelingPass then calls the mapper in three stages and expects VTK's GPU ray
// caster's shader protocol (ray segments between peeled depth layers, written to two targets).
// Our mappers do not speak it yet: they draw the whole volume once, in the first stage, into
// the back accumulation target (clipped by opaque geometry), so the translucent geometry is
// composited over the volume, and draw nothing in the later stages. Before, the peeling targets
// received garbage (dotted and striped blocks).
#ifndef vtkAccelVolumeDepthPeeling_h
#define vtkAccelVolumeDepthPeeling_h

class vtkAbstractMapper;
class vtkOpenGLRenderWindow;
class vtkVolume;

enum class vtkAccelVolumePeelStage
{
  None,         // not inside vtkDualDepthPeelingPass: render as usual
  OutsideRange, // the first volumetric stage: draw, and clear the second target
  Later         // peeling and alpha-blending stages: draw nothing
};

/** The peeling stage `volume` is rendered in (the pass's stage, read through its uniforms). */
vtkAccelVolumePeelStage vtkAccelVolumeGetPeelStage(
  vtkOpenGLRenderWindow* window, vtkVolume* volume, vtkAbstractMapper* mapper);

#endif
