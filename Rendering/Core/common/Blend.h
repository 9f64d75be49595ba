// Blend: how samples along a ray combine into a pixel; one enum for every Core renderer. It
// mirrors vtkVolumeMapper's blend modes (raysum is ADDITIVE_BLEND, average is
// AVERAGE_INTENSITY_BLEND). Not every renderer takes every mode: shear-warp takes Composite,
// Maximum and Minimum; the projection oracle (RenderReference) takes all but Composite, which
// RenderReferenceComposite handles. Slice (SLICE_BLEND: one classified sample where the ray
// meets a plane) and Isosurface (ISOSURFACE_BLEND: the classified, shaded crossings of the
// iso-values, composited) are the ray caster's only.
#ifndef accelvolume_Blend_h
#define accelvolume_Blend_h

namespace accelvolume
{

enum class Blend
{
  Composite,
  Maximum,
  Minimum,
  Additive,
  Average,
  Slice,
  Isosurface
};

} // namespace accelvolume

#endif
