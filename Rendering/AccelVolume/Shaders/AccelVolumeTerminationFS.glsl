//VTK::System::Dec
// Early ray termination mark pass: pixels whose accumulated front-to-back alpha passed the
// threshold get a depth (terminatedDepth) that makes the early depth test reject every later
// slice fragment there.
//VTK::Output::Dec

uniform sampler2D accumulation;
uniform float threshold;
uniform float terminatedDepth; // fails every later slice's depth test

void main()
{
  if (texelFetch(accumulation, ivec2(gl_FragCoord.xy), 0).a < threshold)
  {
    discard;
  }
  gl_FragDepth = terminatedDepth;
  gl_FragData[0] = vec4(0.0);
}
