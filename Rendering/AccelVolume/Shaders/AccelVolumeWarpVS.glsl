//VTK::System::Dec
// Shear-warp's intermediate image drawn warped: the parallelogram it covers in the viewport,
// corners in normalized device coordinates, drawn as a triangle strip of four vertices.
uniform vec2 corners[4];
void main()
{
  gl_Position = vec4(corners[gl_VertexID], 0.0, 1.0);
}
