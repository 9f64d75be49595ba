//VTK::System::Dec
// Shear-warp's intermediate image warped while it is drawn (vtkAccelVolumeImageDisplay::
// DrawWarped), for plain frames; selection and depth-peeling frames use AccelVolumeImageFS.
// The texture coordinate comes interpolated from the parallelogram's corners; the texture unit
// interpolates bilinearly, zero outside (a zero border before the first pixel, one zero column
// and row after the last), as the CPU warp. Kept to one texture lookup and no per-fragment
// matrix: a software rasterizer (llvmpipe) runs this per pixel on the CPU.
//VTK::Output::Dec

uniform sampler2D image;
uniform float colourScale; // FinalColorWindow / Level: rgb * scale + bias * alpha
uniform float colourBias;
in vec2 imageCoordinate;

void main()
{
  vec4 colour = texture(image, imageCoordinate);
  gl_FragData[0] = vec4(colour.rgb * colourScale + colourBias * colour.a, colour.a);
}
