//VTK::System::Dec
// Resolve pass: turns the accumulated value into a premultiplied colour the way VTK's GPU
// ray caster does for the same blend mode, blended over the scene. With an image sample
// distance above 1 (ACCELVOLUME_REDUCED) the target is smaller than the viewport: each window
// pixel blends the colours of its four nearest target texels bilinearly.
//VTK::Output::Dec

uniform sampler2D accumulation;
#if ACCELVOLUME_COMPONENTS > 2
uniform sampler2D accumulationSecond; // components 2-3 of an independent average
#endif
uniform sampler2D transferTable;
uniform float tableSize;
uniform vec2 viewportOrigin;
uniform vec2 viewportSize; // window pixels
uniform vec2 targetSize;   // accumulation texels
uniform float colourScale; // FinalColorWindow / Level: rgb * scale + bias * alpha
uniform float colourBias;
// vtkHardwareSelector: 1 = write selectionColour where the volume is seen (actor / process
// passes, as VTK's GPU mapper), 2 = write nothing (attribute-id passes); 0 = render.
// Depth peeling of volumes (the pass's first volumetric stage): its second target, the front
// accumulation, gets nothing from the volume.
uniform int clearSecondTarget;
uniform int selectionMode;
uniform vec3 selectionColour;

vec4 lookup(float value)
{
  float u = (clamp(value, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  return texture(transferTable, vec2(u, 0.5));
}

#if ACCELVOLUME_COMPONENTS > 1
// Multi-component extremes, coloured as vtkGPUVolumeRayCastMapper does (no shading, opacity
// as the table gives it): independent components add their weighted colour x opacity and
// opacity; dependent ones colour the kept sample (2: component 0 through the colour table,
// opacity of component 1; 4: RGB as is, opacity of component 3).
uniform sampler2D componentTables; // rows c = 0..3: rgba over component c's range
uniform vec4 componentWeights;

vec4 componentLookup(int c, float value)
{
  float u = (clamp(value, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  return texture(componentTables, vec2(u, (float(c) + 0.5) / 4.0));
}

vec4 multiComponentExtreme(vec4 values)
{
#if ACCELVOLUME_INDEPENDENT
  vec4 colour = vec4(0.0);
  for (int c = 0; c < ACCELVOLUME_COMPONENTS; ++c)
  {
    vec4 classified = componentLookup(c, values[c]);
    colour += componentWeights[c] * vec4(classified.rgb * classified.a, classified.a);
  }
  return colour;
#elif ACCELVOLUME_COMPONENTS == 2
  float alpha = componentLookup(0, values.y).a;
  return vec4(componentLookup(0, values.x).rgb * alpha, alpha);
#else
  float alpha = componentLookup(0, values.a).a;
  return vec4(clamp(values.rgb, 0.0, 1.0) * alpha, alpha);
#endif
}
#endif

// The premultiplied colour of one target texel; `covered` is false where no sample landed.
vec4 resolveTexel(ivec2 texel, out bool covered)
{
  vec4 accumulated = texelFetch(accumulation, texel, 0);
  vec2 sums = accumulated.rg;
#if ACCELVOLUME_COMPONENTS > 1 && defined(ACCELVOLUME_BLEND_MAXIMUM)
  // Cleared to -1 in every channel.
  covered = accumulated.x >= -0.5;
  return covered ? multiComponentExtreme(accumulated) : vec4(0.0);
#elif ACCELVOLUME_COMPONENTS > 1 && defined(ACCELVOLUME_BLEND_MINIMUM)
  // Cleared to 2 in every channel.
  covered = accumulated.x <= 1.5;
  return covered ? multiComponentExtreme(accumulated) : vec4(0.0);
#elif ACCELVOLUME_COMPONENTS > 1 && ACCELVOLUME_INDEPENDENT && defined(ACCELVOLUME_BLEND_AVERAGE)
  // Independent components' averages, weighted and added as VTK's GPU mapper does.
#if ACCELVOLUME_COMPONENTS > 2
  vec4 second = texelFetch(accumulationSecond, texel, 0);
#else
  vec4 second = vec4(0.0);
#endif
  vec4 componentSums = vec4(accumulated.x, accumulated.z, second.x, second.z);
  vec4 componentCounts = vec4(accumulated.y, accumulated.w, second.y, second.w);
  float average = 0.0;
  covered = false;
  for (int c = 0; c < ACCELVOLUME_COMPONENTS; ++c)
  {
    if (componentCounts[c] > 0.0)
    {
      average += componentWeights[c] * componentSums[c] / componentCounts[c];
      covered = true;
    }
  }
  return covered ? vec4(vec3(clamp(average, 0.0, 1.0)), 1.0) : vec4(0.0);
#elif defined(ACCELVOLUME_BLEND_MAXIMUM)
  // Single-component MIP/MinIP targets have one channel, cleared to -1 (maximum) or 2 (minimum).
  covered = sums.x >= -0.5;
  vec4 colour = lookup(sums.x);
  return covered ? vec4(colour.rgb * colour.a, colour.a) : vec4(0.0);
#elif defined(ACCELVOLUME_BLEND_MINIMUM)
  covered = sums.x <= 1.5;
  vec4 colour = lookup(sums.x);
  return covered ? vec4(colour.rgb * colour.a, colour.a) : vec4(0.0);
#elif defined(ACCELVOLUME_BLEND_COMPOSITE)
  // Already premultiplied front-to-back colour and alpha.
  covered = accumulated.a > 0.0;
  return covered ? accumulated : vec4(0.0);
#elif defined(ACCELVOLUME_BLEND_ADDITIVE)
  covered = sums.y > 0.0;
  return covered ? vec4(vec3(clamp(sums.x, 0.0, 1.0)), 1.0) : vec4(0.0);
#else
  covered = sums.y > 0.0;
  return covered ? vec4(vec3(clamp(sums.x / sums.y, 0.0, 1.0)), 1.0) : vec4(0.0);
#endif
}

void emit(vec4 premultiplied)
{
  if (selectionMode != 0)
  {
    if (selectionMode != 1 || premultiplied.a <= 3.0 / 255.0)
    {
      discard;
    }
    gl_FragData[0] = vec4(selectionColour, 1.0);
    return;
  }
  premultiplied.rgb = premultiplied.rgb * colourScale + colourBias * premultiplied.a;
  gl_FragData[0] = premultiplied;
}

void main()
{
  if (clearSecondTarget != 0)
  {
    gl_FragData[1] = vec4(0.0);
  }
  vec2 pixel = gl_FragCoord.xy - viewportOrigin;
  bool covered;
#if ACCELVOLUME_REDUCED
  // Target texel centres sit at (i + 0.5) * viewportSize / targetSize window pixels.
  vec2 at = pixel * targetSize / viewportSize - 0.5;
  ivec2 base = ivec2(floor(at));
  vec2 f = at - vec2(base);
  ivec2 last = ivec2(targetSize) - 1;
  vec4 colour = vec4(0.0);
  bool any = false;
  for (int j = 0; j < 2; ++j)
  {
    for (int i = 0; i < 2; ++i)
    {
      ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), last);
      float weight = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
      bool texelCovered;
      colour += weight * resolveTexel(texel, texelCovered);
      any = any || (texelCovered && weight > 0.0);
    }
  }
  covered = any;
#else
  vec4 colour = resolveTexel(ivec2(pixel), covered);
#endif
  if (!covered)
  {
    discard;
  }
  emit(colour);
}
