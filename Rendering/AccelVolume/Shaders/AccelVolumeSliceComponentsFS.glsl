// The slice shader's multi-component sampling and its iso-surface crossings (the depth pass's
// contour too), inserted by vtkAccelVolumeSliceShaderVariant at the slice shader's
// //ACCELVOLUME::ComponentsAndIsoSurfaces::Dec line: it uses that shader's uniforms and helpers.

#if ACCELVOLUME_COMPONENTS > 1
// Multi-component scalars, each normalised to its own data range on upload (as VTK's GPU
// mapper): independent components classified by their own tables and combined with the
// component weights as vtkGPUVolumeRayCastMapper does; dependent ones as luminance-alpha
// (2: colour from component 0, opacity from component 1) or RGBA (4: colour as is, opacity
// from component 3). Shading uses each component's gradient (dependent: component 0's, as VTK).
uniform sampler2D componentTables;   // rows c = 0..3: rgba over component c's range
uniform vec4 componentWeights;
uniform vec4 componentUnitDistances;
uniform vec4 componentLighting[4]; // each independent component's shading coefficients

vec4 componentLookup(int c, float value)
{
  float u = (clamp(value, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  return texture(componentTables, vec2(u, (float(c) + 0.5) / 4.0));
}

#if ACCELVOLUME_GRADIENT_OPACITY
// Row c of the gradient-opacity table at a gradient of normalised values per index step: the
// row spans [0, a quarter of component c's range] per mean voxel step (VTK's units).
float componentGradientOpacity(int c, vec3 indexGradient)
{
  float magnitude = clamp(4.0 * length(indexGradient * gradientAxisScale), 0.0, 1.0);
  float rows = float(ACCELVOLUME_INDEPENDENT != 0 ? ACCELVOLUME_COMPONENTS : 1);
  return texture(gradientOpacityTable,
    vec2((magnitude * 1023.0 + 0.5) / 1024.0, (float(c) + 0.5) / rows)).r;
}
#endif

// planeSample (SLICE_BLEND): the tables' opacities as they are, no correction and no gradient
// opacity (as one-component slices).
vec4 multiComponentSample(vec3 position, vec3 rayDirection, float step, bool planeSample)
{
  ACCELVOLUME_PRECISE vec3 center = ACCELVOLUME_TEXEL_CENTRE(position) / volumeDimensions;
  vec4 values = texture(volumeTexture, center);
  // A transparent sample (every component's opacity 0) needs no gradient and no lighting.
#if ACCELVOLUME_INDEPENDENT
  bool visible = false;
  for (int c = 0; c < ACCELVOLUME_COMPONENTS; ++c)
  {
    visible = visible || componentLookup(c, values[c]).a > 0.0;
  }
#elif ACCELVOLUME_COMPONENTS == 2
  vec3 rgb = componentLookup(0, values.x).rgb;
  float opacityValue = componentLookup(0, values.y).a;
  bool visible = opacityValue > 0.0;
#else
  vec3 rgb = values.rgb;
  float opacityValue = componentLookup(0, values.a).a;
  bool visible = opacityValue > 0.0;
#endif
  if (!visible)
  {
    return vec4(0.0);
  }
#if ACCELVOLUME_SHADE || ACCELVOLUME_GRADIENT_OPACITY
  vec3 texel = 1.0 / volumeDimensions;
  vec4 dx = 0.5 * (texture(volumeTexture, center + vec3(texel.x, 0.0, 0.0)) -
                    texture(volumeTexture, center - vec3(texel.x, 0.0, 0.0)));
  vec4 dy = 0.5 * (texture(volumeTexture, center + vec3(0.0, texel.y, 0.0)) -
                    texture(volumeTexture, center - vec3(0.0, texel.y, 0.0)));
  vec4 dz = 0.5 * (texture(volumeTexture, center + vec3(0.0, 0.0, texel.z)) -
                    texture(volumeTexture, center - vec3(0.0, 0.0, texel.z)));
#endif
#if ACCELVOLUME_INDEPENDENT
  vec3 rgbSum = vec3(0.0);
  float totalAlpha = 0.0;
  float alphaSquares = 0.0;
  for (int c = 0; c < ACCELVOLUME_COMPONENTS; ++c)
  {
    vec4 colour = componentLookup(c, values[c]);
#if ACCELVOLUME_GRADIENT_OPACITY
    // VTK's GPU mapper: every component's function at this component's gradient, weighted.
    for (int i = 0; i < ACCELVOLUME_COMPONENTS && !planeSample; ++i)
    {
      colour.a *= componentGradientOpacity(i, vec3(dx[c], dy[c], dz[c])) * componentWeights[i];
    }
#endif
    float alpha = planeSample
      ? colour.a
      : 1.0 - pow(max(1.0 - colour.a, 0.0), step / componentUnitDistances[c]);
#if ACCELVOLUME_SHADE
    colour.rgb = shadeWith(
      colour.rgb, normalMatrix * vec3(dx[c], dy[c], dz[c]), rayDirection, componentLighting[c]);
#endif
    totalAlpha += alpha * componentWeights[c];
    if (componentWeights[c] > 0.0)
    {
      rgbSum += colour.rgb * alpha * componentWeights[c];
      alphaSquares += alpha * alpha;
    }
  }
  return totalAlpha > 0.0 ? vec4(rgbSum, alphaSquares / totalAlpha) : vec4(0.0);
#else
#if ACCELVOLUME_GRADIENT_OPACITY
  if (!planeSample)
  {
    opacityValue *= componentGradientOpacity(0, vec3(dx.x, dy.x, dz.x)); // component 0's, as VTK
  }
#endif
  float alpha = planeSample
    ? opacityValue
    : 1.0 - pow(max(1.0 - opacityValue, 0.0), step / componentUnitDistances.x);
#if ACCELVOLUME_SHADE
  rgb = shade(rgb, normalMatrix * vec3(dx.x, dy.x, dz.x), rayDirection);
#endif
  return vec4(rgb * alpha, alpha);
#endif
}
#endif

#if ACCELVOLUME_ISOSURFACE || ACCELVOLUME_DEPTH_PASS == 1
// ISOSURFACE_BLEND as vtkGPUVolumeRayCastMapper: where the value crosses one of the
// property's iso-values between the previous sample along the ray and this one, that value's
// colour and (uncorrected) opacity, lit at this sample, composited front to back.
uniform int isoSurfaceCount;
uniform vec3 volumeIndexMaximum;    // the whole volume's largest voxel index per axis
uniform float isoSurfaceValues[16]; // normalised, ascending

#if ACCELVOLUME_COMPONENTS > 1
// Independent components: the iso-values apply to the component of the largest weight (VTK's
// choice), normalised to that component's range, coloured and lit by its own functions.
// Dependent ones: component 0's values, looked up as VTK's GPU mapper does (colour and opacity
// at the value's place in the tables; RGBA: grey at the value).
uniform int isoComponent;

float isoValueAt(vec3 position)
{
  return texture(volumeTexture, ACCELVOLUME_TEXEL_CENTRE(position) / volumeDimensions)[isoComponent];
}

vec4 isoClassify(float value)
{
#if ACCELVOLUME_INDEPENDENT || ACCELVOLUME_COMPONENTS == 2
  return componentLookup(isoComponent, value);
#else
  return vec4(vec3(clamp(value, 0.0, 1.0)), componentLookup(0, value).a);
#endif
}

#if ACCELVOLUME_SHADE
vec3 isoShade(vec3 rgb, vec3 center, vec3 rayDirection)
{
  vec3 texel = 1.0 / volumeDimensions;
  vec3 gradient = 0.5 *
    vec3(texture(volumeTexture, center + vec3(texel.x, 0.0, 0.0))[isoComponent] -
        texture(volumeTexture, center - vec3(texel.x, 0.0, 0.0))[isoComponent],
      texture(volumeTexture, center + vec3(0.0, texel.y, 0.0))[isoComponent] -
        texture(volumeTexture, center - vec3(0.0, texel.y, 0.0))[isoComponent],
      texture(volumeTexture, center + vec3(0.0, 0.0, texel.z))[isoComponent] -
        texture(volumeTexture, center - vec3(0.0, 0.0, texel.z))[isoComponent]);
  return shadeWith(rgb, normalMatrix * gradient, rayDirection, componentLighting[isoComponent]);
}
#endif
#else
float isoValueAt(vec3 position)
{
  return normalizedScalarAt(position);
}

vec4 isoClassify(float value)
{
  return classify(value);
}

#if ACCELVOLUME_SHADE
vec3 isoShade(vec3 rgb, vec3 center, vec3 rayDirection)
{
  return shade(rgb, normalMatrix * centralDifferences(center), rayDirection);
}
#endif
#endif

vec4 isoSurfaceSample(vec3 position, vec3 previous, vec3 rayDirection)
{
  float value = isoValueAt(position);
  float before = isoValueAt(previous);
  float low = min(value, before);
  float high = max(value, before);
  vec4 accumulated = vec4(0.0);
#if ACCELVOLUME_SHADE
  ACCELVOLUME_PRECISE vec3 center = ACCELVOLUME_TEXEL_CENTRE(position) / volumeDimensions;
#endif
  // Crossings in ray order: ascending values when the ray climbs, descending when it falls.
  bool rising = value >= before;
  for (int k = 0; k < isoSurfaceCount; ++k)
  {
    int i = rising ? k : isoSurfaceCount - 1 - k;
    float iso = isoSurfaceValues[i];
    if (iso > low && iso <= high)
    {
      vec4 colour = isoClassify(iso);
#if ACCELVOLUME_SHADE
      colour.rgb = isoShade(colour.rgb, center, rayDirection);
#endif
      accumulated += (1.0 - accumulated.a) * vec4(colour.rgb * colour.a, colour.a);
    }
  }
  return accumulated;
}

// The first sample of a ray has nothing to cross from (as VTK's): the previous sample must lie
// in the volume and inside the clip planes (cropping is not tested here).
bool previousSampleInside(vec3 previous)
{
  bool inside = all(greaterThanEqual(previous, vec3(0.0))) &&
    all(lessThanEqual(previous, volumeIndexMaximum));
  for (int i = 0; i < clipPlaneCount; ++i)
  {
    inside = inside && dot(clipPlanes[i].xyz, previous) + clipPlanes[i].w >= 0.0;
  }
  return inside;
}

// The fraction of the way from `previous` to `position` where the first contour value is
// crossed (linear between the two samples), or 2 when none is.
float firstCrossing(vec3 position, vec3 previous)
{
  float value = isoValueAt(position);
  float before = isoValueAt(previous);
  float first = 2.0;
  for (int i = 0; i < isoSurfaceCount; ++i)
  {
    float iso = isoSurfaceValues[i];
    if (iso > min(value, before) && iso <= max(value, before))
    {
      first = min(first, (iso - before) / (value - before));
    }
  }
  return first;
}
#endif


