//VTK::System::Dec
// Proxy slice / boundary face vertex stage: polygons arrive in volume index coordinates.
in vec3 vertexIndex;

uniform mat4 indexToClip;
uniform mat4 indexToEye;

out vec3 indexPosition;
out vec3 eyePosition;

void main()
{
  indexPosition = vertexIndex;
  eyePosition = (indexToEye * vec4(vertexIndex, 1.0)).xyz;
  gl_Position = indexToClip * vec4(vertexIndex, 1.0);
}
