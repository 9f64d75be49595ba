//VTK::System::Dec
// Resolve pass: turns the accumulated value into a premultiplied colour the way VTK's GPU
// ray caster does for the same blend mode, blended over the scene.
//VTK::Output::Dec

uniform sampler2D accumulation;
uniform sampler2D transferTable;
uniform float tableSize;
uniform vec2 viewportOrigin;
uniform float colourScale; // FinalColorWindow / Level: rgb * scale + bias * alpha
uniform float colourBias;
// vtkHardwareSelector: 1 = write selectionColour where the volume is seen (actor / process
// passes, as VTK's GPU mapper), 2 = write nothing (attribute-id passes); 0 = render.
uniform int selectionMode;
uniform vec3 selectionColour;

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

vec4 lookup(float value)
{
  float u = (clamp(value, 0.0, 1.0) * (tableSize - 1.0) + 0.5) / tableSize;
  return texture(transferTable, vec2(u, 0.5));
}

void main()
{
  vec4 accumulated = texelFetch(accumulation, ivec2(gl_FragCoord.xy - viewportOrigin), 0);
  vec2 sums = accumulated.rg;
  // MIP/MinIP targets have one channel, cleared to -1 (maximum) or 2 (minimum).
#if defined(ACCELVOLUME_BLEND_MAXIMUM)
  if (sums.x < -0.5)
  {
    discard;
  }
  vec4 colour = lookup(sums.x);
  emit(vec4(colour.rgb * colour.a, colour.a));
#elif defined(ACCELVOLUME_BLEND_MINIMUM)
  if (sums.x > 1.5)
  {
    discard;
  }
  vec4 colour = lookup(sums.x);
  emit(vec4(colour.rgb * colour.a, colour.a));
#elif defined(ACCELVOLUME_BLEND_COMPOSITE)
  // Already premultiplied front-to-back colour and alpha.
  if (accumulated.a <= 0.0)
  {
    discard;
  }
  emit(accumulated);
#elif defined(ACCELVOLUME_BLEND_ADDITIVE)
  if (sums.y <= 0.0)
  {
    discard;
  }
  emit(vec4(vec3(clamp(sums.x, 0.0, 1.0)), 1.0));
#else
  if (sums.y <= 0.0)
  {
    discard;
  }
  emit(vec4(vec3(clamp(sums.x / sums.y, 0.0, 1.0)), 1.0));
#endif
}
