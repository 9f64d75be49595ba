//VTK::System::Dec
// Proxy slice / boundary face fragment stage: samples the volume once and writes the
// blend mode's accumulation value into an RG32F target (R: value, G: weight or coverage).
// A prelude defines exactly one of ACCELVOLUME_BLEND_{MAXIMUM,MINIMUM,ADDITIVE,AVERAGE},
// ACCELVOLUME_SLAB_SAMPLES (slice depths per fragment: MIP, MinIP, composite), ACCELVOLUME_BOUNDARY_FACE
// (0: proxy slices, 1: cut faces) and ACCELVOLUME_PROJECTIVE_SLICES (1: the projection's w
// depends on eye x or y, so slice points need a division). They are compile-time constants
// because llvmpipe pays for every branch and loop it cannot resolve while compiling.
// Sample points must round the same way in every shader variant (the skipping modes compare
// images exactly): `precise` stops the compiler from fusing or reordering their arithmetic
// differently per variant. (The extension makes `sample` a keyword: no variable is so named.)
#extension GL_ARB_gpu_shader5 : enable
#ifdef GL_ARB_gpu_shader5
#define ACCELVOLUME_PRECISE precise
#else
#define ACCELVOLUME_PRECISE
#endif
//VTK::Output::Dec

in vec3 interpolatedIndex;
in vec3 interpolatedEye;
flat in mat3 sliceIndexMap;        // proxy slices: (gl_FragCoord.xy, 1) -> index point
flat in mat3 sliceEyeMap;          // ... -> eye point (homogeneous, see pixelWeight)

#define ACCELVOLUME_PIXEL gl_FragCoord.xy

//ACCELVOLUME::Sampling::Dec

// Render-to-image: the window depth of the nearest contributing sample (MIN-blended second
// target), as vtkGPUVolumeRayCastMapper's depth image.
#if ACCELVOLUME_RENDER_TO_IMAGE
#define ACCELVOLUME_WRITE_DEPTH(contributes) gl_FragData[1] = vec4((contributes) ? gl_FragCoord.z : 1.0)
#else
#define ACCELVOLUME_WRITE_DEPTH(contributes)
#endif

void main()
{
#if ACCELVOLUME_BOUNDARY_FACE
  eyePosition = interpolatedEye;
  indexPosition = interpolatedIndex;
#else
  // The projection restricted to the slice plane, inverted: a pixel's point there is linear in
  // its window position (projective if the projection's w row slopes). Interpolating the
  // polygon's vertex positions instead rounds differently for each polygon that covers the
  // pixel (octree-clipped vs. whole slices), and texture units with 8-bit filter weights
  // (NVIDIA) turn that rounding into visible steps.
  vec2 pixel = gl_FragCoord.xy;
  indexPosition = sliceIndexMap[0] * pixel.x + sliceIndexMap[1] * pixel.y + sliceIndexMap[2];
  eyePosition = sliceEyeMap[0] * pixel.x + sliceEyeMap[1] * pixel.y + sliceEyeMap[2];
#if ACCELVOLUME_PROJECTIVE_SLICES
  ACCELVOLUME_PRECISE float weight =
    pixelWeight.x * pixel.x + pixelWeight.y * pixel.y + pixelWeight.z;
  indexPosition /= weight;
  eyePosition /= weight;
#endif
#endif
#if ACCELVOLUME_BRICKED
  // Each sample point belongs to one brick; the slices of its neighbours reach half a voxel in.
  if (any(lessThan(indexPosition, ownedLower)) || any(greaterThanEqual(indexPosition, ownedUpper)))
  {
    discard;
  }
#endif
#if ACCELVOLUME_MASK == 1
  // Binary mask: samples outside it are skipped, whatever the blend mode. A raysum still covers
  // its pixel (VTK's GPU mapper draws black where every sample of a ray is masked).
  if (maskHides(indexPosition))
  {
#if defined(ACCELVOLUME_BLEND_ADDITIVE)
    gl_FragData[0] = vec4(0.0, 1.0, 0.0, 0.0);
    ACCELVOLUME_WRITE_DEPTH(false);
    return;
#else
    discard;
#endif
  }
#endif
#if defined(ACCELVOLUME_BLEND_MAXIMUM) || defined(ACCELVOLUME_BLEND_MINIMUM)
  // Order-independent extremes: opaque geometry is handled by the early depth test against
  // the scene depth attached to the target, so a plain slice costs one texture fetch.
#if ACCELVOLUME_COMPONENTS > 1
  // Multi-component extremes as VTK's GPU mapper: independent components each keep their own
  // extreme (MAX / MIN blending per channel); dependent ones keep the whole sample whose last
  // component is extreme. That sample is kept by a depth test on its last component, written
  // as the fragment's depth (the target's depth buffer is then not the scene's, which is
  // tested here); slices are drawn back to front and the test passes ties, so the front-most
  // such sample stays, VTK's first along the ray.
  vec4 values =
    texture(volumeTexture, ACCELVOLUME_TEXEL_CENTRE(indexPosition) / volumeDimensions);
#if !ACCELVOLUME_INDEPENDENT
  if (gl_FragCoord.z >= texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r)
  {
    discard;
  }
  gl_FragDepth = clamp(values[ACCELVOLUME_COMPONENTS - 1], 0.0, 1.0);
#endif
  gl_FragData[0] = values;
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_SLAB_SAMPLES <= 1
  gl_FragData[0] = vec4(normalizedScalar(), 1.0, 0.0, 0.0);
  ACCELVOLUME_WRITE_DEPTH(true);
#else
  // Slab: this fragment also takes the next slabSamples - 1 slice depths along its ray, so
  // the rasteriser and the blender see a fraction of the fragments. Samples outside the
  // region or behind geometry are skipped, which keeps the sample set of plain slicing.
  vec3 rayOrigin = parallelProjection != 0 ? vec3(eyePosition.xy, 0.0) : vec3(0.0);
  vec3 rayDirection = parallelProjection != 0 ? vec3(0.0, 0.0, -1.0) : normalize(eyePosition);
  float here = dot(eyePosition - rayOrigin, rayDirection);
  float step = sliceSpacing / max(-rayDirection.z, 1.0e-6);
  vec2 interval = regionInterval(rayOrigin, rayDirection);
  float enter = interval.x - 1.0e-3 * step;
  float exit = min(interval.y, sceneDistance(rayOrigin, rayDirection)) + 1.0e-3 * step;
  ACCELVOLUME_PRECISE vec3 textureCoordinate =
    ACCELVOLUME_TEXEL_CENTRE(indexPosition) / volumeDimensions;
  vec3 textureStep = (mat3(eyeToIndex) * rayDirection) * step / volumeDimensions;
#if defined(ACCELVOLUME_BLEND_MAXIMUM)
  float extreme = -1.0;
#else
  float extreme = 2.0;
#endif
  bool sampled = false;
  for (int j = 0; j < ACCELVOLUME_SLAB_SAMPLES; ++j)
  {
    float t = here + float(j) * step;
    if (t >= enter && t <= exit)
    {
      float value = texture(volumeTexture, textureCoordinate + float(j) * textureStep).r *
          scalarScale + scalarBias;
#if defined(ACCELVOLUME_BLEND_MAXIMUM)
      extreme = max(extreme, value);
#else
      extreme = min(extreme, value);
#endif
      sampled = true;
    }
  }
  if (!sampled)
  {
    discard;
  }
  gl_FragData[0] = vec4(extreme, 1.0, 0.0, 0.0);
  ACCELVOLUME_WRITE_DEPTH(true);
#endif
#elif defined(ACCELVOLUME_BLEND_COMPOSITE)
  // Front-to-back compositing (blended "under" in the target); the opacity is corrected from
  // the unit distance to this ray's actual slice spacing, so the image does not change with
  // the slice count.
#if ACCELVOLUME_DEPTH_PASS == 2
  // UseDepthPass: rays start at their first contour crossing, and draw nothing without one
  // (as VTK's GPU mapper, whose rays then start at the far plane). The contour's depth is the
  // target's depth buffer here (GEQUAL: fragments in front of it fail early), so the scene's
  // depth is tested here.
  if (gl_FragCoord.z >= texelFetch(sceneDepth, ivec2(gl_FragCoord.xy), 0).r)
  {
    discard;
  }
#endif
  vec3 rayDirection = parallelProjection != 0 ? vec3(0.0, 0.0, -1.0) : normalize(eyePosition);
  float step = sliceSpacing / max(-rayDirection.z, 1.0e-6);
  ACCELVOLUME_PRECISE vec3 samplePosition = indexPosition;
#if ACCELVOLUME_JITTER
  // Per-pixel offset of up to half a slice along the ray turns wood-grain rings into fine noise.
  samplePosition +=
    (mat3(eyeToIndex) * rayDirection) * (step * (jitterNoise(gl_FragCoord.xy) - 0.5));
#endif
#if ACCELVOLUME_SLICE_PLANE && ACCELVOLUME_COMPONENTS > 1
  // SLICE_BLEND of multi-component scalars: the plane's sample classified as composite
  // classifies it, without opacity correction (VTK 9.1's GPU shader fails on independent ones).
  vec4 premultiplied = multiComponentSample(samplePosition, rayDirection, step, true);
  if (premultiplied.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = premultiplied;
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_SLICE_PLANE
  // SLICE_BLEND (as VTK's GPU mapper): the plane's sample, coloured and opaque as the transfer
  // functions say, no opacity correction (one sample, no step), shaded when the property is.
  vec4 planeSample = classify(normalizedScalarAt(samplePosition));
#if ACCELVOLUME_SHADE
  ACCELVOLUME_PRECISE vec3 planeCenter = ACCELVOLUME_TEXEL_CENTRE(samplePosition) / volumeDimensions;
  planeSample.rgb = shade(planeSample.rgb, normalMatrix * centralDifferences(planeCenter), rayDirection);
#endif
  if (planeSample.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = vec4(planeSample.rgb * planeSample.a, planeSample.a);
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_DEPTH_PASS == 1
  // UseDepthPass, first stage: the depth of the first sample behind the ray's first contour
  // crossing (VTK renders the contour's polygons there; the accumulation starts at that same
  // sample either way). The fragment's own depth, so the depth test keeps the nearest and,
  // slices drawn front to back, culls every slice behind it before shading.
  vec3 previousPosition = samplePosition - (mat3(eyeToIndex) * rayDirection) * step;
  if (!previousSampleInside(previousPosition) ||
    firstCrossing(samplePosition, previousPosition) > 1.0)
  {
    discard;
  }
  gl_FragData[0] = vec4(0.0);
#elif ACCELVOLUME_ISOSURFACE
  vec3 previousPosition = samplePosition - (mat3(eyeToIndex) * rayDirection) * step;
  if (!previousSampleInside(previousPosition))
  {
    discard;
  }
  vec4 premultiplied = isoSurfaceSample(samplePosition, previousPosition, rayDirection);
  if (premultiplied.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = premultiplied;
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_COMPONENTS > 1
#if ACCELVOLUME_SKIP_OCTREE
  // Multi-component: the leaves where every contributing component is transparent.
  vec3 leaf = clamp(floor(samplePosition / leafSize), vec3(0.0), leafGridMaximum);
  if (texelFetch(emptyLeaves, ivec3(leaf), 0).r > 0.5)
  {
    discard;
  }
#endif
  vec4 premultiplied = multiComponentSample(samplePosition, rayDirection, step, false);
  if (premultiplied.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = premultiplied;
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_SLAB_SAMPLES > 1
  // Slab: this fragment composites the next slabSamples slice depths along its ray, front to
  // back in registers, and blends once for them all. Samples outside the region or behind
  // geometry are skipped, which keeps the sample set of plain slicing.
  vec3 rayOrigin = parallelProjection != 0 ? vec3(eyePosition.xy, 0.0) : vec3(0.0);
  float here = dot(eyePosition - rayOrigin, rayDirection);
  vec2 interval = regionInterval(rayOrigin, rayDirection);
  float enter = interval.x - 1.0e-3 * step;
  float exit = min(interval.y, sceneDistance(rayOrigin, rayDirection)) + 1.0e-3 * step;
  vec3 indexStep = (mat3(eyeToIndex) * rayDirection) * step;
  vec3 slabFront = eyePosition;
  vec4 accumulated = vec4(0.0);
  for (int j = 0; j < ACCELVOLUME_SLAB_SAMPLES; ++j)
  {
    float t = here + float(j) * step;
    // Positional lights read the sample's eye point.
    eyePosition = slabFront + rayDirection * (float(j) * step);
    ACCELVOLUME_PRECISE vec3 position = samplePosition + float(j) * indexStep;
    vec4 premultiplied;
    if (t >= enter && t <= exit && compositeSample(position, rayDirection, step, premultiplied))
    {
      accumulated += (1.0 - accumulated.a) * premultiplied;
    }
  }
  if (accumulated.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = accumulated;
  ACCELVOLUME_WRITE_DEPTH(true);
#else
  vec4 premultiplied;
  if (!compositeSample(samplePosition, rayDirection, step, premultiplied))
  {
    discard;
  }
  gl_FragData[0] = premultiplied;
  ACCELVOLUME_WRITE_DEPTH(premultiplied.a > 0.0);
#endif
#else
  vec3 rayOrigin = parallelProjection != 0 ? vec3(eyePosition.xy, 0.0) : vec3(0.0);
  vec3 rayDirection = parallelProjection != 0 ? vec3(0.0, 0.0, -1.0) : normalize(eyePosition);
  float here = dot(eyePosition - rayOrigin, rayDirection);
  float geometry = sceneDistance(rayOrigin, rayDirection);
#if ACCELVOLUME_COMPONENTS > 1
  // Multi-component raysum / average as VTK's GPU mapper: independent components add their
  // weighted opacity(value) * value; dependent ones (luminance-alpha, RGBA) take component 0's
  // value and the opacity of the last component.
  vec4 values =
    texture(volumeTexture, ACCELVOLUME_TEXEL_CENTRE(indexPosition) / volumeDimensions);
  float value = values.x;
#if ACCELVOLUME_INDEPENDENT
  float weightedValue = 0.0;
  vec4 opacityValues = vec4(0.0); // the average keeps them apart (weighted in the resolve)
  for (int c = 0; c < ACCELVOLUME_COMPONENTS; ++c)
  {
    opacityValues[c] = componentLookup(c, values[c]).a * values[c];
    weightedValue += componentWeights[c] * opacityValues[c];
  }
#else
  float weightedValue = componentLookup(0, values[ACCELVOLUME_COMPONENTS - 1]).a * value;
#endif
#else
  float value = normalizedScalar();
  float weightedValue = opacity(value) * value;
#endif
  // Integrating modes: weight each sample by the ray length it stands for, so the result
  // is a line integral whatever the slice count. Slices are planes of constant eye depth;
  // along this ray they are sliceSpacing / cos(theta) apart.
  float cosTheta = max(-rayDirection.z, 1.0e-6);
  float step = sliceSpacing / cosTheta;
  vec2 interval = regionInterval(rayOrigin, rayDirection);
  float enter = interval.x;
  float boxExit = interval.y;
  float exit = min(boxExit, geometry);
  bool exitSampled = boundaryRerendering != 0 && boxExit <= geometry;
  bool enterSampled = boundaryRerendering != 0;
  float weight = 0.0;
#if ACCELVOLUME_BOUNDARY_FACE
  {
    // Trapezoid rule: a face sample covers half of the gap to its nearest slice.
    bool isEnter = abs(here - enter) <= abs(here - exit);
    if (!isEnter && !exitSampled)
    {
      discard;
    }
    float firstSlice = (slicePhase + ceil((enter * cosTheta - slicePhase) / sliceSpacing) * sliceSpacing) / cosTheta;
    float lastSlice = (slicePhase + floor((exit * cosTheta - slicePhase) / sliceSpacing) * sliceSpacing) / cosTheta;
    if (firstSlice > exit)
    {
      weight = 0.5 * (exit - enter);
    }
    else
    {
      weight = isEnter ? 0.5 * (firstSlice - enter) : 0.5 * (exit - lastSlice);
    }
  }
#else
  {
    float lower = here - 0.5 * step;
    float upper = here + 0.5 * step;
    if (here - step < enter)
    {
      lower = enterSampled ? 0.5 * (here + enter) : enter;
    }
    if (here + step > exit)
    {
      upper = exitSampled ? 0.5 * (here + exit) : exit;
    }
    weight = upper - lower;
  }
#endif
  weight = max(weight, 0.0);
#if defined(ACCELVOLUME_BLEND_ADDITIVE)
  gl_FragData[0] = vec4(weight * weightedValue * additiveScale, weight, 0.0, 0.0);
  ACCELVOLUME_WRITE_DEPTH(true);
#elif ACCELVOLUME_COMPONENTS > 1 && ACCELVOLUME_INDEPENDENT
  // Independent components average apart, each over its samples in the range (as VTK's GPU
  // mapper): (sum, weight) pairs, components 0-1 in the first target, 2-3 in the second.
  vec4 inRange = vec4(greaterThanEqual(values, averageLower)) *
    vec4(lessThanEqual(values, averageUpper)) * weight;
  vec4 sums = inRange * opacityValues;
  gl_FragData[0] = vec4(sums.x, inRange.x, sums.y, inRange.y);
  // (VTK's shader cache maps the literal names gl_FragData[n] to its outputs.)
#if ACCELVOLUME_COMPONENTS > 2 && ACCELVOLUME_RENDER_TO_IMAGE
  gl_FragData[2] = vec4(sums.z, inRange.z, sums.w, inRange.w);
#elif ACCELVOLUME_COMPONENTS > 2
  gl_FragData[1] = vec4(sums.z, inRange.z, sums.w, inRange.w);
#endif
  ACCELVOLUME_WRITE_DEPTH(true);
#else
  float inRange = (value >= averageRange.x && value <= averageRange.y) ? 1.0 : 0.0;
  gl_FragData[0] = vec4(inRange * weight * weightedValue, inRange * weight, 0.0, 0.0);
  ACCELVOLUME_WRITE_DEPTH(true);
#endif
#endif
}
