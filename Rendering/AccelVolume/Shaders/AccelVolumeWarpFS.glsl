//VTK::System::Dec
// Shear-warp's intermediate image warped while it is drawn (vtkAccelVolumeImageDisplay::
// DrawWarped), for plain frames; selection and depth-peeling frames use AccelVolumeImageFS.
// The fragment's image position maps through the inverse warp to intermediate coordinates
// (pixel i at i); the texture unit interpolates bilinearly, zero outside (a zero border before
// the first pixel, one zero column and row after the last), as the CPU warp. The parallelogram
// drawn (AccelVolumeWarpVS) covers exactly (-1, limit): the clamp only absorbs rounding.
//VTK::Output::Dec

uniform sampler2D image;
uniform vec2 viewportOrigin;
uniform vec2 viewportToImage; // image pixels per viewport pixel
uniform vec3 warpU;
uniform vec3 warpV;
uniform vec2 warpLimit;
uniform vec2 textureExtent;
uniform float colourScale; // FinalColorWindow / Level: rgb * scale + bias * alpha
uniform float colourBias;

void main()
{
  vec3 position = vec3((gl_FragCoord.xy - viewportOrigin) * viewportToImage, 1.0);
  vec2 uv = clamp(vec2(dot(warpU, position), dot(warpV, position)), vec2(-1.0), warpLimit);
  vec4 colour = texture(image, (uv + 0.5) / textureExtent);
  gl_FragData[0] = vec4(colour.rgb * colourScale + colourBias * colour.a, colour.a);
}
