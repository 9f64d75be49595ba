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
#ifdef ACCELVOLUME_GENERATED_SLICES
// Slices generated here (one instance per slice, 30 vertices: a fan of up to 10 triangles over
// the plane's section of the slice's box, which has at most 12 edge crossings counting a corner
// once per edge through it); the CPU sends only each slice's depth and box.
in float sliceDepth; // the slice's eye depth minus the reference depth
in vec3 sliceLower;  // the box the slice is drawn across, in index coordinates
in vec3 sliceUpper;
uniform vec3 depthGradient; // eye depth minus the reference depth = dot(depthGradient, p) + depthOffset
uniform float depthOffset;
#else
in vec3 vertexIndex;
in float vertexDepth;
#endif

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

#ifdef ACCELVOLUME_GENERATED_SLICES
// The fan vertex gl_VertexID of the section of the plane dot(depthGradient, p) = level with
// the box: the edge crossings sorted by angle around their centroid (every vertex invocation
// of the instance finds the same order); past the last crossing the triangle collapses.
vec3 SectionVertex(float level)
{
  vec3 crossings[12];
  int count = 0;
  for (int axis = 0; axis < 3; ++axis)
  {
    int u = (axis + 1) % 3;
    int w = (axis + 2) % 3;
    float run = depthGradient[axis] * (sliceUpper[axis] - sliceLower[axis]);
    for (int corner = 0; corner < 4; ++corner)
    {
      vec3 start = sliceLower;
      start[u] = (corner & 1) != 0 ? sliceUpper[u] : sliceLower[u];
      start[w] = (corner & 2) != 0 ? sliceUpper[w] : sliceLower[w];
      float t = run != 0.0 ? (level - dot(depthGradient, start)) / run : -1.0;
      if (t >= 0.0 && t <= 1.0)
      {
        vec3 p = start;
        p[axis] = mix(sliceLower[axis], sliceUpper[axis], t);
        crossings[count++] = p;
      }
    }
  }
  int triangle = gl_VertexID / 3;
  int corner = gl_VertexID - 3 * triangle;
  if (count < 3 || triangle + 2 >= count)
  {
    return count > 0 ? crossings[0] : sliceLower;
  }
  vec3 centre = vec3(0.0);
  for (int i = 0; i < count; ++i)
  {
    centre += crossings[i];
  }
  centre /= float(count);
  vec3 normal = normalize(depthGradient);
  vec3 helper = abs(normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 first = normalize(cross(normal, helper));
  vec3 second = cross(normal, first);
  float angles[12];
  for (int i = 0; i < count; ++i)
  {
    vec3 d = crossings[i] - centre;
    angles[i] = atan(dot(d, second), dot(d, first));
  }
  // Insertion sort by angle (at most 12 points).
  for (int i = 1; i < count; ++i)
  {
    float angle = angles[i];
    vec3 p = crossings[i];
    int j = i - 1;
    while (j >= 0 && angles[j] > angle)
    {
      angles[j + 1] = angles[j];
      crossings[j + 1] = crossings[j];
      --j;
    }
    angles[j + 1] = angle;
    crossings[j + 1] = p;
  }
  int index = corner == 0 ? 0 : triangle + corner;
  return crossings[index];
}
#endif

void main()
{
#ifdef ACCELVOLUME_GENERATED_SLICES
  vec3 vertexIndex = SectionVertex(sliceDepth - depthOffset);
  float vertexDepth = sliceDepth;
#endif
  interpolatedIndex = vertexIndex;
  interpolatedEye = (indexToEye * vec4(vertexIndex, 1.0)).xyz;
  ACCELVOLUME_PRECISE mat3 indexMapHere = indexMap + vertexDepth * indexMapPerDepth;
  ACCELVOLUME_PRECISE mat3 eyeMapHere = eyeMap + vertexDepth * eyeMapPerDepth;
  sliceIndexMap = indexMapHere;
  sliceEyeMap = eyeMapHere;
  gl_Position = indexToClip * vec4(vertexIndex, 1.0);
}
