//VTK::System::Dec
// Shear-warp's intermediate image drawn warped: the bands of its parallelogram that hold
// visible pixels (vtkAccelVolumeImageDisplay::SetFootprint), vertices in normalized device
// coordinates with their texture coordinates. The warp is affine, so the corners' texture
// coordinates interpolate to every fragment's inverse warp exactly (no per-fragment matrix).
in vec2 vertexPosition;
in vec2 vertexCoordinate;
out vec2 imageCoordinate;
void main()
{
  imageCoordinate = vertexCoordinate;
  gl_Position = vec4(vertexPosition, 0.0, 1.0);
}
