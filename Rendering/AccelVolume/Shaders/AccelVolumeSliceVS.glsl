//VTK::System::Dec
// Proxy slice / boundary face vertex stage: polygons arrive in volume index coordinates, each
// vertex with the eye depth of its slice plane minus the frame's reference depth (unused by cut
// faces).
#extension GL_ARB_gpu_shader5 : enable
#ifdef GL_ARB_gpu_shader5
#define ACCELVOLUME_PRECISE precise // the same bits in every program this stage is linked into
#else
#define ACCELVOLUME_PRECISE
#endif
in vec3 vertexIndex;
in float vertexDepth;

uniform mat4 indexToClip;
uniform mat4 indexToEye;
// Window position (gl_FragCoord.xy, 1) -> homogeneous index / eye point on the slice plane at
// the frame's reference depth, and their change per unit of slice depth (the maps are affine in
// depth, so this is exact).
uniform mat3 indexMap;
uniform mat3 indexMapPerDepth;
uniform mat3 eyeMap;
uniform mat3 eyeMapPerDepth;

out vec3 interpolatedIndex;
out vec3 interpolatedEye;
// This slice's maps: flat, and computed from the slice depth alone, so every polygon that covers
// a pixel of the slice (octree-clipped or whole, cropped piece or slab proxy) gets the same bits.
flat out mat3 sliceIndexMap;
flat out mat3 sliceEyeMap;

void main()
{
  interpolatedIndex = vertexIndex;
  interpolatedEye = (indexToEye * vec4(vertexIndex, 1.0)).xyz;
  ACCELVOLUME_PRECISE mat3 indexMapHere = indexMap + vertexDepth * indexMapPerDepth;
  ACCELVOLUME_PRECISE mat3 eyeMapHere = eyeMap + vertexDepth * eyeMapPerDepth;
  sliceIndexMap = indexMapHere;
  sliceEyeMap = eyeMapHere;
  gl_Position = indexToClip * vec4(vertexIndex, 1.0);
}
