//VTK::System::Dec
// Image sample distance above 1: the scene depth at the smaller accumulation target's size (the
// window pixel under each target texel's centre), written as the target's depth so the slices'
// early depth test and the integration limits see the opaque geometry there.
//VTK::Output::Dec

uniform sampler2D fullDepth; // the viewport's depth, window pixels
uniform vec2 scale;          // window pixels per target texel
uniform vec2 fullSize;

void main()
{
  ivec2 pixel = ivec2(min(floor(gl_FragCoord.xy * scale), fullSize - 1.0));
  gl_FragDepth = texelFetch(fullDepth, pixel, 0).r;
  gl_FragData[0] = vec4(0.0);
}
