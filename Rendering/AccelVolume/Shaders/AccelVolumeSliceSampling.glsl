// The slice shaders' sampling, shared by the proxy-slice fragment stage (AccelVolumeSliceFS)
// and the compute slices (AccelVolumeSliceCS), inserted at their
// //ACCELVOLUME::Sampling::Dec line after the prelude: the frame's uniforms, the sample point,
// scalar lookup and classification, gradients, VTK's light model, masks and one composite
// sample. ACCELVOLUME_PIXEL is the pixel (window position of its centre) being drawn.

uniform sampler3D volumeTexture;
uniform sampler2D transferTable;   // rgb: colour, a: scalar opacity, over the data range
uniform sampler2D sceneDepth;      // window depth of the opaque geometry already drawn
uniform vec3 volumeDimensions;    // of the texture (the brick's, when bricked)
// ACCELVOLUME_BRICKED: the texture holds the volume's points from textureOrigin on, and this
// brick takes only the samples in [ownedLower, ownedUpper) (its neighbours take the others).
uniform vec3 textureOrigin;
uniform vec3 ownedLower;
uniform vec3 ownedUpper;
uniform float scalarScale;         // normalized scalar = texel * scalarScale + scalarBias
uniform float scalarBias;
uniform float tableSize;
uniform mat4 eyeToIndex;
uniform mat4 inverseProjection;
uniform vec3 pixelWeight;          // ACCELVOLUME_PROJECTIVE_SLICES: homogeneous weight
uniform vec2 viewportSize;
uniform vec3 regionLower;          // the convex cell being drawn, in index coordinates
uniform vec3 regionUpper;
uniform int clipPlaneCount;
uniform vec4 clipPlanes[8];        // index space: keep dot(xyz, p) + w >= 0
uniform float sliceSpacing;        // along the view direction (world units)
uniform float slicePhase;
uniform int boundaryRerendering;
uniform int parallelProjection;
uniform float additiveScale;       // 1 / unit distance
uniform vec2 averageRange;         // normalized scalar range counted by the average
uniform vec4 averageLower;         // ... per component of independent multi-component scalars
uniform vec4 averageUpper;
uniform float opacityUnitDistance; // composite: the table opacities hold for this length
// Composite shading and gradient opacity (ACCELVOLUME_SHADE, ACCELVOLUME_GRADIENT_OPACITY):
uniform mat3 normalMatrix;          // index-space gradient -> eye-space gradient
uniform float scalarRangeWidth;     // data units per normalized unit
uniform sampler2D gradientOpacityTable; // r: opacity over [0, gradientTableMaximum]
uniform float gradientTableMaximum;
// VTK's gradient magnitude: index-step differences times mean spacing / axis spacing.
uniform vec3 gradientAxisScale;
// VTK's light model (Rendering/Core/common/Lighting.h), eye space, colours times intensity.
uniform int lightCount;
uniform int lightPositional[16];
uniform vec3 lightAxis[16];         // the way each light shines
uniform vec3 lightPosition[16];
uniform vec3 lightAmbient[16];
uniform vec3 lightDiffuse[16];
uniform vec3 lightSpecular[16];
uniform vec3 lightAttenuation[16];  // constant, linear, quadratic
uniform float lightCosCone[16];     // spot lights: cos(cone angle); < -1: no cone
uniform float lightExponent[16];
uniform int twoSidedLighting;
uniform int headlightOnly;          // VTK's single headlight: ambient term = ambient * colour
uniform vec4 lighting;              // ambient, diffuse, specular, specular power
// Mask input (ACCELVOLUME_MASK 1: binary, 2: label map), nearest per voxel, as VTK's GPU mapper.
uniform sampler3D maskTexture;      // R8: binary 0 / 1, or the label / 255
uniform vec3 maskMaximum;           // largest voxel index per axis
uniform sampler2D labelTable;       // rgba over (scalar, label), labels 0..255 as rows
uniform float maskBlendFactor;
// Composite empty-space skipping (ACCELVOLUME_SKIP_OCTREE, ACCELVOLUME_SKIP_TRANSPARENT):
uniform sampler3D emptyLeaves;      // 1 where the octree leaf is transparent (leaf grid)
uniform float leafSize;
// Precomputed gradients (ACCELVOLUME_GRADIENT_TEXTURE): index-space central differences in
// normalized scalar units, stored as rgb * 2 - 1 times gradientTextureScale.
uniform sampler3D gradientTexture;
uniform float gradientTextureScale;
// The gradient texture's alpha holds the normalized scalar: compute rays read both from one
// fetch (CPU drivers pay for every fetch on every lane); the proxy slices keep the scalar texture.
#if ACCELVOLUME_GRADIENT_TEXTURE && defined(ACCELVOLUME_COMPUTE_SLICES)
#define ACCELVOLUME_PACKED_SAMPLE 1
#else
#define ACCELVOLUME_PACKED_SAMPLE 0
#endif
// 2D transfer function (ACCELVOLUME_TF2D): rgba over (scalar, gradient magnitude / maximum).
uniform sampler2D transferTable2D;
uniform float gradient2DMaximum;
uniform vec3 leafGridMaximum;       // leaf grid size - 1 per axis

// This fragment's sample point, set first thing in main(): on a proxy slice, from the pixel and
// the slice depth alone; on a cut face (not view-aligned), interpolated from the face.
ACCELVOLUME_PRECISE vec3 indexPosition;
ACCELVOLUME_PRECISE vec3 eyePosition;

#if ACCELVOLUME_BRICKED
#define ACCELVOLUME_TEXEL_CENTRE(position) ((position) - textureOrigin + vec3(0.5))
#else
#define ACCELVOLUME_TEXEL_CENTRE(position) ((position) + vec3(0.5))
#endif

float normalizedScalarAt(vec3 position)
{
  ACCELVOLUME_PRECISE vec3 textureCoordinate = ACCELVOLUME_TEXEL_CENTRE(position) / volumeDimensions;
  return texture(volumeTexture, textureCoordinate).r * scalarScale + scalarBias;
}

float normalizedScalar()
{
  ACCELVOLUME_PRECISE vec3 textureCoordinate =
    ACCELVOLUME_TEXEL_CENTRE(indexPosition) / volumeDimensions;
  return texture(volumeTexture, textureCoordinate).r * scalarScale + scalarBias;
}

vec4 classify(float value)
{
  float u = (clamp(value, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  return texture(transferTable, vec2(u, 0.5));
}

float opacity(float value)
{
  return classify(value).a;
}

// Central differences one texel apart at a texture coordinate, in normalized scalar units.
vec3 centralDifferences(vec3 center)
{
  vec3 texel = 1.0 / volumeDimensions;
  return 0.5 * scalarScale *
    vec3(texture(volumeTexture, center + vec3(texel.x, 0.0, 0.0)).r -
        texture(volumeTexture, center - vec3(texel.x, 0.0, 0.0)).r,
      texture(volumeTexture, center + vec3(0.0, texel.y, 0.0)).r -
        texture(volumeTexture, center - vec3(0.0, texel.y, 0.0)).r,
      texture(volumeTexture, center + vec3(0.0, 0.0, texel.z)).r -
        texture(volumeTexture, center - vec3(0.0, 0.0, texel.z)).r);
}

// The eye point of the opaque geometry on this pixel; false where there is none.
bool sceneEyePoint(out vec3 point)
{
  float depth = texelFetch(sceneDepth, ivec2(ACCELVOLUME_PIXEL), 0).r;
  vec4 ndc = vec4(ACCELVOLUME_PIXEL / viewportSize * 2.0 - 1.0, depth * 2.0 - 1.0, 1.0);
  vec4 eye = inverseProjection * ndc;
  point = eye.xyz / eye.w;
  return depth < 1.0;
}

// Distance along the pixel ray (world units) of the opaque geometry, or a huge value.
float sceneDistance(vec3 rayOrigin, vec3 rayDirection)
{
  vec3 eye;
  return sceneEyePoint(eye) ? dot(eye - rayOrigin, rayDirection) : 1.0e30;
}

// `interval` of the index-space line origin + t * direction narrowed to every clip half-space.
// A line parallel to a plane is kept where `keepParallel` (the caller's geometry was clipped to
// the plane already), else emptied when it lies outside.
vec2 clipInterval(vec3 origin, vec3 direction, vec2 interval, bool keepParallel)
{
  for (int i = 0; i < clipPlaneCount; ++i)
  {
    float along = dot(clipPlanes[i].xyz, direction);
    float at = dot(clipPlanes[i].xyz, origin) + clipPlanes[i].w;
    if (abs(along) < 1.0e-20)
    {
      if (!keepParallel && at < 0.0)
      {
        return vec2(1.0, -1.0);
      }
      continue;
    }
    float t = -at / along;
    if (along > 0.0)
    {
      interval.x = max(interval.x, t);
    }
    else
    {
      interval.y = min(interval.y, t);
    }
  }
  return interval;
}

// Parameter interval of the index-space line origin + t * direction inside the region box
// (empty, x > y, when it misses).
vec2 boxInterval(vec3 origin, vec3 direction)
{
  vec3 safeDirection = mix(direction, vec3(1.0e-20), equal(direction, vec3(0.0)));
  vec3 t0 = (regionLower - origin) / safeDirection;
  vec3 t1 = (regionUpper - origin) / safeDirection;
  vec3 tNear = min(t0, t1);
  vec3 tFar = max(t0, t1);
  return vec2(max(max(tNear.x, tNear.y), tNear.z), min(min(tFar.x, tFar.y), tFar.z));
}

// Ray parameter interval inside the region box and all clip half-spaces (proxy fragments: they
// lie on polygons clipped to the planes).
vec2 regionInterval(vec3 rayOrigin, vec3 rayDirection)
{
  vec3 origin = (eyeToIndex * vec4(rayOrigin, 1.0)).xyz;
  vec3 direction = mat3(eyeToIndex) * rayDirection;
  return clipInterval(origin, direction, boxInterval(origin, direction), true);
}

#if ACCELVOLUME_JITTER
// Jitter noise in [0, 1) of a pixel: white noise from an integer hash of the pixel (as VTK's
// random noise texture; a low-discrepancy pattern such as interleaved gradient noise shows as a
// regular hatch).
float jitterNoise(vec2 pixel)
{
  uvec2 jitterPixel = uvec2(pixel);
  uint hash = jitterPixel.x * 1973u + jitterPixel.y * 9277u + 26699u;
  hash = (hash ^ 61u) ^ (hash >> 16u);
  hash *= 9u;
  hash = hash ^ (hash >> 4u);
  hash *= 0x27d4eb2du;
  hash = hash ^ (hash >> 15u);
  return float(hash & 0xffffffu) / 16777216.0;
}
#endif

#if ACCELVOLUME_SHADE
// The colour `rgb` lit by VTK's light model for an eye-space gradient, with the property's
// (ambient, diffuse, specular, specular power) `coefficients`.
// The prelude fixes the light count, whether any light is positional, two-sided lighting and
// VTK's single-headlight ambient rule (ACCELVOLUME_LIGHT_COUNT, _POSITIONAL_LIGHTS, _TWO_SIDED,
// _HEADLIGHT_ONLY): the loop unrolls and the unused branches go, the arithmetic is the same.
vec3 shadeWith(vec3 rgb, vec3 eyeGradient, vec3 rayDirection, vec4 coefficients)
{
  // VTK's light model: per light ambient, diffuse (N.L) and Blinn-Phong specular (N.H) colours,
  // positional lights attenuated, spot lights within their cone.
  float gradientLength = length(eyeGradient);
  vec3 ambientSum = vec3(0.0);
  vec3 diffuseSum = vec3(0.0);
  vec3 specularSum = vec3(0.0);
  vec3 normal = gradientLength > 1.0e-8 ? -eyeGradient / gradientLength : vec3(0.0);
  vec3 toViewer = -rayDirection;
  for (int i = 0; i < ACCELVOLUME_LIGHT_COUNT; ++i)
  {
    ambientSum += lightAmbient[i];
    if (gradientLength <= 1.0e-8)
    {
      continue;
    }
    vec3 toLight = -lightAxis[i];
    float attenuation = 1.0;
#if ACCELVOLUME_POSITIONAL_LIGHTS
    if (lightPositional[i] != 0)
    {
      vec3 d = lightPosition[i] - eyePosition;
      float distance = length(d);
      toLight = distance > 0.0 ? d / distance : toLight;
      vec3 a = lightAttenuation[i];
      float denominator = a.x + a.y * distance + a.z * distance * distance;
      attenuation = denominator > 0.0 ? 1.0 / denominator : 1.0;
      if (lightCosCone[i] >= -1.0)
      {
        float spot = -dot(toLight, lightAxis[i]);
        attenuation = spot >= lightCosCone[i] ? attenuation * pow(max(spot, 0.0), lightExponent[i])
                                              : 0.0;
      }
    }
#endif
    float nDotL = dot(normal, toLight);
#if ACCELVOLUME_TWO_SIDED
    nDotL = abs(nDotL);
#endif
    if (nDotL > 0.0)
    {
      diffuseSum += attenuation * nDotL * lightDiffuse[i];
    }
    vec3 halfVector = toLight + toViewer;
    float halfLength = length(halfVector);
    if (halfLength > 0.0)
    {
      float nDotH = dot(normal, halfVector) / halfLength;
#if ACCELVOLUME_TWO_SIDED
      nDotH = abs(nDotH);
#endif
      if (nDotH > 0.0)
      {
        specularSum += attenuation * pow(min(nDotH, 1.0), coefficients.w) * lightSpecular[i];
      }
    }
  }
#if ACCELVOLUME_HEADLIGHT_ONLY
  vec3 ambientFactor = vec3(1.0);
#else
  vec3 ambientFactor = ambientSum;
#endif
  vec3 shaded = rgb * (coefficients.x * ambientFactor + coefficients.y * diffuseSum) +
    coefficients.z * specularSum;
  return min(shaded, vec3(1.0));
}

vec3 shade(vec3 rgb, vec3 eyeGradient, vec3 rayDirection)
{
  return shadeWith(rgb, eyeGradient, rayDirection, lighting);
}
#endif

//ACCELVOLUME::ComponentsAndIsoSurfaces::Dec

#if ACCELVOLUME_MASK
// The mask value of the voxel nearest to an index point: 0 / 1 (binary) or the label.
float maskAt(vec3 point)
{
  return texelFetch(maskTexture, ivec3(clamp(floor(point + 0.5), vec3(0.0), maskMaximum)), 0).r;
}

// A binary mask hides the sample; a ghost mask also when a point half a voxel away along an
// axis is hidden (the points of the cells that share the sample, as VTK's GPU mapper tests).
bool maskHides(vec3 point)
{
  bool hidden = maskAt(point) <= 0.0;
#if ACCELVOLUME_MASK_NEIGHBOURS
  for (int axis = 0; axis < 3; ++axis)
  {
    vec3 step = vec3(0.0);
    step[axis] = 0.5;
    hidden = hidden || maskAt(point + step) <= 0.0 || maskAt(point - step) <= 0.0;
  }
#endif
  return hidden;
}
#endif

#if defined(ACCELVOLUME_BLEND_COMPOSITE) && ACCELVOLUME_COMPONENTS == 1
// One composite sample of single-component scalars at an index point, premultiplied and its
// opacity corrected for `step`; false when it is skipped (a transparent leaf or sample).
bool compositeSample(vec3 samplePosition, vec3 rayDirection, float step, out vec4 premultiplied)
{
  premultiplied = vec4(0.0);
#if ACCELVOLUME_SKIP_OCTREE && !defined(ACCELVOLUME_COMPUTE_SLICES)
  // A transparent leaf (every voxel its samples read maps to opacity 0) adds nothing:
  // one nearest fetch of the leaf grid replaces the volume fetch and the shading (the compute
  // slices test leaves before they sample, to leap over them).
  vec3 leaf = clamp(floor(samplePosition / leafSize), vec3(0.0), leafGridMaximum);
  if (texelFetch(emptyLeaves, ivec3(leaf), 0).r > 0.5)
  {
    return false;
  }
#endif
  ACCELVOLUME_PRECISE vec3 center = ACCELVOLUME_TEXEL_CENTRE(samplePosition) / volumeDimensions;
#if ACCELVOLUME_PACKED_SAMPLE
  vec4 gradientSample = texture(gradientTexture, center);
  float sampleScalar = gradientSample.a;
#else
  float sampleScalar = normalizedScalarAt(samplePosition);
#endif
#if ACCELVOLUME_TF2D
  float scalar2D = sampleScalar;
  vec4 classified = vec4(0.0);
#else
  vec4 classified = classify(sampleScalar);
#endif
#if ACCELVOLUME_MASK == 2
  // Label map: a labelled voxel takes its label's colour and opacity, blended with the
  // property's by maskBlendFactor (vtkGPUVolumeRayCastMapper's rule).
  float label = floor(maskAt(indexPosition) * 255.0 + 0.5);
  if (label > 0.0 && maskBlendFactor > 0.0)
  {
    float u = (clamp(normalizedScalarAt(samplePosition), 0.0, 1.0) * (tableSize - 1.0) + 0.5) /
      tableSize;
    vec4 labelled = texture(labelTable, vec2(u, (label + 0.5) / 256.0));
    classified = mix(classified, labelled, maskBlendFactor);
  }
#endif
#if ACCELVOLUME_SKIP_TRANSPARENT && !ACCELVOLUME_TF2D
  // Per-fragment skipping: a transparent sample needs no gradient and no lighting.
  if (classified.a <= 0.0)
  {
    return false;
  }
#endif
#if ACCELVOLUME_SHADE || ACCELVOLUME_GRADIENT_OPACITY || ACCELVOLUME_TF2D
#if ACCELVOLUME_GRADIENT_TEXTURE && !ACCELVOLUME_PACKED_SAMPLE
  vec4 gradientSample = texture(gradientTexture, center);
#endif
#if ACCELVOLUME_GRADIENT_TEXTURE
  vec3 indexGradient = (gradientSample.rgb * 2.0 - vec3(1.0)) * gradientTextureScale;
#else
  vec3 indexGradient = centralDifferences(center);
#endif
  vec3 eyeGradient = normalMatrix * indexGradient;
#endif
#if ACCELVOLUME_TF2D
  // Value x gradient-magnitude classification (the paper's 2D transfer function).
  float magnitude2D = length(indexGradient * gradientAxisScale) * scalarRangeWidth / gradient2DMaximum;
  classified =
    texture(transferTable2D, vec2(clamp(scalar2D, 0.0, 1.0), clamp(magnitude2D, 0.0, 1.0)));
#if ACCELVOLUME_SKIP_TRANSPARENT
  if (classified.a <= 0.0)
  {
    return false;
  }
#endif
#endif
#if ACCELVOLUME_GRADIENT_OPACITY
  // Gradient magnitude as VTK's GPU mapper computes it (data units per mean voxel step).
  float magnitude = length(indexGradient * gradientAxisScale) * scalarRangeWidth;
  float g = (clamp(magnitude / gradientTableMaximum, 0.0, 1.0) * 1023.0 + 0.5) / 1024.0;
  classified.a *= texture(gradientOpacityTable, vec2(g, 0.5)).r;
#endif
#if ACCELVOLUME_SHADE
  classified.rgb = shade(classified.rgb, eyeGradient, rayDirection);
#endif
  float alpha = 1.0 - pow(max(1.0 - classified.a, 0.0), step / opacityUnitDistance);
  premultiplied = vec4(classified.rgb * alpha, alpha);
  return true;
}
#endif
