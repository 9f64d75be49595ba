//VTK::System::Dec
// Early ray termination mark pass: pixels whose accumulated front-to-back alpha passed the
// threshold get depth 0, so the early depth test rejects every later slice fragment there.
//VTK::Output::Dec

uniform sampler2D accumulation;
uniform float threshold;

void main()
{
  if (texelFetch(accumulation, ivec2(gl_FragCoord.xy), 0).a < threshold)
  {
    discard;
  }
  gl_FragDepth = 0.0;
  gl_FragData[0] = vec4(0.0);
}
