// Compute slices (vtkAccelVolumeSliceMapper::SliceCompositing COMPUTE): one invocation per
// accumulation texel takes the samples where the frame's view-aligned slice planes cross its
// ray, at the points the proxy-slice fragments would take (the same slice maps and sampling
// code, to rounding), composites them front to back in registers and stores the value the
// blended slices would leave in the target: no rasterisation and no framebuffer blending, so the
// work runs on every shader core (on compute-class GPUs only a few run fragments) and costs one
// store per pixel. Composite rays stop at the termination threshold and leap over transparent octree
// blocks and leaves (every sample inside one is skipped by the fragment path too); MIP / MinIP
// take the cut-face samples that boundary re-rendering adds. The prelude
// (vtkAccelVolumeSliceShaderPrelude plus ACCELVOLUME_TARGET_FORMAT, ACCELVOLUME_TERMINATE,
// ACCELVOLUME_COUNT_SAMPLES) comes first.
#define ACCELVOLUME_COMPUTE_SLICES 1
#define ACCELVOLUME_PRECISE precise
vec2 computePixel; // the window position of this texel's centre, as gl_FragCoord.xy
#define ACCELVOLUME_PIXEL computePixel

//ACCELVOLUME::Sampling::Dec

layout(local_size_x = 8, local_size_y = 8) in;
layout(ACCELVOLUME_TARGET_FORMAT, binding = 0) uniform writeonly image2D accumulationImage;
#if ACCELVOLUME_COUNT_SAMPLES
layout(std430, binding = 0) buffer SampleCounter
{
  uint samplesTaken;
};
#endif

// The slice maps of the proxy-slice vertex stage: window (x, y, 1) -> index / eye point on the
// plane at the reference depth, and their change per unit of relative slice depth.
uniform mat3 indexMap;
uniform mat3 indexMapPerDepth;
uniform mat3 eyeMap;
uniform mat3 eyeMapPerDepth;
uniform float sliceBase;           // relative depth (eye depth - reference) of slice number 0
uniform float referenceDepth;      // eye depth the relative depths are measured from
uniform float terminationThreshold;

ACCELVOLUME_PRECISE float pixelW; // homogeneous weight of this pixel's slice points (1: affine)
// [enter, exit] of relative slice depth where the ray point origin + depth * perDepth lies in
// the region box and every clip half-space; enter > exit when it misses.
vec2 depthInterval(vec3 origin, vec3 perDepth)
{
  return clipInterval(origin, perDepth, boxInterval(origin, perDepth), false);
}

// Relative depth of the opaque geometry on this pixel (the proxy slices' depth test), or huge.
float sceneRelativeDepth()
{
  vec3 eye;
  return sceneEyePoint(eye) ? -eye.z - referenceDepth : 1.0e30;
}

#if defined(ACCELVOLUME_BLEND_COMPOSITE) && ACCELVOLUME_SKIP_OCTREE
// Blocks of LeafBlock^3 leaves, transparent where all their leaves are (emptyBlocks): rays leap
// over empty space a block at a time, then a leaf at a time.
const float LeafBlock = 4.0;
uniform sampler3D emptyBlocks;
uniform vec3 blockGridMaximum;

// Relative depth where the ray (origin + depth * perDepth) leaves the grid cell of edge
// `cellSize` holding index point `point`; the outermost cells reach past the grid, as the cell
// lookup clamps points to it.
float cellExitDepth(vec3 point, float cellSize, vec3 gridMaximum, vec3 origin, vec3 perDepth)
{
  vec3 cell = clamp(floor(point / cellSize), vec3(0.0), gridMaximum);
  float exit = 1.0e30;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (perDepth[axis] > 1.0e-20 && cell[axis] < gridMaximum[axis])
    {
      exit = min(exit, ((cell[axis] + 1.0) * cellSize - origin[axis]) / perDepth[axis]);
    }
    else if (perDepth[axis] < -1.0e-20 && cell[axis] > 0.0)
    {
      exit = min(exit, (cell[axis] * cellSize - origin[axis]) / perDepth[axis]);
    }
  }
  return exit;
}

// The next slice number to test when the ray point at slice j (index point `point`) is in a
// transparent block or leaf (at most last + 1), else j. The slices skipped lie inside that block
// or leaf at least one slice spacing before its exit (so rounding cannot misplace them); the
// returned one is tested (it may sit on the exit face). When the leaf is not transparent,
// `visibleUntil` gets the depth where the ray leaves it: the samples up to there need no test
// (one on the exit face belongs to the next leaf, but then lies in this leaf's voxels too, so
// were that leaf transparent, its opacity would be 0 all the same).
int leapEmptySpace(int j, int last, vec3 point, vec3 origin, vec3 perDepth, out float visibleUntil)
{
  // One exit computation for whichever cell the point is tested in (CPU drivers run both
  // branches of a per-lane test, so the two cases share it).
  float cellSize = leafSize * LeafBlock;
  vec3 gridMaximum = blockGridMaximum;
  vec3 block = clamp(floor(point / cellSize), vec3(0.0), blockGridMaximum);
  bool transparent = texelFetch(emptyBlocks, ivec3(block), 0).r > 0.5;
  if (!transparent)
  {
    vec3 leaf = clamp(floor(point / leafSize), vec3(0.0), leafGridMaximum);
    transparent = texelFetch(emptyLeaves, ivec3(leaf), 0).r > 0.5;
    cellSize = leafSize;
    gridMaximum = leafGridMaximum;
  }
  float exit = cellExitDepth(point, cellSize, gridMaximum, origin, perDepth);
  if (!transparent)
  {
    visibleUntil = exit;
    return j;
  }
  visibleUntil = -1.0e30;
  float slices = min(floor((exit - sliceBase) / sliceSpacing), float(last + 1));
  return slices >= float(j + 1) ? int(slices) : j + 1;
}

#endif

void main()
{
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= int(viewportSize.x) || texel.y >= int(viewportSize.y))
  {
    return;
  }
  computePixel = vec2(texel) + vec2(0.5);
  vec3 pixel = vec3(computePixel, 1.0);
  pixelW = 1.0;
#if ACCELVOLUME_PROJECTIVE_SLICES
  pixelW = dot(pixelWeight, pixel);
#endif
  // The ray as a function of relative slice depth (index and eye points): the samples lie where
  // the slice planes cross it, as the proxy slices' fragments do (to rounding: each fragment
  // evaluates its slice's map; a ray steps along one line, which costs less per sample).
  vec3 origin = (indexMap * pixel) / pixelW;
  vec3 perDepth = (indexMapPerDepth * pixel) / pixelW;
  vec3 eyeOrigin = (eyeMap * pixel) / pixelW;
  vec3 eyeRay = (eyeMapPerDepth * pixel) / pixelW;
  vec2 interval = depthInterval(origin, perDepth);
  if (!(interval.x <= interval.y) || abs(interval.x) > 1.0e20 || abs(interval.y) > 1.0e20)
  {
    interval = vec2(1.0, -1.0); // misses the region (the region box bounds every hit)
  }
  float regionExit = interval.y;
  float sceneDepthHere = sceneRelativeDepth();
  interval.y = min(interval.y, sceneDepthHere);
  // Slices strictly in front of the scene depth (the proxy slices' LESS test).
  int first = int(ceil((interval.x - sliceBase) / sliceSpacing));
  int last = interval.x <= interval.y ? int(floor((interval.y - sliceBase) / sliceSpacing)) : first - 1;
  if (sliceBase + float(last) * sliceSpacing >= sceneDepthHere)
  {
    --last;
  }
  uint taken = 0u;
#if defined(ACCELVOLUME_BLEND_COMPOSITE)
  vec3 rayDirection = parallelProjection != 0 ? vec3(0.0, 0.0, -1.0) : normalize(eyeRay);
  float step = sliceSpacing / max(-rayDirection.z, 1.0e-6);
#if ACCELVOLUME_JITTER
  vec3 jitterOffset = (mat3(eyeToIndex) * rayDirection) * (step * (jitterNoise(computePixel) - 0.5));
#endif
  vec4 accumulated = vec4(0.0);
  float visibleUntil = -1.0e30; // the ray is in a leaf that is not transparent up to here
  for (int j = first; j <= last; ++j)
  {
    float depth = sliceBase + float(j) * sliceSpacing;
#if ACCELVOLUME_SKIP_OCTREE
    if (depth > visibleUntil)
    {
      int next = leapEmptySpace(j, last, origin + depth * perDepth, origin, perDepth, visibleUntil);
      if (next != j)
      {
        j = next - 1;
        continue;
      }
    }
#endif
    indexPosition = origin + depth * perDepth;
#if ACCELVOLUME_POSITIONAL_LIGHTS
    eyePosition = eyeOrigin + depth * eyeRay;
#endif
    ACCELVOLUME_PRECISE vec3 samplePosition = indexPosition;
#if ACCELVOLUME_JITTER
    samplePosition += jitterOffset;
#endif
    ++taken;
    vec4 premultiplied;
    if (compositeSample(samplePosition, rayDirection, step, premultiplied))
    {
      accumulated += (1.0 - accumulated.a) * premultiplied;
#if ACCELVOLUME_TERMINATE
      if (accumulated.a >= terminationThreshold)
      {
        break;
      }
#endif
    }
  }
  imageStore(accumulationImage, texel, accumulated);
#else
#if defined(ACCELVOLUME_BLEND_MAXIMUM)
  float cleared = -1.0;
#define ACCELVOLUME_EXTREME(a, b) max(a, b)
#else
  float cleared = 2.0;
#define ACCELVOLUME_EXTREME(a, b) min(a, b)
#endif
  float extreme = cleared;
  bool sampled = false;
  for (int j = first; j <= last; ++j)
  {
    indexPosition = origin + (sliceBase + float(j) * sliceSpacing) * perDepth;
    extreme = ACCELVOLUME_EXTREME(extreme, normalizedScalar());
    sampled = true;
    ++taken;
  }
  // Boundary re-rendering: the cut faces' samples where the ray enters and leaves the region
  // (a face behind the opaque geometry is hidden, as its fragments fail the depth test).
  if (boundaryRerendering != 0 && interval.x <= regionExit)
  {
    if (interval.x < sceneDepthHere)
    {
      indexPosition = origin + interval.x * perDepth;
      extreme = ACCELVOLUME_EXTREME(extreme, normalizedScalar());
      sampled = true;
      ++taken;
    }
    if (regionExit < sceneDepthHere)
    {
      indexPosition = origin + regionExit * perDepth;
      extreme = ACCELVOLUME_EXTREME(extreme, normalizedScalar());
      sampled = true;
      ++taken;
    }
  }
  imageStore(accumulationImage, texel, sampled ? vec4(extreme, 1.0, 0.0, 0.0) : vec4(cleared));
#endif
#if ACCELVOLUME_COUNT_SAMPLES
  if (taken > 0u)
  {
    atomicAdd(samplesTaken, taken);
  }
#endif
}
